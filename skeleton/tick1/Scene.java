package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.util.ArrayList;
import java.util.List;

/**
 * The objects and lights, in insertion order (whitted's clean-room skeleton). Objects cannot be
 * listed: shadow rays go through findClosestIntersection, as in the course.
 */
public class Scene {
    private final List<SceneObject> objects = new ArrayList<>();
    private final List<PointLight> pointLights = new ArrayList<>();
    private ColorRGB ambientLight = new ColorRGB(1);

    public void addObject(SceneObject object) {
        objects.add(object);
    }

    /**
     * Every object asked in insertion order; a hit is kept only when its distance is strictly
     * smaller than the best so far, and returned as the object gave it. Negative, zero and NaN
     * distances are not filtered, and a null from intersectionWith throws: students' code meets
     * exactly what it would meet in the course.
     */
    public RaycastHit findClosestIntersection(Ray ray) {
        RaycastHit closest = new RaycastHit();
        for (SceneObject object : objects) {
            RaycastHit hit = object.intersectionWith(ray);
            if (hit.getDistance() < closest.getDistance()) closest = hit;
        }
        return closest;
    }

    /** The ambient light (a colour; from 2019-20 the loader has scaled it by its intensity). */
    public ColorRGB getAmbientLighting() {
        return ambientLight;
    }

    /** Replaces the ambient light: the last one set wins. */
    public void setAmbientLight(ColorRGB ambientLight) {
        this.ambientLight = ambientLight;
    }

    /** The first point light; throws when there is none. */
    public PointLight getPointLight() {
        return pointLights.get(0);
    }

    /** The live list, not a copy. */
    public List<PointLight> getPointLights() {
        return pointLights;
    }

    public void addPointLight(PointLight light) {
        pointLights.add(light);
    }
}
