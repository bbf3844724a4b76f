package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A student's Plane.java: the normal used as the loader stored it. */
public class Plane extends SceneObject {
    private final Vector3 point, normal;

    public Plane(Vector3 point, Vector3 normal, ColorRGB colour) {
        this.point = point;
        this.normal = normal;
        this.colour = colour;
        setMaterial(0.6, 0, 0, 0.1);
    }

    @Override
    public RaycastHit intersectionWith(Ray ray) {
        if (Renderer.bug("planes-missing")) return new RaycastHit();
        double s = point.subtract(ray.getOrigin()).dot(normal) / ray.getDirection().dot(normal);
        if (Double.isNaN(s) || Double.isInfinite(s)) return new RaycastHit();
        if (s < 0 && !Renderer.bug("plane-behind")) return new RaycastHit();
        return new RaycastHit(this, s, ray.evaluateAt(s), normal);
    }

    @Override
    public Vector3 getNormalAt(Vector3 P) {
        return normal;
    }
}
