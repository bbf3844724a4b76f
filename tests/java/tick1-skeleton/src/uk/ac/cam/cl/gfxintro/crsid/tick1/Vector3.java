package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** A point or direction. whitted's test skeleton (its own API, not the course's). */
public class Vector3 {
    public final double x, y, z;

    public Vector3(double x, double y, double z) { this.x = x; this.y = y; this.z = z; }

    public Vector3 add(Vector3 o) { return new Vector3(x + o.x, y + o.y, z + o.z); }
    public Vector3 subtract(Vector3 o) { return new Vector3(x - o.x, y - o.y, z - o.z); }
    public Vector3 scale(double s) { return new Vector3(x * s, y * s, z * s); }
    public Vector3 negated() { return new Vector3(-x, -y, -z); }
    public double dot(Vector3 o) { return x * o.x + y * o.y + z * o.z; }
    public double magnitude() { return Math.sqrt(dot(this)); }
    public Vector3 normalised() { double l = magnitude(); return new Vector3(x / l, y / l, z / l); }
}
