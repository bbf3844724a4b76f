package uk.ac.cam.cl.gfxintro.crsid.tick1star;

import java.awt.image.BufferedImage;
import java.io.File;
import java.io.IOException;
import javax.imageio.ImageIO;

/**
 * A student's Tick 1* BumpySphere.java (option 1, bump mapping): whitted's own, written from
 * docs/courses.md ("Tick 1*"), never from the course's code. The constructor is the skeleton's
 * (skeleton/tick1/BumpySphere.java: height = 5 * blue / 255); getNormalAt is the student's.
 *
 * -Dbump=PARAMETRISATION[,MISTAKE...] chooses how it is written. The parametrisations, each
 * correct (the map lies on the sphere one-to-one, moved or mirrored): poles-y (the poles on the
 * y axis, u from atan2(z, x), v from the polar angle off +y), poles-y-xz (u from atan2(x, z)),
 * poles-z (the poles on z, u from atan2(y, x)), poles-y-mirrored (poles-y with u running the
 * other way). The mistakes: inverted (the relief's sign flipped), swapped-gradients (B_u with
 * P_u and B_v with P_v), unnormalised-tangents, unnormalised-result, left-above (the gradient
 * of the texel to the left and above, the sign kept), colour-height (the packed colour, not the
 * blue byte, taken as height), no-centre (the normal of a sphere at the origin: P not made
 * relative to the centre).
 */
public class BumpySphere extends Sphere {
    private static final String[] BUMP = System.getProperty("bump", "poles-y").split(",");
    private final float BUMP_FACTOR = 5;
    private float[][] bumpMap;
    private int bumpMapHeight;
    private int bumpMapWidth;

    static boolean mistake(String id) {
        for (int i = 1; i < BUMP.length; i++) if (BUMP[i].equals(id)) return true;
        return false;
    }

    public BumpySphere(Vector3 position, double radius, ColorRGB colour, String bumpMapImg) {
        super(position, radius, colour);
        try {
            BufferedImage inputImg = ImageIO.read(new File(bumpMapImg));
            bumpMapHeight = inputImg.getHeight();
            bumpMapWidth = inputImg.getWidth();
            bumpMap = new float[bumpMapHeight][bumpMapWidth];
            for (int row = 0; row < bumpMapHeight; row++) {
                for (int col = 0; col < bumpMapWidth; col++) {
                    int rgb = inputImg.getRGB(col, row);
                    float height = mistake("colour-height") ? (rgb & 0xFFFFFF) / 255f : (float) (rgb & 0xFF) / 0xFF;
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
        // The smooth sphere's normal: also the point of the unit sphere the map is laid on.
        Vector3 n = mistake("no-centre") ? position.normalised() : super.getNormalAt(position);
        double u, v;
        Vector3 Pu, Pv;
        switch (BUMP[0]) {
            case "poles-y-xz": {
                double theta = Math.acos(n.y), phi = Math.atan2(n.x, n.z);
                u = (phi + Math.PI) / (2 * Math.PI);
                v = theta / Math.PI;
                Pu = new Vector3(Math.sin(theta) * Math.cos(phi), 0, -Math.sin(theta) * Math.sin(phi)).scale(2 * Math.PI);
                Pv = new Vector3(Math.cos(theta) * Math.sin(phi), -Math.sin(theta), Math.cos(theta) * Math.cos(phi)).scale(Math.PI);
                break;
            }
            case "poles-z": {
                double theta = Math.acos(n.z), phi = Math.atan2(n.y, n.x);
                u = (phi + Math.PI) / (2 * Math.PI);
                v = theta / Math.PI;
                Pu = new Vector3(-Math.sin(theta) * Math.sin(phi), Math.sin(theta) * Math.cos(phi), 0).scale(2 * Math.PI);
                Pv = new Vector3(Math.cos(theta) * Math.cos(phi), Math.cos(theta) * Math.sin(phi), -Math.sin(theta)).scale(Math.PI);
                break;
            }
            case "poles-y":
            case "poles-y-mirrored": {
                double theta = Math.acos(n.y), phi = Math.atan2(n.z, n.x);
                boolean mirrored = BUMP[0].equals("poles-y-mirrored");
                u = (phi + Math.PI) / (2 * Math.PI);
                if (mirrored) u = 1 - u;
                v = theta / Math.PI;
                Pu = new Vector3(-Math.sin(theta) * Math.sin(phi), 0, Math.sin(theta) * Math.cos(phi)).scale(mirrored ? -2 * Math.PI : 2 * Math.PI);
                Pv = new Vector3(Math.cos(theta) * Math.cos(phi), -Math.sin(theta), Math.cos(theta) * Math.sin(phi)).scale(Math.PI);
                break;
            }
            default:
                throw new IllegalArgumentException("no parametrisation " + BUMP[0]);
        }
        if (!mistake("unnormalised-tangents")) {
            Pu = Pu.normalised();
            Pv = Pv.normalised();
        }
        // The texel under (u, v) and its neighbours (clamped at the map's edges).
        int col = Math.min((int) (u * (bumpMapWidth - 1)), bumpMapWidth - 1);
        int row = Math.min((int) (v * (bumpMapHeight - 1)), bumpMapHeight - 1);
        float here = bumpMap[row][col];
        double Bu, Bv;
        if (mistake("left-above")) {
            Bu = bumpMap[row][Math.max(col - 1, 0)] - here;
            Bv = bumpMap[Math.max(row - 1, 0)][col] - here;
        } else {
            Bu = bumpMap[row][Math.min(col + 1, bumpMapWidth - 1)] - here;
            Bv = bumpMap[Math.min(row + 1, bumpMapHeight - 1)][col] - here;
        }
        if (mistake("swapped-gradients")) {
            double t = Bu;
            Bu = Bv;
            Bv = t;
        }
        if (mistake("inverted")) {
            Bu = -Bu;
            Bv = -Bv;
        }
        Vector3 bumped = n.add(n.cross(Pv).scale(Bu)).add(n.cross(Pu).scale(Bv));
        return mistake("unnormalised-result") ? bumped : bumped.normalised();
    }
}
