package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * A student's Renderer.java of 2021-22, written from whitted's docs/courses.md. The tests bake
 * catalogue mistakes into it by replacing the one property read below with a literal list.
 */
public class Renderer {
    private static final Set<String> BUGS = new HashSet<>(Arrays.asList(System.getProperty("bug", "").split(",")));

    static boolean bug(String id) {
        return BUGS.contains(id);
    }

    private static final double EPSILON = 0.0001;
    private final int width, height, bounces;

    public Renderer(int width, int height, int bounces) {
        this.width = width;
        this.height = height;
        this.bounces = bounces;
    }

    protected ColorRGB trace(Scene scene, Ray ray, int bouncesLeft) {
        RaycastHit hit = scene.findClosestIntersection(ray);
        SceneObject object = hit.getObjectHit();
        if (object == null) return new ColorRGB(bug("background-changed") ? 0.1 : 0.001);
        Vector3 P = hit.getLocation();
        Vector3 N = hit.getNormal();
        ColorRGB direct = illuminate(scene, object, P, N, ray.getOrigin());
        if (bug("reflection-ignored")) return direct;
        double r = object.getReflectivity();
        if (bouncesLeft <= 0 || r == 0) return direct;
        Vector3 toEye = ray.getDirection().negated();
        Vector3 R = N.scale(2 * N.dot(toEye)).subtract(toEye).normalised();
        Vector3 start = bug("reflection-bias-along-n") ? P.add(N.scale(EPSILON)) : P.add(R.scale(EPSILON));
        ColorRGB reflected = trace(scene, new Ray(start, R), bouncesLeft - 1);
        return direct.scale(1 - r).add(reflected.scale(r));
    }

    private ColorRGB illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB C = object.getColour();
        if (bug("shading-missing")) return C;
        ColorRGB colour = bug("no-ambient") ? new ColorRGB(0) : scene.getAmbientLighting().scale(C);
        Vector3 V = bug("view-to-camera") ? P.negated().normalised() : O.subtract(P).normalised();
        List<PointLight> lights = scene.getPointLights();
        for (PointLight light : lights) {
            Vector3 toLight = light.getPosition().subtract(P);
            double d = toLight.magnitude();
            ColorRGB I = light.getIlluminationAt(d);
            Vector3 L = toLight.normalised();
            double NdotL = N.dot(L);
            if (!bug("no-gate") && NdotL < 0) continue;
            Vector3 R = N.scale(2 * NdotL).subtract(L);
            ColorRGB diffuse = C.scale(I).scale(object.getPhong_kD()).scale(Math.max(0, NdotL));
            double phong = Math.pow(Math.max(0, R.dot(V)), object.getPhong_alpha());
            ColorRGB specular = bug("specular-white")
                    ? I.scale(object.getPhong_kS()).scale(phong)
                    : light.getColour().scale(I).scale(object.getPhong_kS()).scale(phong);
            boolean inShadow = false;
            if (bug("star-soft-shadows")) {
                // Tick 1*: ten shadow rays towards random points around the light.
                int lit = 0;
                for (int k = 0; k < 10; k++) {
                    Vector3 jitter = new Vector3(Math.random() - 0.5, Math.random() - 0.5, Math.random() - 0.5).scale(0.4);
                    Vector3 to = light.getPosition().add(jitter).subtract(P);
                    RaycastHit blocker = scene.findClosestIntersection(new Ray(P.add(N.scale(EPSILON)), to.normalised()));
                    if (blocker.getObjectHit() == null || blocker.getDistance() >= to.magnitude()) lit++;
                }
                diffuse = diffuse.scale(lit / 10.0);
                specular = specular.scale(lit / 10.0);
            } else if (!bug("no-shadows")) {
                Vector3 along = bug("shadow-bias-along-l") ? L : N;
                RaycastHit blocker = scene.findClosestIntersection(new Ray(P.add(along.scale(EPSILON)), L));
                inShadow = blocker.getObjectHit() != null && blocker.getDistance() < d;
            }
            if (!inShadow) colour = colour.add(diffuse).add(specular);
        }
        return colour;
    }

    private static double tonemap(double v) {
        double p = Math.pow(v, 1.3);
        double t = p * (1 / (p + Math.pow(0.5 / 2, 1.3)));
        return Math.pow(t, 1 / 2.2);
    }

    private static int toByte(double v) {
        double g = bug("tonemap-missing") ? v : tonemap(v);
        if (Double.isNaN(g)) return 0;
        return (int) (255 * Math.min(1, Math.max(0, g)));
    }

    public BufferedImage render(Scene scene) {
        Camera camera = new Camera(width, height);
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        for (int y = 0; y < height; y++) {
            for (int x = 0; x < width; x++) {
                ColorRGB c = trace(scene, camera.castRay(x, y), bounces);
                image.setRGB(x, y, toByte(c.r) << 16 | toByte(c.g) << 8 | toByte(c.b));
            }
            if (y % 10 == 0) System.out.println("Rendering row " + y);
        }
        return image;
    }
}
