package gfx.tick2;

import java.util.concurrent.ThreadLocalRandom;

/**
 * whitted's clean-room skeleton of the course's gfx.tick2 classes (see docs/grade.md): written
 * from the API in the handout's class list and the arithmetic of docs/rendering.md, so that a
 * student's Plane.java and Renderer.java compile against it unchanged and render the same
 * bytes. Every operation evaluates in the order docs/rendering.md gives.
 */
public class Vector3 {
    public final double x, y, z;

    public Vector3(double uniform) {
        this(uniform, uniform, uniform);
    }

    public Vector3(double x, double y, double z) {
        this.x = x;
        this.y = y;
        this.z = z;
    }

    public Vector3 add(Vector3 other) {
        return new Vector3(x + other.x, y + other.y, z + other.z);
    }

    public Vector3 subtract(Vector3 other) {
        return new Vector3(x - other.x, y - other.y, z - other.z);
    }

    public Vector3 scale(double scalar) {
        return new Vector3(x * scalar, y * scalar, z * scalar);
    }

    /** Component-wise product (colours). */
    public Vector3 scale(Vector3 other) {
        return new Vector3(x * other.x, y * other.y, z * other.z);
    }

    public double dot(Vector3 other) {
        return x * other.x + y * other.y + z * other.z;
    }

    public Vector3 cross(Vector3 other) {
        return new Vector3(y * other.z - z * other.y, z * other.x - x * other.z, x * other.y - y * other.x);
    }

    public double magnitude() {
        return Math.sqrt(dot(this));
    }

    /** Each component divided by the magnitude (not multiplied by its reciprocal). */
    public Vector3 normalised() {
        double length = magnitude();
        return new Vector3(x / length, y / length, z / length);
    }

    /** This vector reflected in the normal N: N * 2(this . N) - this. */
    public Vector3 reflectIn(Vector3 N) {
        return N.scale(2 * this.dot(N)).subtract(this);
    }

    /** The packed 8-bit RGB of this colour: floor(255 * clamp(v, 0, 1)) per channel, NaN as 0. */
    public int toRGB() {
        return channel(x) << 16 | channel(y) << 8 | channel(z);
    }

    private static int channel(double v) {
        // Math.max/min keep a NaN, and (int) NaN is 0.
        return (int) (255 * Math.min(1, Math.max(0, v)));
    }

    /** A point drawn uniformly from inside the unit sphere (by rejection). */
    public static Vector3 randomInsideUnitSphere() {
        ThreadLocalRandom random = ThreadLocalRandom.current();
        for (;;) {
            Vector3 v = new Vector3(random.nextDouble(-1, 1), random.nextDouble(-1, 1), random.nextDouble(-1, 1));
            if (v.dot(v) <= 1) return v;
        }
    }

    public boolean equals(Vector3 other) {
        return other != null && x == other.x && y == other.y && z == other.z;
    }

    @Override
    public String toString() {
        return "(" + x + ", " + y + ", " + z + ")";
    }
}
