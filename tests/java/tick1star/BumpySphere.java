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
 * -Dbump=PARAMETRISATION[,MISTAKE...] chooses how it is written, in the names of whitted's
 * docs/tick1star.md (v = acos(n.pole) / pi throughout). The parametrisations, each correct
 * (the map lies on the sphere one-to-one, moved or mirrored): y-zx (the poles on y,
 * u = 0.5 + atan2(n.z, n.x) / 2pi; the default), y-zx-mirrored (u = 0.5 - that), y-xz
 * (u = 0.5 + atan2(n.x, n.z) / 2pi), y-zx-from-x (u = atan2(n.z, n.x) / 2pi wrapped into
 * [0, 1)), z-yx (the poles on z, u = 0.5 + atan2(n.y, n.x) / 2pi), z-yx-from-x. The mistakes:
 * inverted (the relief's sign flipped), swapped-gradients (B_u with P_u and B_v with P_v),
 * unnormalised-tangents, unnormalised-normal (n' not normalised), wrong-texel (the gradient
 * towards the texel left and above, neighbour minus current as before), colour-as-height (the
 * packed colour 0xRRGGBB as height, not the blue byte), no-centre (the normal
 * of a sphere at the origin: P not made relative to the centre).
 */
public class BumpySphere extends Sphere {
    private static final String[] BUMP = System.getProperty("bump", "y-zx").split(",");
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
                    float height = mistake("colour-as-height") ? (rgb & 0xFFFFFF) / 255f : (float) (rgb & 0xFF) / 0xFF;
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
        String name = BUMP[0];
        boolean poleZ = name.startsWith("z-");
        // (a, b, c): the pole's axis c, u's angle phi = atan2(b, a), as the name says.
        double a, b, c;
        if (poleZ) {
            a = n.x; b = n.y; c = n.z;
        } else if (name.startsWith("y-xz")) {
            a = n.z; b = n.x; c = n.y;
        } else if (name.startsWith("y-zx")) {
            a = n.x; b = n.z; c = n.y;
        } else {
            throw new IllegalArgumentException("no parametrisation " + name);
        }
        double theta = Math.acos(c), phi = Math.atan2(b, a);
        double u = 0.5 + phi / (2 * Math.PI);
        if (name.endsWith("-mirrored")) u = 1 - u;
        if (name.endsWith("-from-x")) u = phi >= 0 ? phi / (2 * Math.PI) : 1 + phi / (2 * Math.PI);
        double v = theta / Math.PI;
        double du = name.endsWith("-mirrored") ? -2 * Math.PI : 2 * Math.PI;
        // The partial derivatives of (a, b, c) = (sin theta cos phi, sin theta sin phi, cos theta).
        double[] dU = {-Math.sin(theta) * Math.sin(phi) * du, Math.sin(theta) * Math.cos(phi) * du, 0};
        double[] dV = {Math.cos(theta) * Math.cos(phi) * Math.PI, Math.cos(theta) * Math.sin(phi) * Math.PI, -Math.sin(theta) * Math.PI};
        Vector3 Pu = back(dU, poleZ, name.startsWith("y-xz"));
        Vector3 Pv = back(dV, poleZ, name.startsWith("y-xz"));
        if (!mistake("unnormalised-tangents")) {
            Pu = Pu.normalised();
            Pv = Pv.normalised();
        }
        // The texel under (u, v) and its neighbours (clamped at the map's edges).
        int col = Math.min((int) Math.floor(u * bumpMapWidth), bumpMapWidth - 1);
        int row = Math.min((int) Math.floor(v * bumpMapHeight), bumpMapHeight - 1);
        float here = bumpMap[row][col];
        double Bu, Bv;
        if (mistake("wrong-texel")) {
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
        return mistake("unnormalised-normal") ? bumped : bumped.normalised();
    }

    /** A vector of the (a, b, c) frame back in (x, y, z). */
    private static Vector3 back(double[] d, boolean poleZ, boolean xz) {
        if (poleZ) return new Vector3(d[0], d[1], d[2]);
        if (xz) return new Vector3(d[1], d[2], d[0]);
        return new Vector3(d[0], d[2], d[1]);
    }
}
