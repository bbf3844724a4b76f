package gfx.tick2;

import java.io.File;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * Reads a scene XML file (whitted's clean-room skeleton: docs/grade.md, "The clean-room
 * skeleton"). It behaves as the course's loader does, because students' code trusts it:
 * a plane's normal is normalised here (a student's Plane.intersectionWith uses it as given),
 * every element anywhere under the root is read in document order, a number that is missing or
 * does not parse is the default, a colour is read from the six hex digits after its `#`
 * (anything after them is ignored), the last ambient light wins, and names it does not know
 * are ignored.
 */
public class SceneLoader {
    private final Scene scene = new Scene();

    public SceneLoader(String filename) {
        NodeList elements;
        try {
            elements = DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(new File(filename))
                    .getDocumentElement().getElementsByTagName("*");
        } catch (Exception e) {
            throw new RuntimeException("cannot read the scene " + filename + ": " + e.getMessage(), e);
        }
        for (int i = 0; i < elements.getLength(); i++) {
            add((Element) elements.item(i));
        }
    }

    public Scene getScene() {
        return scene;
    }

    private void add(Element e) {
        switch (e.getTagName()) {
            case "sphere" -> scene.addObject(new Sphere(position(e), number(e, "radius", 1), colour(e)));
            case "plane" -> scene.addObject(new Plane(position(e),
                    new Vector3(number(e, "nx", 0), number(e, "ny", 0), number(e, "nz", 0)).normalised(), colour(e)));
            case "point-light" -> scene.addPointLight(new PointLight(position(e), colour(e), number(e, "intensity", 100)));
            case "ambient-light" -> scene.setAmbientLight(colour(e));
            default -> { }
        }
    }

    private static Vector3 position(Element e) {
        return new Vector3(number(e, "x", 0), number(e, "y", 0), number(e, "z", 0));
    }

    /** Java's own number syntax (surrounding blanks allowed); the default where it fails. */
    private static double number(Element e, String name, double otherwise) {
        try {
            return Double.parseDouble(e.getAttribute(name));
        } catch (NumberFormatException notANumber) {
            return otherwise;
        }
    }

    /** #RRGGBB: each channel's two hex digits / 255; what follows them is not read. */
    private static Vector3 colour(Element e) {
        String hex = e.getAttribute("colour");
        return new Vector3(channel(hex, 1) / 255.0, channel(hex, 3) / 255.0, channel(hex, 5) / 255.0);
    }

    private static int channel(String hex, int at) {
        return Integer.parseInt(hex.substring(at, at + 2), 16);
    }
}
