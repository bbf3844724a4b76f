package uk.ac.cam.cl.gfxintro.crsid.tick1star;

import java.awt.image.BufferedImage;
import java.io.File;
import java.io.IOException;
import javax.imageio.ImageIO;

/*
 * A Tick 1* hand-in of option 1 as the handout asks for it: this file alone (whitted's own,
 * written from docs/tick1star.md's method, never from the course's code or a student's). The
 * constructor is the skeleton's; getNormalAt is written as a student writes it: the poles on y,
 * u = 0.5 + atan2(z, x) / 2pi, v = acos(y) / pi, unit tangents, the gradient towards the texel
 * to the right and below (clamped at the map's edges), n' = n + B_u (n x P_v) + B_v (n x P_u).
 */
public class BumpySphere extends Sphere {

    private final float BUMP_FACTOR = 5;
    private float[][] bumpMap;
    private int bumpMapHeight;
    private int bumpMapWidth;

    public BumpySphere(Vector3 position, double radius, ColorRGB colour, String bumpMapImg) {
        super(position, radius, colour);
        try {
            BufferedImage inputImg = ImageIO.read(new File(bumpMapImg));
            bumpMapHeight = inputImg.getHeight();
            bumpMapWidth = inputImg.getWidth();
            bumpMap = new float[bumpMapHeight][bumpMapWidth];
            for (int row = 0; row < bumpMapHeight; row++) {
                for (int col = 0; col < bumpMapWidth; col++) {
                    float height = (float) (inputImg.getRGB(col, row) & 0xFF) / 0xFF;
                    bumpMap[row][col] = BUMP_FACTOR * height;
                }
            }
        } catch (IOException e) {
            System.err.println("Error creating bump map");
            e.printStackTrace();
        }
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        Vector3 normal = super.getNormalAt(position);

        // spherical coordinates, poles on the y axis
        double theta = Math.acos(normal.y);
        double phi = Math.atan2(normal.z, normal.x);
        double u = 0.5 + phi / (2 * Math.PI);
        double v = theta / Math.PI;

        // tangents: d/dphi and d/dtheta of (sin t cos p, cos t, sin t sin p), made unit length
        Vector3 Pu = new Vector3(-Math.sin(phi), 0, Math.cos(phi));
        Vector3 Pv = new Vector3(Math.cos(theta) * Math.cos(phi), -Math.sin(theta), Math.cos(theta) * Math.sin(phi));

        int x = Math.min((int) (u * bumpMapWidth), bumpMapWidth - 1);
        int y = Math.min((int) (v * bumpMapHeight), bumpMapHeight - 1);
        int right = Math.min(x + 1, bumpMapWidth - 1);
        int below = Math.min(y + 1, bumpMapHeight - 1);
        double Bu = bumpMap[y][right] - bumpMap[y][x];
        double Bv = bumpMap[below][x] - bumpMap[y][x];

        return normal.add(normal.cross(Pv).scale(Bu)).add(normal.cross(Pu).scale(Bv)).normalised();
    }
}
