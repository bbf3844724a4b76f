package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A point light. whitted's test skeleton (its own API, not the course's). */
public class PointLight {
    private final Vector3 position;
    private final ColorRGB colour;
    private final double intensity;

    public PointLight(Vector3 position, ColorRGB colour, double intensity) {
        this.position = position; this.colour = colour; this.intensity = intensity;
    }

    public Vector3 getPosition() { return position; }
    public ColorRGB getColour() { return colour; }
    public double getIntensity() { return intensity; }

    public ColorRGB getIlluminationAt(double d) {
        return colour.scale(intensity / (Math.PI * 4 * d * d));
    }
}
