package uk.ac.cam.cl.gfxintro.whitted.tick1;

import java.awt.image.BufferedImage;
import java.io.File;
import java.util.ArrayList;
import java.util.List;
import javax.imageio.ImageIO;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.w3c.dom.NodeList;

/**
 * The course's Tick 1 ray tracer of every year from 2016-17 to 2023-24, written from whitted's
 * docs/courses.md and docs/rendering.md (not from any course's code), the year chosen with
 * {@code -Dcourse=2020-21}, for the tests that `whitted render --course YEAR` renders what a
 * correct program of that year renders. Run as
 * {@code java -Dcourse=Y -cp out uk.ac.cam.cl.gfxintro.whitted.tick1.Tick1 -i S.xml -o O.png
 * -b N -r WxH}. {@code -Dbug=id,id} makes the catalogue's mistakes the way a student writes
 * them, for the tests of `whitted check --course`; {@code -Dsphere=geometric} writes the sphere
 * intersection in other arithmetic, as many students do.
 */
public final class Tick1 {
    static final double EPSILON = 0.0001;

    /** What differs between years, read once from the year's name. */
    static final class Year {
        final int start;

        Year(String name) { start = Integer.parseInt(name.substring(0, 4)); }

        boolean tick2() { return start == 2016; }
        boolean viewFromRayOrigin() { return start >= 2017; }
        boolean lightColouredSpecular() { return start >= 2017; }
        boolean reflectUnclamped() { return start >= 2017; }
        boolean farRoot() { return start >= 2017; }
        boolean gate() { return start >= 2018; }
        boolean shadowAlongN() { return start >= 2020; }
        boolean toneMapped() { return start >= 2018; }
        boolean materials() { return start >= 2019; }
        boolean ambientIntensity() { return start >= 2019; }
        boolean separateRowStep() { return start >= 2017; }
        double background() { return start >= 2018 ? 0.001 : 0.1; }
        double sphereKS() { return start >= 2018 ? 1.2 : 0.8; }
        /** kD kS n r of a plane as the year's loader makes it. */
        double[] plane() {
            if (start >= 2019) return new double[] {0.8, 1.2, 10, 0.3};
            if (start == 2018) return new double[] {0.6, 0, 0, 0.1};
            return new double[] {0.9, 0, 0, 0.1};
        }
    }

    static Year year;

    /** Catalogue entries (whitted check --list-bugs) this run makes, from -Dbug=a,b. */
    static final java.util.Set<String> BUGS = new java.util.HashSet<>();

    static boolean bug(String id) { return BUGS.contains(id); }

    /** Tick 1*'s soft shadows (-Dstar=soft-shadows): random, so never the same image twice. */
    static final boolean SOFT_SHADOWS = "soft-shadows".equals(System.getProperty("star", ""));

    /** The sphere intersection written another way (-Dsphere=geometric), as real students do. */
    static final boolean GEOMETRIC_SPHERE = "geometric".equals(System.getProperty("sphere", ""));

    record Vector3(double x, double y, double z) {
        Vector3 add(Vector3 o) { return new Vector3(x + o.x, y + o.y, z + o.z); }
        Vector3 subtract(Vector3 o) { return new Vector3(x - o.x, y - o.y, z - o.z); }
        Vector3 scale(double s) { return new Vector3(x * s, y * s, z * s); }
        Vector3 negated() { return new Vector3(-x, -y, -z); }
        double dot(Vector3 o) { return x * o.x + y * o.y + z * o.z; }
        double magnitude() { return Math.sqrt(dot(this)); }
        Vector3 normalised() { double l = magnitude(); return new Vector3(x / l, y / l, z / l); }
    }

    record ColorRGB(double r, double g, double b) {
        ColorRGB add(ColorRGB o) { return new ColorRGB(r + o.r, g + o.g, b + o.b); }
        ColorRGB scale(double s) { return new ColorRGB(r * s, g * s, b * s); }
        ColorRGB scale(ColorRGB o) { return new ColorRGB(r * o.r, g * o.g, b * o.b); }
    }

    record Ray(Vector3 origin, Vector3 direction) {
        Vector3 evaluateAt(double s) { return origin.add(direction.scale(s)); }
    }

    static abstract class SceneObject {
        ColorRGB colour;
        double kD, kS, alphaS, reflectivity;
        abstract Double intersectionWith(Ray ray);
        abstract Vector3 getNormalAt(Vector3 p);
    }

    static final class Sphere extends SceneObject {
        final Vector3 centre;
        final double radius;

        Sphere(Vector3 centre, double radius) { this.centre = centre; this.radius = radius; }

        Double intersectionWith(Ray ray) {
            // The skeleton's TODO: no sphere is hit yet.
            if (bug("spheres-missing")) return null;
            if (GEOMETRIC_SPHERE) return geometricRoot(ray);
            Vector3 o = ray.origin(), d = ray.direction();
            Vector3 oc = o.subtract(centre);
            double a = d.dot(d);
            double b = 2 * d.dot(oc);
            double c = oc.dot(oc) - radius * radius;
            double disc = b * b - 4 * a * c;
            if (disc < 0) return null;
            double near = (-b - Math.sqrt(disc)) / (2 * a);
            if (near > 0) return near;
            if (year.farRoot()) {
                double far = (-b + Math.sqrt(disc)) / (2 * a);
                if (far > 0) return far;
            }
            return null;
        }

        /**
         * The intersection as many students write it instead (-Dsphere=geometric): the
         * half-chord from the closest approach, other arithmetic than the quadratic's, so other
         * last bits in every hit. Rays are unit length here, as the course's always are.
         */
        Double geometricRoot(Ray ray) {
            Vector3 toCentre = centre.subtract(ray.origin());
            double along = toCentre.dot(ray.direction());
            double r2 = radius * radius;
            double apart2 = toCentre.dot(toCentre) - along * along;
            if (apart2 > r2) return null;
            double half = Math.sqrt(r2 - apart2);
            if (along - half > 0) return along - half;
            if (year.farRoot() && along + half > 0) return along + half;
            return null;
        }

        Vector3 getNormalAt(Vector3 p) { return p.subtract(centre).normalised(); }
    }

    static final class Plane extends SceneObject {
        final Vector3 point, normal;

        Plane(Vector3 point, Vector3 normal) { this.point = point; this.normal = normal; }

        Double intersectionWith(Ray ray) {
            if (bug("planes-missing")) return null;
            double s = point.subtract(ray.origin()).dot(normal) / ray.direction().dot(normal);
            if (Double.isNaN(s) || Double.isInfinite(s)) return null;
            if (s < 0 && !bug("plane-behind")) return null;
            return s;
        }

        Vector3 getNormalAt(Vector3 p) { return normal; }
    }

    record PointLight(Vector3 position, ColorRGB colour, double intensity) {
        ColorRGB getIlluminationAt(double d) {
            if (bug("no-falloff")) return colour.scale(intensity);
            return colour.scale(intensity / (Math.PI * 4 * d * d));
        }
    }

    record Hit(SceneObject object, double distance) {}

    final List<SceneObject> objects = new ArrayList<>();
    final List<PointLight> lights = new ArrayList<>();
    ColorRGB ambient = new ColorRGB(1, 1, 1);

    static ColorRGB colour(String text) {
        String hex = text.trim().substring(1, 7);
        int rgb = Integer.parseInt(hex, 16);
        return new ColorRGB(((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0, (rgb & 255) / 255.0);
    }

    static double number(Element e, String name, double otherwise) {
        try {
            return Double.parseDouble(e.getAttribute(name));
        } catch (NumberFormatException missing) {
            return otherwise;
        }
    }

    static Vector3 vector(Element e, String x, String y, String z) {
        return new Vector3(number(e, x, 0), number(e, y, 0), number(e, z, 0));
    }

    void materials(SceneObject o, Element e, double kD, double kS, double alphaS, double r) {
        o.colour = colour(e.getAttribute("colour"));
        o.kD = kD; o.kS = kS; o.alphaS = alphaS; o.reflectivity = r;
        if (year.materials()) {
            o.kD = number(e, "kD", kD);
            o.kS = number(e, "kS", kS);
            o.alphaS = number(e, "alphaS", alphaS);
            o.reflectivity = number(e, "reflectivity", r);
        }
    }

    void load(File file) throws Exception {
        NodeList nodes = DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(file)
                .getDocumentElement().getChildNodes();
        for (int i = 0; i < nodes.getLength(); i++) {
            if (nodes.item(i).getNodeType() != Node.ELEMENT_NODE) continue;
            Element e = (Element) nodes.item(i);
            switch (e.getTagName()) {
                case "sphere" -> {
                    Sphere s = new Sphere(vector(e, "x", "y", "z"), number(e, "radius", 1));
                    materials(s, e, 0.8, year.sphereKS(), 10, 0.3);
                    objects.add(s);
                }
                case "plane" -> {
                    Plane p = new Plane(vector(e, "x", "y", "z"), vector(e, "nx", "ny", "nz").normalised());
                    double[] m = year.plane();
                    materials(p, e, m[0], m[1], m[2], m[3]);
                    objects.add(p);
                }
                case "point-light" -> lights.add(new PointLight(vector(e, "x", "y", "z"),
                        colour(e.getAttribute("colour")), number(e, "intensity", 100)));
                case "ambient-light" -> {
                    ambient = colour(e.getAttribute("colour"));
                    if (year.ambientIntensity()) ambient = ambient.scale(number(e, "intensity", 1));
                }
                default -> { }
            }
        }
    }

    Hit closest(Ray ray) {
        Hit best = null;
        for (SceneObject o : objects) {
            Double d = o.intersectionWith(ray);
            if (d != null && (best == null || d < best.distance())) best = new Hit(o, d);
        }
        return best;
    }

    ColorRGB illuminate(SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB C = object.colour;
        // The skeleton's TODO: every object flat in its own colour.
        if (bug("shading-missing")) return C;
        ColorRGB colour = bug("no-ambient") ? new ColorRGB(0, 0, 0) : ambient.scale(C);
        boolean fromOrigin = year.viewFromRayOrigin() && !bug("view-to-camera");
        Vector3 V = bug("view-flipped") ? P.normalised()
                : fromOrigin ? O.subtract(P).normalised() : P.negated().normalised();
        List<PointLight> used = bug("first-light-only") ? lights.subList(0, Math.min(1, lights.size())) : lights;
        for (PointLight light : used) {
            Vector3 toLight = light.position().subtract(P);
            double d = toLight.magnitude();
            ColorRGB I = light.getIlluminationAt(d);
            Vector3 L = bug("light-unnormalised") ? toLight : toLight.normalised();
            double NdotL = N.dot(L);
            if (year.gate() && !bug("no-gate") && NdotL < 0) continue;
            Vector3 R = year.reflectUnclamped() ? N.scale(2 * NdotL).subtract(L)
                    : N.scale(2 * Math.max(0, NdotL)).subtract(L);
            ColorRGB diffuse = bug("diffuse-no-colour") ? I.scale(object.kD).scale(Math.max(0, NdotL))
                    : C.scale(I).scale(object.kD).scale(Math.max(0, NdotL));
            double RdotV = bug("rv-unclamped") ? R.dot(V) : Math.max(0, R.dot(V));
            double phong = Math.pow(RdotV, object.alphaS);
            ColorRGB specular = year.lightColouredSpecular() && !bug("specular-white")
                    ? light.colour().scale(I).scale(object.kS).scale(phong)
                    : I.scale(object.kS).scale(phong);
            if (bug("specular-object-colour")) specular = specular.scale(C);
            boolean alongN = bug("shadow-bias-along-n") || year.shadowAlongN() && !bug("shadow-bias-along-l");
            Vector3 origin = bug("no-shadow-bias") ? P : P.add((alongN ? N : L).scale(EPSILON));
            boolean inShadow = false;
            if (SOFT_SHADOWS) {
                // Tick 1*: ten shadow rays towards random points of a sphere around the light.
                int lit = 0;
                for (int k = 0; k < 10; k++) {
                    Vector3 jitter = new Vector3(Math.random() - 0.5, Math.random() - 0.5, Math.random() - 0.5).scale(0.4);
                    Vector3 to = light.position().add(jitter).subtract(P);
                    Hit blocker = closest(new Ray(origin, to.normalised()));
                    if (blocker == null || blocker.distance() >= to.magnitude()) lit++;
                }
                diffuse = diffuse.scale(lit / 10.0);
                specular = specular.scale(lit / 10.0);
            } else if (!bug("no-shadows")) {
                Hit blocker = closest(new Ray(origin, L));
                inShadow = blocker != null && (bug("shadow-any-hit") || blocker.distance() < d);
            }
            if (!inShadow) {
                ColorRGB base = bug("last-light-wins") ? (bug("no-ambient") ? new ColorRGB(0, 0, 0) : ambient.scale(C)) : colour;
                colour = base.add(diffuse).add(specular);
            }
        }
        return colour;
    }

    ColorRGB trace(Ray ray, int bouncesLeft) {
        Hit hit = closest(ray);
        // A student writing 2016-17's grey in a later year.
        double bg = bug("background-changed") ? 0.1 : year.background();
        if (hit == null) return new ColorRGB(bg, bg, bg);
        SceneObject o = hit.object();
        Vector3 P = ray.evaluateAt(hit.distance());
        Vector3 N = o.getNormalAt(P);
        ColorRGB direct = illuminate(o, P, N, ray.origin());
        // The skeleton's trace has no reflection code yet.
        if (bug("reflection-ignored")) return direct;
        if (bouncesLeft <= 0 || o.reflectivity == 0) return direct;
        Vector3 toEye = ray.direction().negated();
        Vector3 R = bug("reflection-wrong-sign")
                ? N.scale(2 * N.dot(ray.direction())).subtract(ray.direction()).normalised()
                : N.scale(2 * N.dot(toEye)).subtract(toEye).normalised();
        // The handout's words: "as for the shadow ray", i.e. along N.
        Vector3 start = bug("no-reflection-bias") ? P
                : bug("reflection-bias-along-n") ? P.add(N.scale(EPSILON)) : P.add(R.scale(EPSILON));
        ColorRGB reflected = trace(new Ray(start, R), bouncesLeft - 1);
        if (bug("reflection-unweighted")) return direct.add(reflected.scale(o.reflectivity));
        return direct.scale(1 - o.reflectivity).add(reflected.scale(o.reflectivity));
    }

    static double toneMap(double v) {
        double p = Math.pow(v, 1.3);
        double t = p * (1 / (p + Math.pow(0.5 / 2, 1.3)));
        return Math.pow(t, 1 / 2.2);
    }

    static int toByte(double v) {
        boolean mapped = year.toneMapped() && !bug("tonemap-missing");
        double g = mapped ? toneMap(v) : v;
        if (mapped && bug("tonemap-twice")) g = toneMap(g);
        if (Double.isNaN(g)) return 0;
        return (int) (255 * Math.min(1, Math.max(0, g)));
    }

    public static void main(String[] args) throws Exception {
        year = new Year(System.getProperty("course", "2021-22"));
        String bugs = System.getProperty("bug", "");
        if (!bugs.isEmpty()) BUGS.addAll(java.util.Arrays.asList(bugs.split(",")));
        String input = "tick1.xml", output = "output.png";
        int bounces = 2;
        // The year's own size: 800x600 from 2021-22 (fixed then, 2023-24's default).
        int width = year.start >= 2021 ? 800 : 640, height = year.start >= 2021 ? 600 : 480;
        for (int i = 0; i + 1 < args.length; i += 2) {
            switch (args[i]) {
                case "-i", "--input" -> input = args[i + 1];
                case "-o", "--output" -> output = args[i + 1];
                case "-b", "--bounces" -> bounces = Integer.parseInt(args[i + 1]);
                case "-r", "--resolution" -> {
                    String[] wh = args[i + 1].split("x");
                    width = Integer.parseInt(wh[0]);
                    height = Integer.parseInt(wh[1]);
                }
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        System.out.println("Loading scene '" + input + "'");
        Tick1 scene = new Tick1();
        scene.load(new File(input));
        double w = 2 * Math.tan(Math.toRadians(45.0 / 2));
        double h = w / ((double) width / height);
        double xStep = w / width;
        double yStep = year.separateRowStep() ? h / height : xStep;
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        for (int y = 0; y < height; y++) {
            for (int x = 0; x < width; x++) {
                double xPos = (xStep - w) / 2 + x * xStep;
                double yPos = (yStep + h) / 2 - y * yStep;
                Ray ray = new Ray(new Vector3(0, 0, 0), new Vector3(xPos, yPos, 1).normalised());
                ColorRGB c = scene.trace(ray, bounces);
                image.setRGB(x, y, toByte(c.r()) << 16 | toByte(c.g()) << 8 | toByte(c.b()));
            }
            if (y % 10 == 0) System.out.println("Rendering row " + y);
        }
        ImageIO.write(image, "png", new File(output));
    }
}
