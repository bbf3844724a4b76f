package gfx.tick2;

/**
 * A student's Plane.java for the tests of `whitted grade`: the two files a submission holds,
 * compiled against whitted's skeleton (skeleton/gfx/tick2). The mistakes of docs/check.md that
 * live in this file are switched on with -Dbug=id,id, as in tests/java/gfx/tick2/Tick2.java.
 */
public class Plane extends SceneObject {
    private static final double PLANE_KD = 0.9, PLANE_KS = 0.0, PLANE_N = 0, PLANE_REFLECTIVITY = 0.1;

    // A point in the plane, and its normal as the skeleton's loader gives it (normalised there):
    // used as given, as real students' files do.
    private Vector3 point;
    private Vector3 normal;

    public Plane(Vector3 point, Vector3 normal, Vector3 colour) {
        this.point = point;
        this.normal = normal;
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
        Vector3 O = ray.getOrigin();
        Vector3 D = ray.getDirection();
        Vector3 Q = this.point;
        Vector3 N = this.normal;
        double s = Q.subtract(O).dot(N) / D.dot(N);
        if (Double.isNaN(s) || Double.isInfinite(s)) return new RaycastHit();
        if (s < 0 && !Renderer.bug("plane-behind")) return new RaycastHit();
        return new RaycastHit(this, s, ray.evaluateAt(s), N);
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return normal;
    }
}
