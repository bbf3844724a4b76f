package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * Sphere.java as a student finds it in the course's zip (whitted's own, written from docs/grade.md's
 * "The student's three files as shipped"), in the skeleton template's markers: the quadratic's
 * a, b and c are computed, and no hit is ever returned: only the background shows.
 */
public class Sphere extends SceneObject {
    private final double SPHERE_KD = 0.8;
    private final double SPHERE_KS = 0.8; //@T1
    private final double SPHERE_KS = 1.2; //@T2+
    private final double SPHERE_ALPHA = 10;
    private final double SPHERE_REFLECTIVITY = 0.3;

    private Vector3 position;
    private double radius;

    public Sphere(Vector3 position, double radius, ColorRGB colour) {
        this.position = position;
        this.radius = radius;
        this.colour = colour;
        this.phong_kD = SPHERE_KD;
        this.phong_kS = SPHERE_KS;
        this.phong_alpha = SPHERE_ALPHA;
        this.reflectivity = SPHERE_REFLECTIVITY;
    }

    public Sphere(Vector3 position, double radius, ColorRGB colour, double kD, double kS, double alphaS, double reflectivity) { //@T3
    public Sphere(Vector3 position, double radius, ColorRGB colour, double kD, double kS, double alphaS, double reflectivity, ColorRGB transmittance) { //@T4
        //@if T3+
        this.position = position;
        this.radius = radius;
        this.colour = colour;
        this.phong_kD = kD;
        this.phong_kS = kS;
        this.phong_alpha = alphaS;
        this.reflectivity = reflectivity;
        this.transmittance = transmittance; //@T4
    }
    //@end

    public Vector3 getPosition() {
        return position;
    }

    @Override
    public RaycastHit intersectionWith(Ray ray) {
        Vector3 O = ray.getOrigin();
        Vector3 D = ray.getDirection();
        Vector3 C = position;
        double r = radius;
        double a = D.dot(D);
        double b = 2 * D.dot(O.subtract(C));
        double c = O.subtract(C).dot(O.subtract(C)) - Math.pow(r, 2);
        // TODO: determine if ray and sphere intersect; if so, return a RaycastHit
        return new RaycastHit();
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return position.subtract(this.position).normalised();
    }
}
