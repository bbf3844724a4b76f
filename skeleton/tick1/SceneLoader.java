package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.io.File;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * Reads a scene file as the year's course loader does (whitted's clean-room skeleton:
 * docs/grade.md), because students' code trusts it: the JDK's DOM parser; the root must be
 * `scene`; every descendant element is read in document order and a name other than the five
 * throws; unknown attributes are ignored; a number that is missing or does not parse is the
 * default; a colour is the three hex pairs after its first character (the rest ignored), and a
 * missing or short one throws; a plane's normal is normalised here (a zero one gives NaNs); the
 * last ambient light wins. The constructors called are the year's: from 2019-20 the loader
 * gives materials, planes getting the sphere's defaults.
 */
public class SceneLoader {
    private final Scene scene = new Scene();

    public SceneLoader(String filename) {
        Element root;
        try {
            root = DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(new File(filename))
                    .getDocumentElement();
        } catch (Exception e) {
            throw new RuntimeException(e);
        }
        if (!root.getTagName().equals("scene")) {
            throw new RuntimeException("The scene file's root element must be <scene>, not <" + root.getTagName() + ">");
        }
        NodeList elements = root.getElementsByTagName("*");
        for (int i = 0; i < elements.getLength(); i++) {
            add((Element) elements.item(i));
        }
    }

    public Scene getScene() {
        return scene;
    }

    private void add(Element e) {
        switch (e.getTagName()) {
            case "sphere":
                scene.addObject(new Sphere(position(e), number(e, "radius", 1), colour(e) //@T1-T2
                scene.addObject(new Sphere(position(e), number(e, "radius", 1), colour(e), //@T3+
                        number(e, "kD", 0.8), number(e, "kS", 1.2), number(e, "alphaS", 10), number(e, "reflectivity", 0.3) //@T3+
                        , new ColorRGB(number(e, "tr", 0), number(e, "tg", 0), number(e, "tb", 0)) //@T4
                ));
                break;
            case "bumpy-sphere":
                scene.addObject(new BumpySphere(position(e), number(e, "radius", 1), colour(e), e.getAttribute("bump-map")));
                break;
            case "plane":
                scene.addObject(new Plane(position(e), normal(e), colour(e) //@T1-T2
                scene.addObject(new Plane(position(e), normal(e), colour(e), //@T3+
                        number(e, "kD", 0.8), number(e, "kS", 1.2), number(e, "alphaS", 10), number(e, "reflectivity", 0.3) //@T3+
                ));
                break;
            case "point-light":
                scene.addPointLight(new PointLight(position(e), colour(e), number(e, "intensity", 100)));
                break;
            case "ambient-light":
                scene.setAmbientLight(colour(e)); //@T1-T2
                scene.setAmbientLight(colour(e).scale(number(e, "intensity", 1))); //@T3+
                break;
            default:
                throw new RuntimeException("Unknown element <" + e.getTagName() + "> in the scene file");
        }
    }

    private static Vector3 position(Element e) {
        return new Vector3(number(e, "x", 0), number(e, "y", 0), number(e, "z", 0));
    }

    private static Vector3 normal(Element e) {
        return new Vector3(number(e, "nx", 0), number(e, "ny", 0), number(e, "nz", 0)).normalised();
    }

    /** Double.parseDouble (surrounding blanks allowed); the default where it fails. */
    private static double number(Element e, String name, double otherwise) {
        try {
            return Double.parseDouble(e.getAttribute(name));
        } catch (NumberFormatException notANumber) {
            return otherwise;
        }
    }

    /** Characters 2-7 as three hex pairs, each / 255.0; throws when they are not there. */
    private static ColorRGB colour(Element e) {
        String hex = e.getAttribute("colour");
        return new ColorRGB(channel(hex, 1) / 255.0, channel(hex, 3) / 255.0, channel(hex, 5) / 255.0);
    }

    private static int channel(String hex, int at) {
        return Integer.parseInt(hex.substring(at, at + 2), 16);
    }
}
