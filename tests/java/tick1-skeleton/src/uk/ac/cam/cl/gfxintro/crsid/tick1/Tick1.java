package uk.ac.cam.cl.gfxintro.crsid.tick1;

import java.awt.image.BufferedImage;
import java.io.File;
import javax.imageio.ImageIO;

/** `-i scene -o image -b bounces -r WxH`; 800x600 by default (2021-22 on). */
public class Tick1 {
    public static void main(String[] args) throws Exception {
        String input = "tick1.xml", output = "output.png";
        int bounces = 2, width = 800, height = 600;
        for (int i = 0; i + 1 < args.length; i += 2) {
            switch (args[i]) {
                case "-i", "--input" -> input = args[i + 1];
                case "-o", "--output" -> output = args[i + 1];
                case "-b", "--bounces" -> bounces = Integer.parseInt(args[i + 1]);
                case "-r", "--resolution" -> {
                    String[] wh = args[i + 1].split("x");
                    width = Integer.parseInt(wh[0]);
                    height = Integer.parseInt(wh[1]);
                }
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        System.out.println("Loading scene '" + input + "'");
        Scene scene = new SceneLoader(input).getScene();
        BufferedImage image = new Renderer(width, height, bounces).render(scene);
        ImageIO.write(image, "png", new File(output));
    }
}
