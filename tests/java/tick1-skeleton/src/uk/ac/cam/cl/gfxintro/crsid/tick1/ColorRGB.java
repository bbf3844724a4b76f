package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A linear colour. whitted's test skeleton (its own API, not the course's). */
public class ColorRGB {
    public final double r, g, b;

    public ColorRGB(double r, double g, double b) { this.r = r; this.g = g; this.b = b; }
    public ColorRGB(double v) { this(v, v, v); }

    public ColorRGB add(ColorRGB o) { return new ColorRGB(r + o.r, g + o.g, b + o.b); }
    public ColorRGB scale(double s) { return new ColorRGB(r * s, g * s, b * s); }
    public ColorRGB scale(ColorRGB o) { return new ColorRGB(r * o.r, g * o.g, b * o.b); }
}
