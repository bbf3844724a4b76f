package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A point light (whitted's clean-room skeleton). */
public class PointLight {
    private final Vector3 position;
    private final ColorRGB colour;
    private final double intensity;

    public PointLight(Vector3 position, ColorRGB colour, double intensity) {
        this.position = position;
        this.colour = colour;
        this.intensity = intensity;
    }

    public Vector3 getPosition() {
        return position;
    }

    public ColorRGB getColour() {
        return colour;
    }

    public double getIntensity() {
        return intensity;
    }

    /**
     * A new colour: the light's colour scaled by intensity / (pi * 4 * d^2), the quotient first,
     * with Math.pow(d, 2). It already holds the light's colour, so the shipped Renderer's
     * C_spec * I counts the colour twice (docs/courses.md).
     */
    public ColorRGB getIlluminationAt(double distance) {
        return colour.scale(intensity / (Math.PI * 4 * Math.pow(distance, 2)));
    }
}
