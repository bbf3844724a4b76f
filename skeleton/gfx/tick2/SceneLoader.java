package gfx.tick2;

import java.io.File;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.w3c.dom.NodeList;

/** Reads a scene XML file (whitted's clean-room skeleton: docs/grade.md, docs/scene-format.md). */
public class SceneLoader {
    private final Scene scene = new Scene();

    public SceneLoader(String filename) {
        try {
            NodeList nodes = DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(new File(filename))
                    .getDocumentElement().getChildNodes();
            for (int i = 0; i < nodes.getLength(); i++) {
                if (nodes.item(i).getNodeType() == Node.ELEMENT_NODE) add((Element) nodes.item(i));
            }
        } catch (Exception e) {
            throw new RuntimeException("cannot read the scene " + filename + ": " + e.getMessage(), e);
        }
    }

    public Scene getScene() {
        return scene;
    }

    private void add(Element e) {
        switch (e.getTagName()) {
            case "sphere" -> scene.addObject(new Sphere(position(e), number(e, "radius", 1), colour(e)));
            case "plane" -> scene.addObject(new Plane(position(e),
                    new Vector3(number(e, "nx", 0), number(e, "ny", 0), number(e, "nz", 0)), colour(e)));
            case "point-light" -> scene.addPointLight(new PointLight(position(e), colour(e), number(e, "intensity", 100)));
            case "ambient-light" -> scene.setAmbientLight(colour(e));
            default -> throw new IllegalArgumentException("unknown element <" + e.getTagName() + ">");
        }
    }

    private static Vector3 position(Element e) {
        return new Vector3(number(e, "x", 0), number(e, "y", 0), number(e, "z", 0));
    }

    private static double number(Element e, String name, double otherwise) {
        String value = e.getAttribute(name);
        return value.isEmpty() ? otherwise : Double.parseDouble(value.trim());
    }

    /** #RRGGBB, each channel byte / 255. */
    private static Vector3 colour(Element e) {
        int rgb = Integer.parseInt(e.getAttribute("colour").substring(1), 16);
        return new Vector3(((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0, (rgb & 255) / 255.0);
    }
}
