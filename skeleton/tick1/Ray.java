package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A ray: origin + s * direction, both stored as given, not normalised (whitted's clean-room skeleton). */
public class Ray {
    private final Vector3 origin, direction;

    public Ray(Vector3 origin, Vector3 direction) {
        this.origin = origin;
        this.direction = direction;
    }

    public Vector3 getOrigin() {
        return origin;
    }

    public Vector3 getDirection() {
        return direction;
    }

    /** origin + direction * s. */
    public Vector3 evaluateAt(double s) {
        return origin.add(direction.scale(s));
    }
}
