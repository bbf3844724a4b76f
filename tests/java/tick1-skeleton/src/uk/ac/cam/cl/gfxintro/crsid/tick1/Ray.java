package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A ray. whitted's test skeleton (its own API, not the course's). */
public class Ray {
    private final Vector3 origin, direction;

    public Ray(Vector3 origin, Vector3 direction) { this.origin = origin; this.direction = direction; }

    public Vector3 getOrigin() { return origin; }
    public Vector3 getDirection() { return direction; }
    public Vector3 evaluateAt(double s) { return origin.add(direction.scale(s)); }
}
