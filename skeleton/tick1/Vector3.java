package uk.ac.cam.cl.gfxintro.crsid.tick1;

/**
 * A point or direction, immutable (whitted's clean-room skeleton: docs/grade.md, "The Tick 1
 * skeleton's API"). Every method returns a new vector; each evaluates in the order the course's
 * classes do (dot summed x, y, z; normalised divides), so a student's code renders the same bytes.
 * There is no toString, length or normalize: a call the course's classes do not offer must not
 * compile here either.
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

    public Vector3 add(double scalar) { //@T2+
        return new Vector3(x + scalar, y + scalar, z + scalar); //@T2+
    } //@T2+

    public Vector3 subtract(Vector3 other) {
        return new Vector3(x - other.x, y - other.y, z - other.z);
    }

    public Vector3 subtract(double scalar) { //@T4
        return new Vector3(x - scalar, y - scalar, z - scalar); //@T4
    } //@T4

    public Vector3 scale(double scalar) {
        return new Vector3(x * scalar, y * scalar, z * scalar);
    }

    /** Component-wise product. */
    public Vector3 scale(Vector3 other) {
        return new Vector3(x * other.x, y * other.y, z * other.z);
    }

    //@if T2+
    /** Each component raised to `e` by Math.pow. */
    public Vector3 power(double e) {
        return new Vector3(Math.pow(x, e), Math.pow(y, e), Math.pow(z, e));
    }

    /** 1 / each component: a zero gives infinity. */
    public Vector3 inv() {
        return new Vector3(1 / x, 1 / y, 1 / z);
    }
    //@end

    public double dot(Vector3 other) {
        return x * other.x + y * other.y + z * other.z;
    }

    public Vector3 cross(Vector3 other) {
        return new Vector3(y * other.z - z * other.y, z * other.x - x * other.z, x * other.y - y * other.x);
    }

    public double magnitude() {
        return Math.sqrt(x * x + y * y + z * z);
    }

    /** Each component divided by the magnitude (not multiplied by its reciprocal): zero gives NaNs. */
    public Vector3 normalised() {
        double magnitude = magnitude();
        return new Vector3(x / magnitude, y / magnitude, z / magnitude);
    }

    /** This vector mirrored in N: N * 2(this . N) - this, neither negated nor normalised. */
    public Vector3 reflectIn(Vector3 N) {
        return N.scale(2 * this.dot(N)).subtract(this);
    }

    /**
     * Three Math.random() draws, in this order: a radius in [0, 1), a polar angle in [0, pi), an
     * azimuth in [0, 2 pi). Not uniform in volume, as the course's is not.
     */
    public static Vector3 randomInsideUnitSphere() {
        double r = Math.random();
        double theta = Math.random() * Math.PI;
        double phi = Math.random() * 2 * Math.PI;
        return new Vector3(r * Math.sin(theta) * Math.cos(phi), r * Math.sin(theta) * Math.sin(phi), r * Math.cos(theta));
    }

    /** Exact comparison: an overload, so equals(Object) and hashCode stay Object's. */
    public boolean equals(Vector3 other) {
        return x == other.x && y == other.y && z == other.z;
    }

    /** Whether all three components are exactly 0. */ //@T4
    public boolean isZero() { //@T4
        return x == 0 && y == 0 && z == 0; //@T4
    } //@T4
}
