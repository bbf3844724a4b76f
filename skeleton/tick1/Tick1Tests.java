package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.lang.reflect.Method;

/**
 * Unit tests a student runs against their own Sphere, Plane and Renderer (whitted's clean-room
 * skeleton; its tests are whitted's own, not the course's). Compiled with every submission because
 * it pins what the course's own tests call: the three-argument Sphere and Plane constructors,
 * intersectionWith, the material getters, Renderer(int, int, int), trace(Scene, Ray, int) visible
 * in the package and returning ColorRGB, and illuminate(Scene, SceneObject, Vector3, Vector3,
 * Vector3) declared in Renderer (found by reflection, any visibility). Part 1 by default; with
 * -a or --all part 2 as well; exit status 1 when a test fails.
 */
public class Tick1Tests {
    private int failed = 0;

    public Tick1Tests() {
    }

    private void expect(boolean ok, String what) {
        System.out.println((ok ? "PASS " : "FAIL ") + what);
        if (!ok) failed++;
    }

    private static boolean near(double a, double b) {
        return Math.abs(a - b) < 1e-9;
    }

    public boolean test(boolean all) {
        Ray alongZ = new Ray(new Vector3(0), new Vector3(0, 0, 1));
        Sphere sphere = new Sphere(new Vector3(0, 0, 5), 1, new ColorRGB(1, 0, 0));
        RaycastHit hit = sphere.intersectionWith(alongZ);
        expect(hit.getObjectHit() == sphere && near(hit.getDistance(), 4), "sphere intersection: the near root");
        expect(hit.getLocation() != null && near(hit.getLocation().z, 4), "sphere intersection: the location");
        expect(hit.getNormal() != null && near(hit.getNormal().z, -1), "sphere intersection: the normal");
        Ray away = new Ray(new Vector3(0), new Vector3(0, 0, -1));
        expect(sphere.intersectionWith(away).getObjectHit() == null, "sphere intersection: a sphere behind is missed");
        Ray inside = new Ray(new Vector3(0, 0, 5), new Vector3(0, 0, 1));
        expect(near(sphere.intersectionWith(inside).getDistance(), 1), "sphere intersection: from inside, the far root");
        expect(sphere.getPhong_kD() > 0 && sphere.getPhong_kS() >= 0 && sphere.getReflectivity() >= 0, "sphere material");
        boolean declared = false;
        for (Method m : Renderer.class.getDeclaredMethods()) {
            Class<?>[] p = m.getParameterTypes();
            declared |= m.getName().equals("illuminate") && p.length == 5 && p[0] == Scene.class
                    && p[1] == SceneObject.class && p[2] == Vector3.class && p[3] == Vector3.class && p[4] == Vector3.class;
        }
        expect(declared, "Renderer declares illuminate(Scene, SceneObject, Vector3, Vector3, Vector3)");
        if (all) {
            Plane floor = new Plane(new Vector3(0, -1, 0), new Vector3(0, 1, 0), new ColorRGB(0.5));
            Ray down = new Ray(new Vector3(0), new Vector3(0, -1, 0));
            expect(near(floor.intersectionWith(down).getDistance(), 1), "plane intersection");
            expect(floor.intersectionWith(alongZ).getObjectHit() == null, "plane intersection: a parallel ray misses");
            Ray up = new Ray(new Vector3(0, 1, 0), new Vector3(0, 1, 0));
            expect(floor.intersectionWith(up).getObjectHit() == null, "plane intersection: a plane behind is missed");
            expect(floor.getReflectivity() >= 0 && floor.getPhong_kD() >= 0, "plane material");
            Scene scene = new Scene();
            scene.addObject(sphere);
            scene.addPointLight(new PointLight(new Vector3(0, 5, 0), new ColorRGB(1), 100));
            expect(new Renderer(0, 0, 1).trace(scene, alongZ, 1) != null, "trace with a bounce");
            expect(new Renderer(0, 0, 2).trace(scene, away, 2) != null, "trace of a miss");
        }
        return failed == 0;
    }

    public static void main(String[] args) {
        boolean all = args.length > 0 && (args[0].equals("-a") || args[0].equals("--all"));
        if (!new Tick1Tests().test(all)) {
            System.exit(1);
        }
    }
}
