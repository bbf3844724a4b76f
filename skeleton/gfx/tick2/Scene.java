package gfx.tick2;

import java.util.ArrayList;
import java.util.List;

/** The objects and lights (whitted's clean-room skeleton: docs/grade.md). */
public class Scene {
    private final List<SceneObject> objects = new ArrayList<>();
    private final List<PointLight> pointLights = new ArrayList<>();
    private Vector3 ambientLight = new Vector3(1);

    public void addObject(SceneObject object) {
        objects.add(object);
    }

    /** The closest hit in file order; a later hit replaces it only if strictly nearer. */
    public RaycastHit findClosestIntersection(Ray ray) {
        RaycastHit closest = new RaycastHit();
        for (SceneObject object : objects) {
            RaycastHit hit = object.intersectionWith(ray);
            if (hit.getDistance() < closest.getDistance()) closest = hit;
        }
        return closest;
    }

    public Vector3 getAmbientLighting() {
        return ambientLight;
    }

    public void setAmbientLight(Vector3 ambientLight) {
        this.ambientLight = ambientLight;
    }

    /** The first point light (Tick 1's single light), or null when there is none. */
    public PointLight getPointLight() {
        return pointLights.isEmpty() ? null : pointLights.get(0);
    }

    public List<PointLight> getPointLights() {
        return pointLights;
    }

    public void addPointLight(PointLight light) {
        pointLights.add(light);
    }
}
