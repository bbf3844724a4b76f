package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * whitted's finished Tick 1 Plane (the normal used as stored, as the loader normalises it), in the
 * skeleton template's markers: it completes a Tick 1* hand-in of one file (grade's finished.rs).
 * The tests' students are this Tick 1 edited (tests/java/tick1-mistakes.txt).
 */
public class Plane extends SceneObject {
    private final double PLANE_KD = 0.9; //@T1
    private final double PLANE_KD = 0.6; //@T2
    private final double PLANE_KS = 0; //@T1-T2
    private final double PLANE_ALPHA = 0; //@T1-T2
    private final double PLANE_REFLECTIVITY = 0.1; //@T1-T2
    private final double DEFAULT_PLANE_KD = 0.6; //@T3+
    private final double DEFAULT_PLANE_KS = 0; //@T3+
    private final double DEFAULT_PLANE_ALPHA = 0; //@T3+
    private final double DEFAULT_PLANE_REFLECTIVITY = 0.1; //@T3+

    private Vector3 point;
    private Vector3 normal;

    public Plane(Vector3 point, Vector3 normal, ColorRGB colour) {
        this.point = point;
        this.normal = normal;
        this.colour = colour;
        this.phong_kD = PLANE_KD; //@T1-T2
        this.phong_kS = PLANE_KS; //@T1-T2
        this.phong_alpha = PLANE_ALPHA; //@T1-T2
        this.reflectivity = PLANE_REFLECTIVITY; //@T1-T2
        this.phong_kD = DEFAULT_PLANE_KD; //@T3+
        this.phong_kS = DEFAULT_PLANE_KS; //@T3+
        this.phong_alpha = DEFAULT_PLANE_ALPHA; //@T3+
        this.reflectivity = DEFAULT_PLANE_REFLECTIVITY; //@T3+
    }

    //@if T3+
    public Plane(Vector3 point, Vector3 normal, ColorRGB colour, double kD, double kS, double alphaS, double reflectivity) {
        this.point = point;
        this.normal = normal;
        this.colour = colour;
        this.phong_kD = kD;
        this.phong_kS = kS;
        this.phong_alpha = alphaS;
        this.reflectivity = reflectivity;
    }
    //@end

    /* s = (Q - O).N / D.N, in front of the ray only. */
    @Override
    public RaycastHit intersectionWith(Ray ray) {
        Vector3 O = ray.getOrigin();
        Vector3 D = ray.getDirection();
        double s = point.subtract(O).dot(normal) / D.dot(normal);
        if (Double.isNaN(s) || Double.isInfinite(s) || s < 0) {
            return new RaycastHit();
        }
        return new RaycastHit(this, s, ray.evaluateAt(s), normal);
    }

    @Override
    public Vector3 getNormalAt(Vector3 point) {
        return normal;
    }
}
