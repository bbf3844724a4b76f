package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A sphere or a plane with its Phong material. whitted's test skeleton. */
public abstract class SceneObject {
    protected ColorRGB colour;
    protected double kD = 0.8, kS = 1.2, alphaS = 10, reflectivity = 0.3;

    public abstract RaycastHit intersectionWith(Ray ray);
    public abstract Vector3 getNormalAt(Vector3 position);

    public ColorRGB getColour() { return colour; }
    public double getPhong_kD() { return kD; }
    public double getPhong_kS() { return kS; }
    public double getPhong_alpha() { return alphaS; }
    public double getReflectivity() { return reflectivity; }

    public void setMaterial(double kD, double kS, double alphaS, double reflectivity) {
        this.kD = kD; this.kS = kS; this.alphaS = alphaS; this.reflectivity = reflectivity;
    }
}
