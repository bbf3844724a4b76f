package gfx.tick2;

import java.awt.image.BufferedImage;
import java.io.File;
import javax.imageio.ImageIO;

/**
 * The course's entry point: {@code java gfx.tick2.Tick2 --input S.xml --output O.png --bounces N}
 * (whitted's clean-room skeleton: docs/grade.md). 640x480, as the course's tester renders.
 */
public class Tick2 {
    public static final int WIDTH = 640, HEIGHT = 480;

    public static void main(String[] args) throws Exception {
        String input = null, output = null;
        int bounces = 2;
        for (int i = 0; i + 1 < args.length; i += 2) {
            switch (args[i]) {
                case "--input" -> input = args[i + 1];
                case "--output" -> output = args[i + 1];
                case "--bounces" -> bounces = Integer.parseInt(args[i + 1]);
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        if (input == null || output == null) {
            System.err.println("usage: gfx.tick2.Tick2 --input S.xml --output O.png [--bounces N]");
            System.exit(2);
        }
        Scene scene = new SceneLoader(input).getScene();
        BufferedImage image = new Renderer(WIDTH, HEIGHT, bounces).render(scene);
        ImageIO.write(image, "png", new File(output));
    }
}
