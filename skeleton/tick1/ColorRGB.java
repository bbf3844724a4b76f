package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * A linear colour, immutable (whitted's clean-room skeleton: docs/grade.md). It wraps a private
 * Vector3, so its arithmetic is the vector's; its constructor from a Vector3 is private, so code
 * outside converts only component by component. No dot, magnitude, getters or toString.
 */
public class ColorRGB {
    public final double r, g, b;
    private final Vector3 vector;

    public ColorRGB(double grey) {
        this(new Vector3(grey));
    }

    public ColorRGB(double r, double g, double b) {
        this(new Vector3(r, g, b));
    }

    private ColorRGB(Vector3 vector) {
        this.vector = vector;
        this.r = vector.x;
        this.g = vector.y;
        this.b = vector.z;
    }

    public ColorRGB add(ColorRGB other) {
        return new ColorRGB(vector.add(other.vector));
    }

    public ColorRGB add(double scalar) { //@T2+
        return new ColorRGB(vector.add(scalar)); //@T2+
    } //@T2+

    public ColorRGB subtract(ColorRGB other) {
        return new ColorRGB(vector.subtract(other.vector));
    }

    public ColorRGB subtract(double scalar) { //@T4
        return new ColorRGB(vector.subtract(scalar)); //@T4
    } //@T4

    public ColorRGB scale(double scalar) {
        return new ColorRGB(vector.scale(scalar));
    }

    /** Component-wise product. */
    public ColorRGB scale(ColorRGB other) {
        return new ColorRGB(vector.scale(other.vector));
    }

    //@if T2+
    public ColorRGB power(double e) {
        return new ColorRGB(vector.power(e));
    }

    public ColorRGB inv() {
        return new ColorRGB(vector.inv());
    }
    //@end

    public boolean isZero() { //@T4
        return vector.isZero(); //@T4
    } //@T4

    /** Exact comparison; an overload. */
    public boolean equals(ColorRGB other) {
        return vector.equals(other.vector);
    }

    /**
     * The packed 8-bit RGB: per channel (int)(255 * max(0, min(1, c))), truncating; a NaN gives 0
     * (Math.min and max keep it, and (int) NaN is 0). The course classes' only clamp.
     */
    public int toRGB() {
        return channel(r) << 16 | channel(g) << 8 | channel(b);
    }

    private static int channel(double c) {
        return (int) (255 * Math.max(0, Math.min(1, c)));
    }
}
