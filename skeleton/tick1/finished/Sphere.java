package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * whitted's finished Tick 1 Sphere (written from the handout's method and docs/rendering.md, never
 * from the course's code), in the skeleton template's markers. It completes a Tick 1* hand-in of
 * BumpySphere.java or Renderer.java alone, as the handout asks students to submit: the option's
 * file is then judged on a correct Tick 1 (grade's finished.rs). The tests' students are this
 * Tick 1 edited (tests/java/tick1-mistakes.txt).
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

    /* |O + sD - C|^2 = r^2: the near root, else the far one. */
    @Override
    public RaycastHit intersectionWith(Ray ray) {
        Vector3 O = ray.getOrigin();
        Vector3 D = ray.getDirection();
        Vector3 OC = O.subtract(position);
        double a = D.dot(D);
        double b = 2 * D.dot(OC);
        double c = OC.dot(OC) - radius * radius;
        double discriminant = b * b - 4 * a * c;
        if (discriminant < 0) {
            return new RaycastHit();
        }
        double s1 = (-b - Math.sqrt(discriminant)) / (2 * a);
        double s2 = (-b + Math.sqrt(discriminant)) / (2 * a);
        double s = s1 > 0 ? s1 : s2;
        if (s <= 0) {
            return new RaycastHit();
        }
        Vector3 P = ray.evaluateAt(s);
        return new RaycastHit(this, s, P, getNormalAt(P));
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return position.subtract(this.position).normalised();
    }
}
