package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A ray's nearest hit, or none (distance +infinity). whitted's test skeleton. */
public class RaycastHit {
    private final SceneObject object;
    private final double distance;
    private final Vector3 location, normal;

    public RaycastHit() { this(null, Double.POSITIVE_INFINITY, null, null); }

    public RaycastHit(SceneObject object, double distance, Vector3 location, Vector3 normal) {
        this.object = object; this.distance = distance; this.location = location; this.normal = normal;
    }

    public SceneObject getObjectHit() { return object; }
    public double getDistance() { return distance; }
    public Vector3 getLocation() { return location; }
    public Vector3 getNormal() { return normal; }
}
