package gfx.tick2;

/** A point light (whitted's clean-room skeleton: docs/grade.md; docs/rendering.md's falloff). */
public class PointLight {
    private final Vector3 position, colour;
    private final double intensity;

    public PointLight(Vector3 position, Vector3 colour, double intensity) {
        this.position = position;
        this.colour = colour;
        this.intensity = intensity;
    }

    public Vector3 getPosition() {
        return position;
    }

    public Vector3 getColour() {
        return colour;
    }

    public double getIntensity() {
        return intensity;
    }

    /** colour * (intensity / (PI * 4 * d^2)): the quotient first, then the colour scaled. */
    public Vector3 getIlluminationAt(double distance) {
        return colour.scale(intensity / (Math.PI * 4 * distance * distance));
    }
}
