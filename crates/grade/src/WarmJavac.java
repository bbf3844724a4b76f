// whitted grade's warm compiler: one JVM per grading slot compiles student after student
// through javax.tools, so that each student costs a compilation (~0.1 s of CPU) and not a
// JVM's start and warm-up (~1 s). Run in the sandbox by src/grade/warm_javac.rs, in Java's
// source-file mode (`java WarmJavac.java SRC CLASSES OPTION...`).
//
// Protocol, one line in and one reply out per student: whitted lays the student's sources out
// under SRC, empties CLASSES and writes `compile\n`; this answers `ok N\n` or `errors N\n`
// followed by N bytes of javac's messages (UTF-8, at most MESSAGES). Anything else on stdin,
// or its end, stops it. javac's own failures (a stack overflow on a hostile source, out of
// memory) end the process: whitted then compiles that student with a javac of their own.

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.OutputStream;
import java.io.StringWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.stream.Collectors;
import java.util.stream.Stream;
import javax.tools.JavaCompiler;
import javax.tools.StandardJavaFileManager;
import javax.tools.ToolProvider;

public class WarmJavac {
    /** Bytes of messages sent back: the first errors are the ones to fix. */
    private static final int MESSAGES = 64 << 10;

    public static void main(String[] args) throws IOException {
        Path src = Path.of(args[0]);
        List<String> options = Arrays.asList(Arrays.copyOfRange(args, 1, args.length));
        JavaCompiler javac = ToolProvider.getSystemJavaCompiler();
        BufferedReader in =
                new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
        OutputStream out = System.out;
        String line;
        while ((line = in.readLine()) != null && line.equals("compile")) {
            List<Path> sources;
            try (Stream<Path> walk = Files.walk(src)) {
                sources = walk.filter(p -> p.toString().endsWith(".java"))
                        .sorted()
                        .collect(Collectors.toList());
            }
            StringWriter messages = new StringWriter();
            boolean ok;
            try (StandardJavaFileManager files =
                    javac.getStandardFileManager(null, Locale.ROOT, StandardCharsets.UTF_8)) {
                ok = javac.getTask(messages, files, null, options, null,
                        files.getJavaFileObjectsFromPaths(sources)).call();
            }
            byte[] text = messages.toString().getBytes(StandardCharsets.UTF_8);
            int length = Math.min(text.length, MESSAGES);
            String header = (ok ? "ok " : "errors ") + length + "\n";
            out.write(header.getBytes(StandardCharsets.UTF_8));
            out.write(text, 0, length);
            out.flush();
        }
    }
}
