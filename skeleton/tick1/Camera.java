package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * The pinhole camera at the origin looking down +z (whitted's clean-room skeleton). The row and
 * column steps are computed separately, as the course's are: at some sizes they differ by an ulp.
 */
public class Camera {
    double fov = 45;
    double aspectRatio;
    private final double widthM, heightM, xStep, yStep;

    public Camera(int width, int height) {
        widthM = 2 * Math.tan(Math.toRadians(fov) / 2);
        aspectRatio = (double) width / (double) height;
        heightM = widthM / aspectRatio;
        xStep = widthM / width;
        yStep = heightM / height;
    }

    /** The primary ray of pixel (x, y), y = 0 the top row. */
    public Ray castRay(int x, int y) {
        double xPos = (xStep - widthM) / 2 + x * xStep;
        double yPos = (yStep + heightM) / 2 - y * yStep;
        return new Ray(new Vector3(0), new Vector3(xPos, yPos, 1).normalised());
    }
}
