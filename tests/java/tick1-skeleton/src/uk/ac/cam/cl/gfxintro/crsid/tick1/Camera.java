package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** The pinhole camera at the origin, 45 degrees wide, rows stepped by height/H. */
public class Camera {
    private final int width, height;
    private final double w, h, xStep, yStep;

    public Camera(int width, int height) {
        this.width = width; this.height = height;
        w = 2 * Math.tan(Math.toRadians(45.0 / 2));
        h = w / ((double) width / height);
        xStep = w / width;
        yStep = h / height;
    }

    public Ray castRay(int x, int y) {
        double xPos = (xStep - w) / 2 + x * xStep;
        double yPos = (yStep + h) / 2 - y * yStep;
        return new Ray(new Vector3(0, 0, 0), new Vector3(xPos, yPos, 1).normalised());
    }
}
