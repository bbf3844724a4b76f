package gfx.tick2;

/** A sphere (whitted's clean-room skeleton: docs/grade.md; docs/rendering.md's intersection). */
public class Sphere extends SceneObject {
    private static final double SPHERE_KD = 0.8, SPHERE_KS = 0.8, SPHERE_N = 10, SPHERE_REFLECTIVITY = 0.3;

    private final Vector3 position;
    private final double radius;

    public Sphere(Vector3 position, double radius, Vector3 colour) {
        this.position = position;
        this.radius = radius;
        this.colour = colour;
        this.phong_kD = SPHERE_KD;
        this.phong_kS = SPHERE_KS;
        this.phong_n = SPHERE_N;
        this.reflectivity = SPHERE_REFLECTIVITY;
    }

    /** The near root only, and only in front of the origin: a ray from inside misses. */
    @Override
    public RaycastHit intersectionWith(Ray ray) {
        Vector3 O = ray.getOrigin(), D = ray.getDirection();
        Vector3 OC = O.subtract(position);
        double a = D.dot(D);
        double b = 2 * D.dot(OC);
        double c = OC.dot(OC) - radius * radius;
        double disc = b * b - 4 * a * c;
        if (disc < 0) return new RaycastHit();
        double s = (-b - Math.sqrt(disc)) / (2 * a);
        if (!(s > 0)) return new RaycastHit();
        Vector3 location = ray.evaluateAt(s);
        return new RaycastHit(this, s, location, getNormalAt(location));
    }

    @Override
    public Vector3 getNormalAt(Vector3 location) {
        return location.subtract(position).normalised();
    }
}
