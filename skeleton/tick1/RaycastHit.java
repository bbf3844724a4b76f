package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * Where a ray hit what (whitted's clean-room skeleton). The empty hit holds nulls, not zero
 * vectors, as the course's does: a student's code that reads a miss's location throws there too.
 */
public class RaycastHit {
    private final SceneObject objectHit;
    private final double distance;
    private final Vector3 location, normal;

    /** No hit: at infinite distance, of nothing, nowhere. */
    public RaycastHit() {
        this(null, Double.POSITIVE_INFINITY, null, null);
    }

    /** Exactly what it is given. */
    public RaycastHit(SceneObject objectHit, double distance, Vector3 location, Vector3 normal) {
        this.objectHit = objectHit;
        this.distance = distance;
        this.location = location;
        this.normal = normal;
    }

    public SceneObject getObjectHit() {
        return objectHit;
    }

    public Vector3 getLocation() {
        return location;
    }

    public Vector3 getNormal() {
        return normal;
    }

    public double getDistance() {
        return distance;
    }
}
