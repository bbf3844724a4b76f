package uk.ac.cam.cl.gfxintro.crsid.tick1star;

import java.awt.image.BufferedImage;
import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Random;
import java.util.Set;

/**
 * A student's Tick 1* Renderer.java (option 2, distributed ray tracing): whitted's own, written
 * from docs/courses.md ("Tick 1*") on top of the Tick 1 fixture's renderer
 * (tests/java/tick1-submission), never from the course's code. It compiles against whitted's
 * clean-room skeleton of 2020-21 on (the markers of skeleton/tick1/README.md), copied into the
 * package tick1star as the handout has students copy their Tick 1.
 *
 * The ways students write it are system properties, so that one program serves every test:
 * -Dsoft=course|uniform-sphere|light-surface|light-size|not-averaged|specular-not-scaled|none,
 * -Ddof=course|aperture-full-side|focal-distance|not-averaged|none ("none": the option not
 * done, the plain Tick 1 shadow or pinhole); each variant is written as a student writes it
 * (light-surface: the course's point normalised; not-averaged: the shadow rays' count used
 * as the scale; specular-not-scaled: the scale applied to the diffuse term only;
 * focal-distance: ray.evaluateAt(DOF_FOCAL_PLANE) as the focal point); -Dseed=N draws from a seeded java.util.Random
 * instead of the course's Math.random (reproducible tests; unseeded by default, as the course);
 * -Drays=F scales both ray counts by F (10 shadow rays, 50 lens rays; at least one each), which
 * changes the distribution: a check must be told the counts.
 */
public class Renderer {
    private static final String SOFT = System.getProperty("soft", "course");
    private static final String DOF = System.getProperty("dof", "course");
    private static final double RAYS = Double.parseDouble(System.getProperty("rays", "1"));
    private static final Random SEEDED = System.getProperty("seed") == null
            ? null : new Random(Long.parseLong(System.getProperty("seed")));

    /** The Tick 1 fixture's mistakes (-Dbug=id,id), which its Sphere and Plane read here. */
    private static final Set<String> BUGS = new HashSet<>(Arrays.asList(System.getProperty("bug", "").split(",")));

    static boolean bug(String id) {
        return BUGS.contains(id);
    }

    private int width, height, bounces;
    private final double EPSILON = 0.0001;
    private ColorRGB backgroundColor = new ColorRGB(0.001);

    // Tick 1*'s constants, as the handout gives them.
    private final int SHADOW_RAY_COUNT = Math.max(1, (int) Math.round(10 * RAYS));
    private final double LIGHT_SIZE = SOFT.equals("light-size") ? 0.2 : 0.4;
    private final int DOF_RAY_COUNT = Math.max(1, (int) Math.round(50 * RAYS));
    private final double DOF_FOCAL_PLANE = 3.51805;
    private final double DOF_AMOUNT = 0.2;

    public Renderer(int width, int height, int bounces) {
        this.width = width;
        this.height = height;
        this.bounces = bounces;
    }

    /** Uniform in [0, 1): the seeded generator's when -Dseed is given, else Math.random. */
    static double random() {
        return SEEDED == null ? Math.random() : SEEDED.nextDouble();
    }

    /** A point of the light's sphere of jitter, drawn as the variant draws it. */
    private Vector3 jitter() {
        switch (SOFT) {
            case "uniform-sphere": {
                // Uniform in volume: rejection from the cube, as a careful student writes it.
                while (true) {
                    Vector3 p = new Vector3(2 * random() - 1, 2 * random() - 1, 2 * random() - 1);
                    if (p.dot(p) <= 1) return p;
                }
            }
            case "light-surface":
                // "The light is a sphere": its surface, the random point pushed out to radius one.
                return insideUnitSphere().normalised();
            default:
                return insideUnitSphere();
        }
    }

    /** The course's Vector3.randomInsideUnitSphere, its draws from the seeded generator when -Dseed is given. */
    private static Vector3 insideUnitSphere() {
        if (SEEDED == null) return Vector3.randomInsideUnitSphere();
        double r = random();
        double theta = random() * Math.PI;
        double phi = random() * 2 * Math.PI;
        return new Vector3(r * Math.sin(theta) * Math.cos(phi), r * Math.sin(theta) * Math.sin(phi), r * Math.cos(theta));
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
        if (bouncesLeft == 0 || reflectivity == 0) {
            return directIllumination;
        } else {
            Vector3 R = ray.getDirection().scale(-1).reflectIn(N).normalised();
            ColorRGB reflectedIllumination = trace(scene, new Ray(P.add(R.scale(EPSILON)), R), bouncesLeft - 1);
            directIllumination = directIllumination.scale(1.0 - reflectivity);
            reflectedIllumination = reflectedIllumination.scale(reflectivity);
            return directIllumination.add(reflectedIllumination);
        }
    }

    /** The fraction of SHADOW_RAY_COUNT rays from P to points around the light that nothing blocks. */
    private double visible(Scene scene, Vector3 P, Vector3 N, PointLight light) {
        int lit = 0;
        for (int k = 0; k < SHADOW_RAY_COUNT; k++) {
            Vector3 to = light.getPosition().add(jitter().scale(LIGHT_SIZE)).subtract(P);
            RaycastHit blocker = scene.findClosestIntersection(new Ray(P.add(N.scale(EPSILON)), to.normalised()));
            if (blocker.getObjectHit() == null || blocker.getDistance() > to.magnitude()) lit++;
        }
        return SOFT.equals("not-averaged") ? lit : lit / (double) SHADOW_RAY_COUNT;
    }

    private ColorRGB illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB I_a = scene.getAmbientLighting();
        ColorRGB C_diff = object.getColour();
        double k_d = object.getPhong_kD();
        double k_s = object.getPhong_kS();
        double alpha = object.getPhong_alpha();
        ColorRGB colourToReturn = I_a.scale(C_diff);
        List<PointLight> pointLights = scene.getPointLights();
        for (PointLight light : pointLights) {
            double distanceToLight = light.getPosition().subtract(P).magnitude();
            ColorRGB C_spec = light.getColour();
            ColorRGB I = light.getIlluminationAt(distanceToLight);
            Vector3 L = light.getPosition().subtract(P).normalised();
            Vector3 V = O.subtract(P).normalised();
            double NdotL = N.dot(L);
            if (NdotL < 0) continue;
            Vector3 R = L.reflectIn(N);
            ColorRGB diffuse = C_diff.scale(I).scale(k_d).scale(Math.max(0, NdotL));
            ColorRGB specular = C_spec.scale(I).scale(k_s).scale(Math.pow(Math.max(0, R.dot(V)), alpha));
            if (SOFT.equals("none")) {
                RaycastHit blocker = scene.findClosestIntersection(new Ray(P.add(N.scale(EPSILON)), L));
                if (blocker.getObjectHit() != null && blocker.getDistance() < distanceToLight) continue;
            } else {
                double fraction = visible(scene, P, N, light);
                diffuse = diffuse.scale(fraction);
                if (!SOFT.equals("specular-not-scaled")) specular = specular.scale(fraction);
            }
            colourToReturn = colourToReturn.add(diffuse).add(specular);
        }
        return colourToReturn;
    }

    /* The course's sigmoid and gamma, built from the colour's own power, add and inv. */
    public ColorRGB tonemap(ColorRGB linearRGB) {
        double invGamma = 1. / 2.2;
        double a = 2;
        double b = 1.3;
        double lum_white = 0.5;
        ColorRGB powRGB = linearRGB.power(b);
        ColorRGB displayRGB = powRGB.scale(powRGB.add(Math.pow(lum_white / a, b)).inv());
        return displayRGB.power(invGamma);
    }

    /** Depth of field: DOF_RAY_COUNT rays from random points of the square aperture through the
     *  point where the pinhole ray meets the focal plane, their colours averaged. */
    private ColorRGB throughLens(Scene scene, Ray ray) {
        // Where the ray meets the focal plane z = DOF_FOCAL_PLANE; "focal-distance": the
        // constant taken as a distance along the ray.
        Vector3 focus = DOF.equals("focal-distance")
                ? ray.evaluateAt(DOF_FOCAL_PLANE)
                : ray.evaluateAt(DOF_FOCAL_PLANE / ray.getDirection().z);
        double half = DOF.equals("aperture-full-side") ? DOF_AMOUNT : DOF_AMOUNT / 2;
        ColorRGB sum = new ColorRGB(0);
        for (int k = 0; k < DOF_RAY_COUNT; k++) {
            Vector3 from = new Vector3((2 * random() - 1) * half, (2 * random() - 1) * half, 0);
            sum = sum.add(trace(scene, new Ray(from, focus.subtract(from).normalised()), bounces));
        }
        return DOF.equals("not-averaged") ? sum : sum.scale(1.0 / DOF_RAY_COUNT);
    }

    public BufferedImage render(Scene scene) {
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        Camera camera = new Camera(width, height);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                Ray ray = camera.castRay(x, y);
                ColorRGB linearRGB = DOF.equals("none") ? trace(scene, ray, bounces) : throughLens(scene, ray);
                image.setRGB(x, y, tonemap(linearRGB).toRGB());
            }
            if (y % 10 == 9 || y == height - 1) {
                System.out.println(String.format("%.2f", 100 * y / (float) (height - 1)) + "% completed");
            }
        }
        return image;
    }
}
