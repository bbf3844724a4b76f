//! `whitted grade` against hostile submissions (docs/grade.md, "Bad input"): each gets its
//! status in class.csv and its report, nothing escapes the sandbox (no file outside its
//! folder, no connection, no secret read), no process is left, and the class is still graded.

use std::io::Write;
use std::net::TcpListener;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::time::Duration;

use crate::common::*;
use crate::grade::{grade, hostile, records, submission};

fn student(root: &Path, folder: &str, files: (String, String)) {
    let dir = root.join(folder).join("src/gfx/tick2");
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("Plane.java"), files.0).expect("Plane.java");
    std::fs::write(dir.join("Renderer.java"), files.1).expect("Renderer.java");
}

/// Processes whose command line holds every one of `markers`.
fn processes_with(markers: &[&str]) -> usize {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| {
            std::fs::read(e.path().join("cmdline")).is_ok_and(|c| {
                let c = String::from_utf8_lossy(&c);
                markers.iter().all(|m| c.contains(m))
            })
        })
        .count()
}

#[test]
fn hostile_programs_get_their_status_and_nothing_escapes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let class = d.join("class");
    let outside = d.join("escaped.txt");
    let listener = TcpListener::bind("127.0.0.1:0").expect("listen");
    listener.set_nonblocking(true).expect("nonblocking");
    let port = listener.local_addr().expect("addr").port();
    let java_string = |p: &Path| format!("{:?}", p.display().to_string());
    let cases: Vec<(&str, String, &str)> = vec![
        ("exits-early", "System.exit(0);".into(), "no-output"),
        (
            "reads-passwd",
            "try { System.err.println(new String(java.nio.file.Files.readAllBytes(\
             java.nio.file.Path.of(\"/etc/passwd\")))); } catch (java.io.IOException e) \
             { throw new RuntimeException(\"no /etc/passwd: \" + e); }"
                .into(),
            "crashed",
        ),
        (
            "opens-a-socket",
            format!(
                "try {{ new java.net.Socket(\"127.0.0.1\", {port}).close(); }} catch \
                 (java.io.IOException e) {{ throw new RuntimeException(\"no network: \" + e); }}"
            ),
            "crashed",
        ),
        (
            "writes-outside",
            format!(
                "try {{ java.nio.file.Files.writeString(java.nio.file.Path.of({}), \"x\"); }} \
                 catch (java.io.IOException e) {{ throw new RuntimeException(e); }}",
                java_string(&outside)
            ),
            // Where the path's folders are ones the sandbox made to hold its binds, the write
            // lands in its private /tmp and succeeds; either way the host never sees it.
            "any",
        ),
        (
            "sleeps-forever",
            "try { Thread.sleep(Long.MAX_VALUE); } catch (InterruptedException e) {}".into(),
            "timeout",
        ),
        (
            "allocates-forever",
            "java.util.List<long[]> hog = new java.util.ArrayList<>(); \
             while (scene != null) hog.add(new long[1 << 20]);"
                .into(),
            "out-of-memory",
        ),
        (
            // Outside the heap, where -Xmx does not reach: the sandbox's cgroup does. 2 GiB
            // at most, so that a machine without one is never at risk.
            "allocates-natively",
            "try { java.lang.reflect.Field f = sun.misc.Unsafe.class.getDeclaredField(\
             \"theUnsafe\"); f.setAccessible(true); sun.misc.Unsafe u = (sun.misc.Unsafe) \
             f.get(null); for (int i = 0; i < 32 && scene != null; i++) { long a = \
             u.allocateMemory(1L << 26); u.setMemory(a, 1L << 26, (byte) 1); } } catch \
             (ReflectiveOperationException e) { throw new RuntimeException(e); }"
                .into(),
            "out-of-memory",
        ),
        (
            "forks-forever",
            "try { while (scene != null) new ProcessBuilder(\"sleep\", \"4242\").start(); } catch \
             (java.io.IOException e) { throw new RuntimeException(e); }"
                .into(),
            "crashed",
        ),
        (
            "writes-too-much",
            "try (java.io.OutputStream o = new java.io.FileOutputStream(\"big.bin\")) { \
             byte[] mb = new byte[1 << 20]; for (int i = 0; i < 200; i++) o.write(mb); } \
             catch (java.io.IOException e) { throw new RuntimeException(e); }"
                .into(),
            "output-too-large",
        ),
        (
            // 1 GB in files of 32 MiB: stopped at the case's writable area, whose tmpfs is in
            // the sandbox, not on the host's disk.
            "fills-the-disk",
            "byte[] mb = new byte[1 << 20]; outer: for (int f = 0; f < 32; f++) { try \
             (java.io.OutputStream o = new java.io.FileOutputStream(\"fill\" + f)) { for (int i = 0; \
             i < 32; i++) o.write(mb); } catch (java.io.IOException e) { break outer; } }"
                .into(),
            "output-too-large",
        ),
        (
            "writes-100000-files",
            "for (int i = 0; i < 100000; i++) { try { new java.io.File(\"f\" + i).createNewFile(); \
             } catch (java.io.IOException e) { break; } }"
                .into(),
            "output-too-large",
        ),
        (
            // A PNG whose header says 30000x30000 (3.6 GB decoded): told from its header.
            "png-bomb",
            "try (java.io.DataOutputStream o = new java.io.DataOutputStream(new \
             java.io.FileOutputStream(\"output.png\"))) { o.write(new byte[] {(byte) 0x89, 'P', 'N', \
             'G', 13, 10, 26, 10}); byte[] ihdr = java.nio.ByteBuffer.allocate(17).put(\"IHDR\"\
             .getBytes()).putInt(30000).putInt(30000).put(new byte[] {8, 2, 0, 0, 0}).array(); \
             java.util.zip.CRC32 crc = new java.util.zip.CRC32(); crc.update(ihdr); o.writeInt(13); \
             o.write(ihdr); o.writeInt((int) crc.getValue()); } catch (java.io.IOException e) { throw \
             new RuntimeException(e); } System.exit(0);"
                .into(),
            "wrong-size",
        ),
    ];
    for (name, code, _) in &cases {
        student(&class, name, hostile(code));
    }
    // One that does not compile, one without Renderer.java, one correct.
    let (plane, renderer) = submission(&[]);
    student(
        &class,
        "compile-error",
        (
            plane.clone(),
            renderer.replace("return colour;", "return colour"),
        ),
    );
    std::fs::create_dir_all(class.join("no-renderer")).expect("mkdir");
    std::fs::write(class.join("no-renderer/Plane.java"), &plane).expect("write");
    student(&class, "correct", (plane, renderer));
    let out = d.join("out");
    // A temporary folder of this test's own: its JVMs are told from other tests' by it.
    let tmp = d.join("tmp");
    std::fs::create_dir_all(&tmp).expect("tmp");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args([
            "grade",
            "-q",
            "class",
            "-o",
            "out",
            "--timeout",
            "8",
            "--memory",
            "256",
        ])
        .args(["-j", "2"])
        .current_dir(d)
        .env("TMPDIR", &tmp)
        .output()
        .expect("grade runs");
    assert!(run.status.success(), "{}", stderr(&run));

    let rows = records(&out.join("class.csv"));
    let status_of = |id: &str| {
        rows.iter()
            .find(|r| r["id"] == id)
            .map(|r| r["status"].clone())
            .unwrap_or_default()
    };
    assert_eq!(status_of("correct"), "graded");
    assert_eq!(status_of("compile-error"), "compile-error");
    assert_eq!(status_of("no-renderer"), "no-files");
    // Why each scored what it did, in class.csv itself: a 0 says which limit or failure.
    let reason_of = |id: &str| {
        rows.iter()
            .find(|r| r["id"] == id)
            .map(|r| r["reason"].clone())
            .unwrap_or_default()
    };
    assert_eq!(reason_of("correct"), "");
    assert_eq!(reason_of("compile-error"), "compile-error");
    assert_eq!(reason_of("no-renderer"), "no-files");
    for (name, _, expected) in &cases {
        if *expected != "any" {
            assert_eq!(reason_of(name), *expected, "{name}");
        }
    }
    let report =
        std::fs::read_to_string(out.join("students/compile-error/report.html")).expect("report");
    assert!(
        report.contains("Renderer.java") && report.contains("error"),
        "{report}"
    );
    for (name, _, expected) in &cases {
        assert_eq!(status_of(name), "graded", "{name}");
        let result: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join("students").join(name).join("result.json"))
                .expect("result.json"),
        )
        .expect("json");
        let first = &result["extra_data"]["check"]["cases"][0];
        if *expected != "any" {
            assert_eq!(first["status"], *expected, "{name}: {first}");
        }
    }
    // Nothing escaped: no file outside, no connection, no secret in any report.
    assert!(!outside.exists(), "a program wrote outside its folder");
    assert!(
        listener.accept().is_err(),
        "a program reached the host's network"
    );
    let passwd = std::fs::read_to_string("/etc/passwd").unwrap_or_default();
    let secret = passwd.lines().next().unwrap_or("root:x:0:0");
    for entry in std::fs::read_dir(out.join("students"))
        .expect("students")
        .flatten()
    {
        for file in ["report.html", "result.json"] {
            let text = std::fs::read_to_string(entry.path().join(file)).unwrap_or_default();
            assert!(
                !text.contains(secret),
                "{}: /etc/passwd leaked",
                entry.path().display()
            );
        }
    }
    // No process left behind.
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        processes_with(&["sleep", "4242"]),
        0,
        "a forked process outlived its case"
    );
    assert_eq!(
        processes_with(&["gfx.tick2.Tick2", &tmp.to_string_lossy()]),
        0,
        "a JVM outlived its case"
    );
    let _ = std::io::stdout().flush();
}

#[test]
fn hostile_archives_and_folders_are_refused_or_read_without_writing_a_name_they_hold() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (plane, renderer) = submission(&[]);
    let zip_path = d.join("class.zip");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&zip_path).expect("zip"));
    let options = zip::write::SimpleFileOptions::default();
    let mut add = |name: &str, bytes: &[u8]| {
        zip.start_file(name, options).expect("entry");
        zip.write_all(bytes).expect("write");
    };
    // Zip-slip and absolute names: read for their bytes, never written by their names.
    add(
        "Slip_1_assignsubmission_file/../../escaped/Renderer.java",
        renderer.as_bytes(),
    );
    add(
        "/Slip_1_assignsubmission_file/../../escaped/Plane.java",
        plane.as_bytes(),
    );
    // A zip bomb: 256 MiB of zeros as Renderer.java, a few hundred KiB compressed.
    add("Bomb_2_assignsubmission_file/Plane.java", plane.as_bytes());
    zip.start_file("Bomb_2_assignsubmission_file/Renderer.java", options)
        .expect("entry");
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..256 {
        zip.write_all(&zeros).expect("bomb");
    }
    // Links: a Renderer.java that is a symbolic link to /etc/passwd.
    zip.start_file("Link_3_assignsubmission_file/Plane.java", options)
        .expect("entry");
    zip.write_all(plane.as_bytes()).expect("write");
    zip.add_symlink(
        "Link_3_assignsubmission_file/Renderer.java",
        "/etc/passwd",
        options,
    )
    .expect("link");
    // Two folders with one id.
    for who in ["Twin A", "Twin B"] {
        for (name, text) in [("Plane.java", &plane), ("Renderer.java", &renderer)] {
            zip.start_file(format!("{who}_4_assignsubmission_file/{name}"), options)
                .expect("entry");
            zip.write_all(text.as_bytes()).expect("write");
        }
    }
    zip.finish().expect("zip");
    let run = grade(d, &["class.zip", "-o", "out", "--timeout", "30"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let rows = records(&d.join("out/class.csv"));
    let status_of = |id: &str| -> Vec<String> {
        rows.iter()
            .filter(|r| r["id"] == id)
            .map(|r| r["status"].clone())
            .collect()
    };
    assert_eq!(status_of("1"), ["graded"]);
    assert_eq!(status_of("2"), ["no-files"]);
    assert_eq!(status_of("3"), ["no-files"]);
    // Both twins refused, and said so.
    assert_eq!(status_of("4"), ["error", "error"]);
    let twins = std::fs::read_to_string(d.join("out/students/4/result.json")).expect("twins");
    assert!(twins.contains("2 submissions have the id 4"), "{twins}");
    // Nothing was written by a name the archive holds.
    for escaped in [
        d.join("escaped"),
        d.join("out/escaped"),
        d.parent().expect("tmp").join("escaped"),
    ] {
        assert!(!escaped.exists(), "{}", escaped.display());
    }
    let bomb = std::fs::read_to_string(d.join("out/students/2/result.json")).expect("bomb");
    assert!(bomb.contains("larger than"), "{bomb}");

    // A folder of students: a name that is not UTF-8, links and a FIFO where files should be.
    let folders = d.join("folders");
    let odd = std::ffi::OsStr::from_bytes(b"Caf\xe9_6_assignsubmission_file");
    let student = folders.join(odd).join("gfx/tick2");
    std::fs::create_dir_all(&student).expect("mkdir");
    std::fs::write(student.join("Plane.java"), &plane).expect("write");
    std::fs::write(student.join("Renderer.java"), &renderer).expect("write");
    let linked = folders.join("Linked_7_assignsubmission_file");
    std::fs::create_dir_all(&linked).expect("mkdir");
    std::os::unix::fs::symlink("/etc/passwd", linked.join("Renderer.java")).expect("link");
    std::os::unix::fs::symlink(&student, linked.join("elsewhere")).expect("link");
    let fifo = folders.join("Fifo_8_assignsubmission_file");
    std::fs::create_dir_all(&fifo).expect("mkdir");
    std::fs::write(fifo.join("Plane.java"), &plane).expect("write");
    let made = std::process::Command::new("mkfifo")
        .arg(fifo.join("Renderer.java"))
        .status()
        .expect("mkfifo");
    assert!(made.success());
    let run = grade(d, &["folders", "-o", "out2", "--timeout", "30"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let rows = records(&d.join("out2/class.csv"));
    let row = |id: &str| rows.iter().find(|r| r["id"] == id).cloned().expect(id);
    assert_eq!(row("6")["status"], "graded");
    assert_eq!(row("6")["name"], "Caf\u{fffd}");
    assert_eq!(row("7")["status"], "no-files");
    assert_eq!(row("8")["status"], "no-files");

    // A folder with no student in it is a wrong path, not an empty class.
    std::fs::create_dir_all(d.join("empty")).expect("mkdir");
    let run = grade(d, &["empty", "-o", "out3"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("no students there"),
        "{}",
        stderr(&run)
    );
    assert!(!d.join("out3").exists());
}

/// A source that makes javac take minutes (nested conditionals around a generic call: each
/// level doubles its work; 16 levels, a few hundred bytes) holds neither the warm compiler
/// nor the other students: they finish within what they take in a class without it beside a
/// core kept busy (its javac yields the CPU now, `nice -n 19`, but on a machine whose CPUs
/// share cores that gives back only part of it: docs/grade.md has the figures), and it is
/// stopped at the compile deadline, counted in CPU seconds, and named.
#[test]
fn a_slow_compile_holds_no_other_student() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let mut nested = "1".to_string();
    for _ in 0..16 {
        nested = format!("id(b ? {nested} : null)");
    }
    let (plane, renderer) = submission(&[]);
    let slow = renderer.replacen(
        "public class Renderer {",
        &format!(
            "public class Renderer {{\n    static <T> T id(T t) {{ return t; }}\n    \
             static boolean b;\n    Object slow = {nested};\n"
        ),
        1,
    );
    assert_ne!(slow, renderer);
    for who in ["b-good", "c-good"] {
        student(&d.join("alone"), who, (plane.clone(), renderer.clone()));
        student(&d.join("class"), who, (plane.clone(), renderer.clone()));
    }
    student(&d.join("class"), "a-slow", (plane.clone(), slow));
    // Seconds from the start until both good students' results are written.
    let good_done = |class: &str, jobs: &str, out: &str| {
        let started = std::time::Instant::now();
        let mut run = std::process::Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args([
                "grade",
                "-q",
                class,
                "-o",
                out,
                "--timeout",
                "20",
                "-j",
                jobs,
            ])
            .current_dir(d)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("grade runs");
        let done = |who: &str| d.join(out).join("students").join(who).join("result.json");
        while !(done("b-good").exists() && done("c-good").exists()) {
            assert!(
                started.elapsed().as_secs() < 300,
                "the good students never finished"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        let seconds = started.elapsed().as_secs_f64();
        let status = run.wait().expect("wait");
        assert!(status.success());
        seconds
    };
    // Alone, on one worker, beside a process that keeps one core busy as the slow javac does;
    // then beside the slow source, on the one worker it leaves. Held by the slow compile (the
    // warm compiler's lock for its whole deadline, 60 s), they would take a minute more.
    let mut hog = std::process::Command::new("sh")
        .args(["-c", "while :; do :; done"])
        .spawn()
        .expect("a busy loop");
    let alone = good_done("alone", "1", "out-alone");
    let _ = hog.kill();
    let _ = hog.wait();
    let beside = good_done("class", "2", "out-class");
    assert!(
        beside < alone * 2.0 + 10.0,
        "the good students took {beside:.1} s beside a slow compile, {alone:.1} s without it"
    );
    let rows = records(&d.join("out-class/class.csv"));
    let row = |id: &str| rows.iter().find(|r| r["id"] == id).cloned().expect(id);
    assert_eq!(row("b-good")["status"], "graded");
    assert_eq!(row("c-good")["status"], "graded");
    assert_eq!(row("a-slow")["status"], "error");
    let result =
        std::fs::read_to_string(d.join("out-class/students/a-slow/result.json")).expect("result");
    assert!(result.contains("javac did not finish"), "{result}");
}
