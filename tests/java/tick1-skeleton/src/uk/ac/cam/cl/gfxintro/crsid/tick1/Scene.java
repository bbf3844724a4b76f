package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.util.ArrayList;
import java.util.List;

/** The objects and lights. whitted's test skeleton (its own API, not the course's). */
public class Scene {
    private final List<SceneObject> objects = new ArrayList<>();
    private final List<PointLight> lights = new ArrayList<>();
    private ColorRGB ambient = new ColorRGB(1);

    public void addObject(SceneObject o) { objects.add(o); }
    public void addPointLight(PointLight l) { lights.add(l); }
    public List<PointLight> getPointLights() { return lights; }
    public ColorRGB getAmbientLighting() { return ambient; }
    public void setAmbientLight(ColorRGB c) { ambient = c; }

    /** The nearest hit of `ray`, the first object's on a tie. */
    public RaycastHit findClosestIntersection(Ray ray) {
        RaycastHit best = new RaycastHit();
        for (SceneObject o : objects) {
            RaycastHit hit = o.intersectionWith(ray);
            if (hit.getDistance() < best.getDistance()) best = hit;
        }
        return best;
    }
}
