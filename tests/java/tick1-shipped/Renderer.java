package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.util.List;

/**
 * Renderer.java as a student finds it in the course's zip (whitted's own, from docs/grade.md):
 * trace shades the closest hit with no reflection code, and illuminate reads the ambient light,
 * the object's colour and its Phong numbers and walks the lights, but a placeholder returns the
 * object's flat colour.
 */
public class Renderer {
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
        // TODO: reflection
        return directIllumination;
    }

    private ColorRGB illuminate(Scene scene, SceneObject object, Vector3 P, Vector3 N, Vector3 O) {
        ColorRGB I_a = scene.getAmbientLighting();
        ColorRGB C_diff = object.getColour();
        double k_d = object.getPhong_kD();
        double k_s = object.getPhong_kS();
        double alpha = object.getPhong_alpha();
        ColorRGB colourToReturn = new ColorRGB(0);
        List<PointLight> pointLights = scene.getPointLights();
        for (int i = 0; i < pointLights.size(); i++) {
            PointLight light = pointLights.get(i);
            double distanceToLight = light.getPosition().subtract(P).magnitude();
            ColorRGB C_spec = light.getColour();
            ColorRGB I = light.getIlluminationAt(distanceToLight);
            // TODO: diffuse and specular terms, and shadows
        }
        // TODO: remove this placeholder
        colourToReturn = C_diff;
        return colourToReturn;
    }

    //@if T2+
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
                Ray ray = camera.castRay(x, y);
                ColorRGB linearRGB = trace(scene, ray, bounces);
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
