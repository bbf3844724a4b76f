package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.util.List;

/**
 * whitted's finished Tick 1 Renderer (written from the handout's method and docs/rendering.md,
 * never from the course's code), in the skeleton template's markers; ${YEAR} is the course's year,
 * whose rules it follows (the N.L gate from 2018-19, the shadow ray moved along N from 2020-21).
 * It completes a Tick 1* hand-in of BumpySphere.java alone (grade's finished.rs): the bump map
 * is then judged on a correct Tick 1, as the ticker sees it on the student's own. The tests'
 * students are this Tick 1 edited (tests/java/tick1-mistakes.txt).
 */
public class Renderer {
    private static final String YEAR = "${YEAR}";

    private int width, height, bounces;
    private final double EPSILON = 0.0001;
    private ColorRGB backgroundColor = new ColorRGB(0.1); //@T1
    private ColorRGB backgroundColor = new ColorRGB(0.001); //@T2+

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
        if (bouncesLeft == 0 || reflectivity == 0) {
            return directIllumination;
        }
        Vector3 R = ray.getDirection().scale(-1).reflectIn(N).normalised();
        ColorRGB reflectedIllumination = trace(scene, new Ray(P.add(R.scale(EPSILON)), R), bouncesLeft - 1);
        return directIllumination.scale(1.0 - reflectivity).add(reflectedIllumination.scale(reflectivity));
    }

    private ColorRGB illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB C_diff = object.getColour();
        double k_d = object.getPhong_kD();
        double k_s = object.getPhong_kS();
        double alpha = object.getPhong_alpha();
        ColorRGB colourToReturn = scene.getAmbientLighting().scale(C_diff);
        boolean gated = YEAR.compareTo("2018-19") >= 0;
        boolean shadowAlongN = YEAR.compareTo("2020-21") >= 0;
        List<PointLight> pointLights = scene.getPointLights();
        for (PointLight light : pointLights) {
            double distanceToLight = light.getPosition().subtract(P).magnitude();
            ColorRGB I = light.getIlluminationAt(distanceToLight);
            Vector3 L = light.getPosition().subtract(P).normalised();
            Vector3 V = O.subtract(P).normalised();
            double NdotL = N.dot(L);
            if (gated && NdotL < 0) continue;
            Vector3 R = L.reflectIn(N);
            ColorRGB diffuse = C_diff.scale(I).scale(k_d).scale(Math.max(0, NdotL));
            ColorRGB specular = light.getColour().scale(I).scale(k_s).scale(Math.pow(Math.max(0, R.dot(V)), alpha));
            Vector3 shadowOrigin = P.add((shadowAlongN ? N : L).scale(EPSILON));
            RaycastHit blocker = scene.findClosestIntersection(new Ray(shadowOrigin, L));
            boolean inShadow = blocker.getObjectHit() != null && blocker.getDistance() < distanceToLight;
            if (!inShadow) {
                colourToReturn = colourToReturn.add(diffuse).add(specular);
            }
        }
        return colourToReturn;
    }

    //@if T2+
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
    //@end

    public BufferedImage render(Scene scene) {
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        Camera camera = new Camera(width, height);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                ColorRGB linearRGB = trace(scene, camera.castRay(x, y), bounces);
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
