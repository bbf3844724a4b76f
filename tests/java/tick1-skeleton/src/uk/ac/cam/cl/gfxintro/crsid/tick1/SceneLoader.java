package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.io.File;
import javax.xml.parsers.DocumentBuilderFactory;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.w3c.dom.NodeList;

/** A 2021-22 scene file, read as docs/courses.md says that year's loader reads it. */
public class SceneLoader {
    private final Scene scene = new Scene();

    public SceneLoader(String filename) throws Exception {
        NodeList nodes = DocumentBuilderFactory.newInstance().newDocumentBuilder()
                .parse(new File(filename)).getDocumentElement().getChildNodes();
        for (int i = 0; i < nodes.getLength(); i++) {
            if (nodes.item(i).getNodeType() != Node.ELEMENT_NODE) continue;
            Element e = (Element) nodes.item(i);
            switch (e.getTagName()) {
                case "sphere" -> scene.addObject(material(new Sphere(vector(e, "x", "y", "z"),
                        number(e, "radius", 1), colour(e.getAttribute("colour"))), e));
                case "bumpy-sphere" -> scene.addObject(material(new BumpySphere(vector(e, "x", "y", "z"),
                        number(e, "radius", 1), colour(e.getAttribute("colour"))), e));
                case "plane" -> scene.addObject(material(new Plane(vector(e, "x", "y", "z"),
                        vector(e, "nx", "ny", "nz").normalised(), colour(e.getAttribute("colour"))), e));
                case "point-light" -> scene.addPointLight(new PointLight(vector(e, "x", "y", "z"),
                        colour(e.getAttribute("colour")), number(e, "intensity", 100)));
                case "ambient-light" -> scene.setAmbientLight(
                        colour(e.getAttribute("colour")).scale(number(e, "intensity", 1)));
                default -> { }
            }
        }
    }

    public Scene getScene() { return scene; }

    /** The loader gives planes the sphere defaults too. */
    private static SceneObject material(SceneObject o, Element e) {
        o.setMaterial(number(e, "kD", 0.8), number(e, "kS", 1.2), number(e, "alphaS", 10),
                number(e, "reflectivity", 0.3));
        return o;
    }

    private static ColorRGB colour(String text) {
        int rgb = Integer.parseInt(text.trim().substring(1, 7), 16);
        return new ColorRGB(((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0, (rgb & 255) / 255.0);
    }

    private static double number(Element e, String name, double otherwise) {
        try {
            return Double.parseDouble(e.getAttribute(name));
        } catch (NumberFormatException missing) {
            return otherwise;
        }
    }

    private static Vector3 vector(Element e, String x, String y, String z) {
        return new Vector3(number(e, x, 0), number(e, y, 0), number(e, z, 0));
    }
}
