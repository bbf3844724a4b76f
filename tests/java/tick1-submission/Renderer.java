package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * A student's Renderer.java of any year from 2017-18 (whitted's own, written from docs/courses.md
 * and docs/grade.md in the handout's shape; the skeleton template's markers choose the year's
 * API). The tests replace YEAR with the year (its rules: the gate, the shadow ray's bias) and bake
 * catalogue mistakes in by replacing the one property read below with a literal list.
 */
public class Renderer {
    private static final String YEAR = System.getProperty("year", "2021-22");
    private static final Set<String> BUGS = new HashSet<>(Arrays.asList(System.getProperty("bug", "").split(",")));

    static boolean bug(String id) {
        return BUGS.contains(id);
    }

    private int width, height, bounces;
    private final double EPSILON = 0.0001;
    private ColorRGB backgroundColor = new ColorRGB(bug("background-changed") ? 0.01 : 0.1); //@T1
    private ColorRGB backgroundColor = new ColorRGB(bug("background-changed") ? 0.1 : 0.001); //@T2+

    public Renderer(int width, int height, int bounces) {
        this.width = width;
        this.height = height;
        this.bounces = bounces;
    }

    protected ColorRGB trace(Scene scene, Ray ray, int bouncesLeft) {
        RaycastHit closestHit = scene.findClosestIntersection(ray);
        SceneObject object = closestHit.getObjectHit();
        if (object == null) {
            return backgroundColor;
        }
        Vector3 P = closestHit.getLocation();
        Vector3 N = closestHit.getNormal();
        Vector3 O = ray.getOrigin();
        ColorRGB directIllumination = illuminate(scene, object, P, N, O);
        double reflectivity = object.getReflectivity();
        if (bug("reflection-ignored") || bouncesLeft == 0 || reflectivity == 0) {
            return directIllumination;
        } else {
            Vector3 R = ray.getDirection().scale(-1).reflectIn(N).normalised();
            Vector3 start = bug("reflection-bias-along-n") ? P.add(N.scale(EPSILON)) : P.add(R.scale(EPSILON));
            ColorRGB reflectedIllumination = trace(scene, new Ray(start, R), bouncesLeft - 1);
            directIllumination = directIllumination.scale(1.0 - reflectivity);
            reflectedIllumination = reflectedIllumination.scale(reflectivity);
            return directIllumination.add(reflectedIllumination);
        }
    }

    private ColorRGB illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB I_a = scene.getAmbientLighting();
        ColorRGB C_diff = object.getColour();
        if (bug("shading-missing")) return C_diff;
        double k_d = object.getPhong_kD();
        double k_s = object.getPhong_kS();
        double alpha = object.getPhong_alpha();
        ColorRGB colourToReturn = bug("no-ambient") ? new ColorRGB(0) : I_a.scale(C_diff);
        boolean gated = YEAR.compareTo("2018-19") >= 0;
        boolean shadowAlongN = YEAR.compareTo("2020-21") >= 0;
        List<PointLight> pointLights = scene.getPointLights();
        for (int i = 0; i < pointLights.size(); i++) {
            PointLight light = pointLights.get(i);
            double distanceToLight = light.getPosition().subtract(P).magnitude();
            ColorRGB C_spec = light.getColour();
            ColorRGB I = light.getIlluminationAt(distanceToLight);
            Vector3 L = light.getPosition().subtract(P).normalised();
            Vector3 V = bug("view-to-camera") ? P.scale(-1).normalised() : O.subtract(P).normalised();
            double NdotL = N.dot(L);
            if ((gated ^ bug("no-gate")) && NdotL < 0) continue;
            Vector3 R = L.reflectIn(N);
            ColorRGB diffuse = C_diff.scale(I).scale(k_d).scale(Math.max(0, NdotL));
            double phong = Math.pow(Math.max(0, R.dot(V)), alpha);
            ColorRGB specular = bug("specular-white")
                    ? I.scale(k_s).scale(phong)
                    : C_spec.scale(I).scale(k_s).scale(phong);
            boolean inShadow = false;
            if (bug("star-soft-shadows")) {
                // Tick 1*: ten shadow rays towards random points around the light.
                int lit = 0;
                for (int k = 0; k < 10; k++) {
                    Vector3 to = light.getPosition().add(Vector3.randomInsideUnitSphere().scale(0.4)).subtract(P);
                    RaycastHit blocker = scene.findClosestIntersection(new Ray(P.add(N.scale(EPSILON)), to.normalised()));
                    if (blocker.getObjectHit() == null || blocker.getDistance() >= to.magnitude()) lit++;
                }
                diffuse = diffuse.scale(lit / 10.0);
                specular = specular.scale(lit / 10.0);
            } else if (!bug("no-shadows")) {
                boolean alongN = shadowAlongN ^ bug(shadowAlongN ? "shadow-bias-along-l" : "shadow-bias-along-n");
                Vector3 shadowOrigin = P.add((alongN ? N : L).scale(EPSILON));
                RaycastHit blocker = scene.findClosestIntersection(new Ray(shadowOrigin, L));
                inShadow = blocker.getObjectHit() != null && (bug("shadow-any-hit") || blocker.getDistance() < distanceToLight);
            }
            if (!inShadow) {
                colourToReturn = colourToReturn.add(diffuse).add(specular);
            }
        }
        return colourToReturn;
    }

    //@if T2+
    /* The course's sigmoid and gamma, built from the colour's own power, add and inv. */
    public ColorRGB tonemap(ColorRGB linearRGB) {
        if (bug("tonemap-missing")) return linearRGB;
        double invGamma = 1. / 2.2;
        double a = 2;
        double b = 1.3;
        double lum_white = 0.5;
        ColorRGB powRGB = linearRGB.power(b);
        ColorRGB displayRGB = powRGB.scale(powRGB.add(Math.pow(lum_white / a, b)).inv());
        return displayRGB.power(invGamma);
    }
    //@end

    /* Tick 1*: 50 rays from random points of a square aperture of side 0.2, through the point
       where the pinhole ray meets the focal plane z = 3.51805, averaged. */
    private ColorRGB throughLens(Scene scene, Ray ray) {
        Vector3 focus = ray.evaluateAt(3.51805 / ray.getDirection().z);
        ColorRGB sum = new ColorRGB(0);
        for (int k = 0; k < 50; k++) {
            Vector3 from = new Vector3((2 * Math.random() - 1) * 0.1, (2 * Math.random() - 1) * 0.1, 0);
            sum = sum.add(trace(scene, new Ray(from, focus.subtract(from).normalised()), bounces));
        }
        return sum.scale(1.0 / 50);
    }

    public BufferedImage render(Scene scene) {
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        Camera camera = new Camera(width, height);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                Ray ray = camera.castRay(x, y);
                ColorRGB linearRGB = bug("star-depth-of-field") ? throughLens(scene, ray) : trace(scene, ray, bounces);
                image.setRGB(x, y, linearRGB.toRGB()); //@T1
                image.setRGB(x, y, tonemap(linearRGB).toRGB()); //@T2+
            }
            if (y % 10 == 9 || y == height - 1) {
                System.out.println(String.format("%.2f", 100 * y / (float) (height - 1)) + "% completed");
            }
        }
        return image;
    }
}
