package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * A shape with a Phong material (whitted's clean-room skeleton). The material is set by the
 * subclasses' constructors (the student's Sphere and Plane): there are no setters for kD, kS and
 * alpha. 2016-17's getPhong_n is getPhong_alpha here.
 */
public abstract class SceneObject {
    protected ColorRGB colour;
    protected double phong_kD, phong_kS, phong_alpha, reflectivity;
    protected ColorRGB transmittance; //@T4
    protected double refractive_index; //@T4

    protected SceneObject() {
        colour = new ColorRGB(1);
        phong_kD = phong_kS = phong_alpha = reflectivity = 0;
        transmittance = new ColorRGB(0); //@T4
        refractive_index = 1.5; //@T4
    }

    public abstract RaycastHit intersectionWith(Ray ray);

    public abstract Vector3 getNormalAt(Vector3 position);

    public ColorRGB getColour() {
        return colour;
    }

    public void setColour(ColorRGB colour) {
        this.colour = colour;
    }

    public double getPhong_kD() {
        return phong_kD;
    }

    public double getPhong_kS() {
        return phong_kS;
    }

    public double getPhong_alpha() {
        return phong_alpha;
    }

    public double getReflectivity() {
        return reflectivity;
    }

    public void setReflectivity(double reflectivity) {
        this.reflectivity = reflectivity;
    }

    //@if T4
    /** Whether any channel of the transmittance is not zero (no course code uses it). */
    public boolean isTransmissive() {
        return !transmittance.isZero();
    }

    public ColorRGB getTransmittance() {
        return transmittance;
    }

    public double getRefractiveIndex() {
        return refractive_index;
    }
    //@end
}
