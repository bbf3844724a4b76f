package gfx.tick2;

/** The pinhole camera (whitted's clean-room skeleton: docs/grade.md; docs/rendering.md's grid). */
public class Camera {
    private static final double FOV_DEGREES = 45;

    private final double width, step, height;

    public Camera(int width, int height) {
        this.width = 2 * Math.tan(Math.toRadians(FOV_DEGREES / 2));
        this.height = this.width / ((double) width / height);
        this.step = this.width / width;
    }

    /** The primary ray of pixel (x, y), y = 0 the top row, in docs/rendering.md's order. */
    public Ray castRay(int x, int y) {
        double xPos = (step - width) / 2 + x * step;
        double yPos = (step + height) / 2 - y * step;
        return new Ray(new Vector3(0), new Vector3(xPos, yPos, 1).normalised());
    }
}
