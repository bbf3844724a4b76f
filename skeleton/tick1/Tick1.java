package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.io.File;
import java.io.IOException;
import java.util.regex.Matcher; //@T4
import java.util.regex.Pattern; //@T4
import javax.imageio.ImageIO;

/**
 * The course's entry point (whitted's clean-room skeleton: docs/grade.md): options in pairs,
 * -i/--input, -o/--output, -b/--bounces (from 2023-24 also -r/--resolution WxH). A usage error
 * exits with status 255 (System.exit(-1)); a bounce count that is no number throws (status 1).
 */
public class Tick1 {
    public static final String DEFAULT_INPUT = "tick1.xml";
    public static final String DEFAULT_OUTPUT = "output.png";
    public static final int DEFAULT_BOUNCES = 2;
    private static final int WIDTH_PX = ${WIDTH}; //@T1-T3
    private static final int HEIGHT_PX = ${HEIGHT}; //@T1-T3
    private static final int DEFAULT_WIDTH_PX = ${WIDTH}; //@T4
    private static final int DEFAULT_HEIGHT_PX = ${HEIGHT}; //@T4

    public static void usageError() {
        System.err.println("Usage: <tick2> [--input <file.xml>] [--output <file.png>] [--bounces <n>]"); //@T1-T3
        System.err.println("Usage: <tick2> [--input <file.xml>] [--output <file.png>] [--bounces <n>] [--resolution <W>x<H>]"); //@T4
        System.exit(-1);
    }

    public static void main(String[] args) throws IOException {
        String input = DEFAULT_INPUT;
        String output = DEFAULT_OUTPUT;
        int bounces = DEFAULT_BOUNCES;
        int width = WIDTH_PX; //@T1-T3
        int height = HEIGHT_PX; //@T1-T3
        int width = DEFAULT_WIDTH_PX; //@T4
        int height = DEFAULT_HEIGHT_PX; //@T4
        if (args.length % 2 != 0) {
            usageError();
        }
        for (int i = 0; i < args.length; i += 2) {
            String option = args[i];
            String value = args[i + 1];
            switch (option) {
                case "-i":
                case "--input":
                    input = value;
                    break;
                case "-o":
                case "--output":
                    output = value;
                    break;
                case "-b":
                case "--bounces":
                    bounces = Integer.parseInt(value);
                    break;
                //@if T4
                case "-r":
                case "--resolution":
                    Matcher size = Pattern.compile("(\\d+)x(\\d+)").matcher(value);
                    if (size.find()) {
                        width = Integer.parseInt(size.group(1));
                        height = Integer.parseInt(size.group(2));
                    }
                    if (!size.find(0) || width <= 0 || height <= 0 || width > 4096 || height >= 4096) {
                        System.err.println("unsupported resolution: " + value);
                        usageError();
                    }
                    break;
                //@end
                default:
                    System.err.println("Unknown option: " + option);
                    usageError();
            }
        }
        System.out.println("Loading scene '" + input + "'"); //@T2+
        Scene scene = new SceneLoader(input).getScene();
        Renderer renderer = new Renderer(width, height, bounces);
        BufferedImage image = renderer.render(scene);
        ImageIO.write(image, "png", new File(output));
    }
}
