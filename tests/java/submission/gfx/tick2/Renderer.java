package gfx.tick2;

import java.awt.image.BufferedImage;
import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * A student's Renderer.java for the tests of `whitted grade` (see Plane.java): the mistakes of
 * docs/check.md that live in this file, switched on with -Dbug=id,id. `sphere-far-root` lives in
 * the skeleton's Sphere, which a submission cannot replace, so it is not here.
 */
public class Renderer {
    private static final double EPSILON = 0.0001;
    private static final Set<String> BUGS = new HashSet<>(Arrays.asList(System.getProperty("bug", "").split(",")));

    static boolean bug(String id) {
        return BUGS.contains(id);
    }

    private final Vector3 backgroundColor = new Vector3(0.1);
    private final int width, height, bounces;

    public Renderer(int width, int height, int bounces) {
        this.width = width;
        this.height = height;
        this.bounces = bounces + (bug("bounces-plus-one") ? 1 : 0) - (bug("bounces-minus-one") ? 1 : 0);
    }

    protected Vector3 trace(Scene scene, Ray ray, int bouncesLeft) {
        RaycastHit closestHit = scene.findClosestIntersection(ray);
        SceneObject object = closestHit.getObjectHit();
        if (object == null) return backgroundColor;
        Vector3 P = closestHit.getLocation();
        Vector3 N = closestHit.getNormal();
        Vector3 direct = illuminate(scene, object, P, N, ray);
        // Reflection not written at all: the direct illumination as it is.
        if (bug("reflection-ignored")) return direct;
        double reflectivity = object.getReflectivity();
        if (bouncesLeft <= 0 || reflectivity == 0) return direct;
        if (bug("reflection-missing")) {
            // The skeleton's TODO, left as it is: reflectedIllumination stays black.
            Vector3 reflectedIllumination = new Vector3(0);
            return direct.scale(1 - reflectivity).add(reflectedIllumination.scale(reflectivity));
        }
        Vector3 D = ray.getDirection();
        Vector3 R = bug("reflection-wrong-sign") ? D.reflectIn(N).normalised() : D.scale(-1).reflectIn(N).normalised();
        Vector3 origin = bug("no-reflection-bias") ? P : P.add(R.scale(EPSILON));
        Vector3 reflected = trace(scene, new Ray(origin, R), bouncesLeft - 1);
        if (bug("reflection-unweighted")) return direct.add(reflected.scale(reflectivity));
        return direct.scale(1 - reflectivity).add(reflected.scale(reflectivity));
    }

    private Vector3 illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N) {
        return illuminate(scene, object, P, N, null);
    }

    private Vector3 illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Ray ray) {
        Vector3 C = object.getColour();
        double kD = object.getPhong_kD(), kS = object.getPhong_kS(), n = object.getPhong_n();
        Vector3 ambient = bug("no-ambient") ? new Vector3(0) : scene.getAmbientLighting().scale(C);
        Vector3 colour = ambient;
        Vector3 V = bug("view-flipped") ? P.normalised()
                : bug("view-from-ray-origin") && ray != null ? ray.getOrigin().subtract(P).normalised()
                : P.scale(-1).normalised();
        List<PointLight> lights = scene.getPointLights();
        if (bug("first-light-only") && !lights.isEmpty()) lights = lights.subList(0, 1);
        // The skeleton's TODO, left as it is: the ambient term only.
        if (bug("lights-missing")) lights = List.of();
        for (PointLight light : lights) {
            Vector3 toLight = light.getPosition().subtract(P);
            double d = toLight.magnitude();
            Vector3 I = bug("no-falloff") ? light.getColour().scale(light.getIntensity()) : light.getIlluminationAt(d);
            Vector3 L = bug("light-unnormalised") ? toLight : toLight.normalised();
            double NdotL = N.dot(L);
            Vector3 R = bug("reflect-unclamped") ? N.scale(2 * NdotL).subtract(L) : N.scale(2 * Math.max(0, NdotL)).subtract(L);
            Vector3 diffuse = bug("diffuse-no-colour") ? I.scale(kD).scale(Math.max(0, NdotL))
                    : C.scale(I).scale(kD).scale(Math.max(0, NdotL));
            // Not in the catalogue: for the tests of the term fit.
            double exponent = bug("exponent-doubled") ? 2 * n : n;
            double RdotV = bug("rv-unclamped") ? R.dot(V) : Math.max(0, R.dot(V));
            Vector3 specular = I.scale(kS).scale(Math.pow(RdotV, exponent));
            if (bug("specular-gated") && !(NdotL > 0)) specular = new Vector3(0);
            if (bug("specular-object-colour")) specular = specular.scale(C);
            boolean inShadow = false;
            if (!bug("no-shadows")) {
                Vector3 origin = bug("no-shadow-bias") ? P : P.add(L.scale(EPSILON));
                RaycastHit blocker = scene.findClosestIntersection(new Ray(origin, L));
                inShadow = blocker.getObjectHit() != null && (bug("shadow-any-hit") || blocker.getDistance() < d);
            }
            if (!inShadow) {
                Vector3 base = bug("last-light-wins") ? ambient : colour;
                colour = base.add(diffuse).add(specular);
            }
        }
        return colour;
    }

    public BufferedImage render(Scene scene) {
        Camera camera = new Camera(width, height);
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        for (int y = 0; y < height; y++) {
            for (int x = 0; x < width; x++) {
                image.setRGB(x, y, trace(scene, camera.castRay(x, y), bounces).toRGB());
            }
        }
        return image;
    }
}
