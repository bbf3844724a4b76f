package gfx.tick2;

/** A shape with a Phong material (whitted's clean-room skeleton: docs/grade.md). */
public abstract class SceneObject {
    protected Vector3 colour;
    protected double phong_kD, phong_kS, phong_n;
    protected double reflectivity;

    /** The nearest hit in front of the ray's origin, or a RaycastHit() when there is none. */
    public abstract RaycastHit intersectionWith(Ray ray);

    public abstract Vector3 getNormalAt(Vector3 position);

    public Vector3 getColour() {
        return colour;
    }

    public void setColour(Vector3 colour) {
        this.colour = colour;
    }

    public double getPhong_kD() {
        return phong_kD;
    }

    public double getPhong_kS() {
        return phong_kS;
    }

    public double getPhong_n() {
        return phong_n;
    }

    public double getReflectivity() {
        return reflectivity;
    }

    public void setReflectivity(double reflectivity) {
        this.reflectivity = reflectivity;
    }
}
