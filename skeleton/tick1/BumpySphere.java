package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.io.File;
import java.io.IOException;
import javax.imageio.ImageIO;

/**
 * Tick 1*'s bump-mapped sphere as the course ships it (whitted's clean-room skeleton): it reads
 * its map (height = 5 * blue / 255) and calls the student's three-argument Sphere constructor, so
 * Sphere must keep that constructor and stay overridable. Its normal is a stub returning the zero
 * vector: the Tick 1* part is the student's to write (2023-24's as shipped has no return at all
 * and does not compile; whitted's compiles in every year, docs/grade.md).
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

    /** The stub: the student's Tick 1* replaces it. */
    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return new Vector3(0);
    }
}
