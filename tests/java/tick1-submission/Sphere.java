package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A student's Sphere.java (2017-18 on, students write the intersection). */
public class Sphere extends SceneObject {
    private final Vector3 position;
    private final double radius;

    public Sphere(Vector3 position, double radius, ColorRGB colour) {
        this.position = position;
        this.radius = radius;
        this.colour = colour;
    }

    @Override
    public RaycastHit intersectionWith(Ray ray) {
        // TODO done: |O + sD - C|^2 = r^2, the near root, else the far one.
        if (Renderer.bug("spheres-missing")) return new RaycastHit();
        Vector3 O = ray.getOrigin(), D = ray.getDirection();
        Vector3 OC = O.subtract(position);
        double a = D.dot(D);
        double b = 2 * D.dot(OC);
        double c = OC.dot(OC) - radius * radius;
        double disc = b * b - 4 * a * c;
        if (disc < 0) return new RaycastHit();
        double s1 = (-b - Math.sqrt(disc)) / (2 * a);
        double s2 = (-b + Math.sqrt(disc)) / (2 * a);
        double s = s1 > 0 ? s1 : s2;
        if (s <= 0) return new RaycastHit();
        Vector3 P = ray.evaluateAt(s);
        return new RaycastHit(this, s, P, getNormalAt(P));
    }

    @Override
    public Vector3 getNormalAt(Vector3 P) {
        return P.subtract(position).normalised();
    }
}
