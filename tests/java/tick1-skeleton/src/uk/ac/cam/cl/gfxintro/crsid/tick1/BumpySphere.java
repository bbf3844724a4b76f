package uk.ac.cam.cl.gfxintro.crsid.tick1;

/** Tick 1*'s bump-mapped sphere, without its map here: it compiles against the student's Sphere. */
public class BumpySphere extends Sphere {
    public BumpySphere(Vector3 position, double radius, ColorRGB colour) {
        super(position, radius, colour);
    }

    @Override
    public Vector3 getNormalAt(Vector3 position) {
        return super.getNormalAt(position);
    }
}
