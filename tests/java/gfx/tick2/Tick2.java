package gfx.tick2;

import java.awt.image.BufferedImage;
import java.io.File;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Set;
import javax.imageio.ImageIO;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.w3c.dom.NodeList;

/**
 * A Tick 2 ray tracer written from whitted's docs/rendering.md, as a student would write it, for
 * the tests of `whitted check --program`. Run as
 * {@code java -cp out gfx.tick2.Tick2 --input S.xml --output O.png --bounces N}; the mistakes of
 * docs/check.md are switched on with {@code -Dbug=id,id}.
 */
public final class Tick2 {
    static final double EPSILON = 0.0001;
    static final Set<String> BUGS = new HashSet<>();

    static boolean bug(String id) {
        return BUGS.contains(id);
    }

    /**
     * How this program computes the points and directions whose last bits decide shadow acne
     * and a reflected ray's self-hit (issue 41): students compute them their own ways, and a
     * mistake without the EPSILON offset renders differently under each. {@code -Dway=}:
     * {@code direct} (the default: the plane's root as (Q - O).N / D.N, accepted when s >= 0,
     * L = (X - P) / |X - P|), {@code constant} (the plane's constant d = Q.N, s = (d - O.N) / D.N,
     * accepted when s > 0), {@code reciprocal} (L and the sphere's normal scaled by a
     * reciprocal, P = O + s D evaluated by the shape), {@code shifted} (P = O + D s computed as
     * D s + O, the sphere's root from the half-b form).
     */
    static final String WAY = System.getProperty("way", "direct");

    record Vec3(double x, double y, double z) {
        Vec3 add(Vec3 o) { return new Vec3(x + o.x, y + o.y, z + o.z); }
        Vec3 sub(Vec3 o) { return new Vec3(x - o.x, y - o.y, z - o.z); }
        Vec3 mul(Vec3 o) { return new Vec3(x * o.x, y * o.y, z * o.z); }
        Vec3 scale(double s) { return new Vec3(x * s, y * s, z * s); }
        Vec3 negate() { return new Vec3(-x, -y, -z); }
        double dot(Vec3 o) { return x * o.x + y * o.y + z * o.z; }
        double length() { return Math.sqrt(dot(this)); }
        Vec3 normalised() { double l = length(); return new Vec3(x / l, y / l, z / l); }
    }

    record Ray(Vec3 origin, Vec3 direction) {
        Vec3 at(double s) { return origin.add(direction.scale(s)); }
    }

    static abstract class Shape {
        Vec3 colour;
        double kD, kS, n, reflectivity;
        abstract Double intersect(Ray ray);
        abstract Vec3 normalAt(Vec3 p);
    }

    static final class Sphere extends Shape {
        final Vec3 centre;
        final double radius;

        Sphere(Vec3 centre, double radius, Vec3 colour) {
            this.centre = centre; this.radius = radius; this.colour = colour;
            kD = 0.8; kS = 0.8; n = 10; reflectivity = 0.3;
        }

        Double intersect(Ray ray) {
            Vec3 d = ray.direction(), oc = ray.origin().sub(centre);
            double a = d.dot(d);
            double b = 2 * d.dot(oc);
            double c = oc.dot(oc) - radius * radius;
            double disc = b * b - 4 * a * c;
            if (disc < 0) return null;
            double near = (-b - Math.sqrt(disc)) / (2 * a);
            if (WAY.equals("shifted")) {
                double halfB = d.dot(oc);
                double quarter = halfB * halfB - a * c;
                if (quarter < 0) return null;
                near = (-halfB - Math.sqrt(quarter)) / a;
            }
            if (near > 0) return near;
            if (bug("sphere-far-root")) {
                double far = (-b + Math.sqrt(disc)) / (2 * a);
                if (far > 0) return far;
            }
            return null;
        }

        Vec3 normalAt(Vec3 p) {
            return WAY.equals("reciprocal") ? p.sub(centre).scale(1.0 / radius) : p.sub(centre).normalised();
        }
    }

    static final class Plane extends Shape {
        final Vec3 point, normal;

        Plane(Vec3 point, Vec3 normal, Vec3 colour) {
            this.point = point; this.normal = normal.normalised(); this.colour = colour;
            kD = 0.9; kS = 0.0; n = 0; reflectivity = 0.1;
        }

        Double intersect(Ray ray) {
            // The skeleton's TODO, left as it is: the empty hit.
            if (bug("planes-missing")) return null;
            double s = WAY.equals("constant")
                    ? (point.dot(normal) - ray.origin().dot(normal)) / ray.direction().dot(normal)
                    : point.sub(ray.origin()).dot(normal) / ray.direction().dot(normal);
            if (Double.isNaN(s) || Double.isInfinite(s)) return null;
            boolean behind = WAY.equals("constant") ? !(s > 0) : s < 0;
            if (behind && !bug("plane-behind")) return null;
            return s;
        }

        Vec3 normalAt(Vec3 p) { return normal; }
    }

    record Light(Vec3 position, Vec3 colour, double intensity) {
        Vec3 illumination(double d) {
            if (bug("no-falloff")) return colour.scale(intensity);
            return colour.scale(intensity / (Math.PI * 4 * d * d));
        }
    }

    record Hit(Shape shape, double distance) {}

    final List<Shape> shapes = new ArrayList<>();
    final List<Light> lights = new ArrayList<>();
    Vec3 ambient = new Vec3(1, 1, 1);
    static final Vec3 BACKGROUND = new Vec3(0.1, 0.1, 0.1);

    static Vec3 colour(String hex) {
        int rgb = Integer.parseInt(hex.substring(1), 16);
        return new Vec3(((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0, (rgb & 255) / 255.0);
    }

    static double number(Element e, String name, double otherwise) {
        String v = e.getAttribute(name);
        return v.isEmpty() ? otherwise : Double.parseDouble(v.trim());
    }

    static Vec3 vector(Element e, String x, String y, String z) {
        return new Vec3(number(e, x, 0), number(e, y, 0), number(e, z, 0));
    }

    void load(File file) throws Exception {
        NodeList nodes = DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(file)
                .getDocumentElement().getChildNodes();
        for (int i = 0; i < nodes.getLength(); i++) {
            if (nodes.item(i).getNodeType() != Node.ELEMENT_NODE) continue;
            Element e = (Element) nodes.item(i);
            switch (e.getTagName()) {
                case "sphere" -> shapes.add(new Sphere(vector(e, "x", "y", "z"), number(e, "radius", 1),
                        colour(e.getAttribute("colour"))));
                case "plane" -> shapes.add(new Plane(vector(e, "x", "y", "z"), vector(e, "nx", "ny", "nz"),
                        colour(e.getAttribute("colour"))));
                case "point-light" -> lights.add(new Light(vector(e, "x", "y", "z"),
                        colour(e.getAttribute("colour")), number(e, "intensity", 100)));
                case "ambient-light" -> ambient = colour(e.getAttribute("colour"));
                default -> throw new IllegalArgumentException("unknown element " + e.getTagName());
            }
        }
    }

    Hit closest(Ray ray) {
        Hit best = null;
        for (Shape s : shapes) {
            Double d = s.intersect(ray);
            if (d != null && (best == null || d < best.distance())) best = new Hit(s, d);
        }
        return best;
    }

    static double max0(double x) {
        return Math.max(0, x);
    }

    Vec3 illuminate(Shape shape, Vec3 p, Vec3 n, Ray ray) {
        Vec3 ambientTerm = bug("no-ambient") ? new Vec3(0, 0, 0) : ambient.mul(shape.colour);
        Vec3 colour = ambientTerm;
        Vec3 v = bug("view-flipped") ? p.normalised()
                : bug("view-from-ray-origin") ? ray.origin().sub(p).normalised()
                : p.negate().normalised();
        List<Light> used = bug("first-light-only") && !lights.isEmpty() ? lights.subList(0, 1) : lights;
        // The skeleton's TODO, left as it is: the ambient term only.
        if (bug("lights-missing")) used = List.of();
        for (Light light : used) {
            Vec3 toLight = light.position().sub(p);
            double d = toLight.length();
            Vec3 intensity = light.illumination(d);
            Vec3 l = bug("light-unnormalised") ? toLight
                    : WAY.equals("reciprocal") ? toLight.scale(1.0 / d) : toLight.normalised();
            double nDotL = n.dot(l);
            Vec3 r = bug("reflect-unclamped") ? n.scale(2 * nDotL).sub(l) : n.scale(2 * max0(nDotL)).sub(l);
            Vec3 diffuse = bug("diffuse-no-colour") ? intensity.scale(shape.kD).scale(max0(nDotL))
                    : shape.colour.mul(intensity).scale(shape.kD).scale(max0(nDotL));
            // Not in the catalogue: for the tests of the term fit.
            double exponent = bug("exponent-doubled") ? 2 * shape.n : shape.n;
            double rDotV = bug("rv-unclamped") ? r.dot(v) : max0(r.dot(v));
            Vec3 specular = intensity.scale(shape.kS).scale(Math.pow(rDotV, exponent));
            if (bug("specular-gated") && !(nDotL > 0)) specular = new Vec3(0, 0, 0);
            if (bug("specular-object-colour")) specular = specular.mul(shape.colour);
            boolean inShadow = false;
            if (!bug("no-shadows")) {
                Vec3 origin = bug("no-shadow-bias") ? p : p.add(l.scale(EPSILON));
                Hit blocker = closest(new Ray(origin, l));
                inShadow = blocker != null && (bug("shadow-any-hit") || blocker.distance() < d);
            }
            if (!inShadow) {
                Vec3 base = bug("last-light-wins") ? ambientTerm : colour;
                colour = base.add(diffuse).add(specular);
            }
        }
        return colour;
    }

    Vec3 trace(Ray ray, int bouncesLeft) {
        Hit hit = closest(ray);
        if (hit == null) return BACKGROUND;
        Shape s = hit.shape();
        Vec3 p = WAY.equals("shifted") ? ray.direction().scale(hit.distance()).add(ray.origin())
                : ray.at(hit.distance());
        Vec3 n = s.normalAt(p);
        Vec3 direct = illuminate(s, p, n, ray);
        // Reflection not written at all: the direct illumination as it is.
        if (bug("reflection-ignored")) return direct;
        if (bouncesLeft <= 0 || s.reflectivity == 0) return direct;
        if (bug("reflection-missing")) {
            // The skeleton's TODO, left as it is: reflectedIllumination stays black.
            Vec3 reflectedIllumination = new Vec3(0, 0, 0);
            return direct.scale(1 - s.reflectivity).add(reflectedIllumination.scale(s.reflectivity));
        }
        Vec3 d = ray.direction();
        Vec3 r = bug("reflection-wrong-sign") ? n.scale(2 * n.dot(d)).sub(d).normalised()
                : n.scale(2 * n.dot(d.negate())).sub(d.negate()).normalised();
        Vec3 origin = bug("no-reflection-bias") ? p : p.add(r.scale(EPSILON));
        Vec3 reflected = trace(new Ray(origin, r), bouncesLeft - 1);
        if (bug("reflection-unweighted")) return direct.add(reflected.scale(s.reflectivity));
        return direct.scale(1 - s.reflectivity).add(reflected.scale(s.reflectivity));
    }

    static int toByte(double v) {
        if (Double.isNaN(v)) return 0;
        return (int) (255 * Math.min(1, Math.max(0, v)));
    }

    public static void main(String[] args) throws Exception {
        String input = null, output = null;
        int bounces = 2;
        for (int i = 0; i + 1 < args.length; i += 2) {
            switch (args[i]) {
                case "--input" -> input = args[i + 1];
                case "--output" -> output = args[i + 1];
                case "--bounces" -> bounces = Integer.parseInt(args[i + 1]);
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        String bugs = System.getProperty("bug", "");
        if (!bugs.isEmpty()) BUGS.addAll(Arrays.asList(bugs.split(",")));
        if (bug("bounces-plus-one")) bounces += 1;
        if (bug("bounces-minus-one")) bounces -= 1;
        Tick2 scene = new Tick2();
        scene.load(new File(input));
        int width = 640, height = 480;
        double w = 2 * Math.tan(Math.toRadians(45.0 / 2));
        double h = w / ((double) width / height);
        double step = w / width;
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        for (int y = 0; y < height; y++) {
            for (int x = 0; x < width; x++) {
                double xPos = (step - w) / 2 + x * step;
                double yPos = (step + h) / 2 - y * step;
                Ray ray = new Ray(new Vec3(0, 0, 0), new Vec3(xPos, yPos, 1).normalised());
                Vec3 c = scene.trace(ray, bounces);
                image.setRGB(x, y, toByte(c.x()) << 16 | toByte(c.y()) << 8 | toByte(c.z()));
            }
            System.out.println("row " + (y + 1) + " of " + height);
        }
        ImageIO.write(image, "png", new File(output));
    }
}
