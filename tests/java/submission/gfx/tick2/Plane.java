package gfx.tick2;

/**
 * A student's Plane.java for the tests of `whitted grade`: the two files a submission holds,
 * compiled against whitted's skeleton (skeleton/gfx/tick2). The mistakes of docs/check.md that
 * live in this file are switched on with -Dbug=id,id, as in tests/java/gfx/tick2/Tick2.java.
 */
public class Plane extends SceneObject {
    private static final double PLANE_KD = 0.9, PLANE_KS = 0.0, PLANE_N = 0, PLANE_REFLECTIVITY = 0.1;

    // The point and the unit normal that intersectionWith reads.
    private final Vector3 point;
    private final Vector3 normal;

    public Plane(Vector3 point, Vector3 normal, Vector3 colour) {
        this.point = point;
        this.normal = normal.normalised();
        this.colour = colour;
        this.phong_kD = PLANE_KD;
        this.phong_kS = PLANE_KS;
        this.phong_n = PLANE_N;
        this.reflectivity = PLANE_REFLECTIVITY;
    }

    @Override
    public RaycastHit intersectionWith(Ray ray) {
        // The skeleton's TODO, left as it is: the empty hit.
        if (Renderer.bug("planes-missing")) return new RaycastHit();
        double s = point.subtract(ray.getOrigin()).dot(normal) / ray.getDirection().dot(normal);
        if (Double.isNaN(s) || Double.isInfinite(s)) return new RaycastHit();
        if (s < 0 && !Renderer.bug("plane-behind")) return new RaycastHit();
        return new RaycastHit(this, s, ray.evaluateAt(s), normal);
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return normal;
    }
}
