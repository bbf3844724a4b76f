//! whitted's clean-room Tick 1 skeletons (`skeleton/tick1`: T1 2017-18, T2 2018-19, T3 2019-20
//! to 2022-23, T4 2023-24), held against the course's own images and against what
//! docs/grade.md says the course's classes do. The student's side is whitted's finished Tick 1
//! (`skeleton/tick1/finished`, through tick1_fixture.rs), written in the handout's shape as
//! students write it (the plane's stored normal trusted, `reflectIn`, the tone map from
//! `power`/`add`/`inv`), selected for each year's API with the skeleton's own template markers; and small submissions written the ways
//! real ones lean on the course's classes (a miss's null location, unfiltered hits, the loader's
//! defaults). These compile with javac directly, without grade's sandbox: grade's own tests
//! (grade_courses.rs) run classes through it.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::*;
use crate::tick1_fixture::fixture;
use whitted_core::course::Course;

/// The package our students' files are in here.
const PACKAGE: &str = "uk.ac.cam.cl.gfxintro.ab123.tick1";

fn course(name: &str) -> Course {
    Course::from_name(name).expect("course")
}

/// `year`'s clean-room skeleton and `files` (in [`PACKAGE`]) compiled into `d/tag/classes`:
/// the classes, or javac's messages.
fn compile(d: &Path, tag: &str, year: &str, files: &[(&str, String)]) -> Result<PathBuf, String> {
    let src = d.join(tag).join("src");
    let classes = d.join(tag).join("classes");
    std::fs::create_dir_all(&classes).expect("classes");
    let skeleton =
        whitted_grade::clean_room_skeleton(course(year), Some(PACKAGE)).expect("skeleton");
    let folder = PACKAGE.replace('.', "/");
    let mut paths = Vec::new();
    let theirs = files
        .iter()
        .map(|(name, text)| (format!("{folder}/{name}"), text.clone().into_bytes()));
    for (path, bytes) in skeleton.into_iter().chain(theirs) {
        let path = src.join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(&path, bytes).expect("write");
        paths.push(path);
    }
    let javac = std::process::Command::new("javac")
        .args(["-proc:none", "-nowarn", "-d"])
        .arg(&classes)
        .args(&paths)
        .output()
        .expect("javac");
    match javac.status.success() {
        true => Ok(classes),
        false => Err(stderr(&javac)),
    }
}

/// `java -cp classes PACKAGE.Tick1 args...` in `d`.
fn tick1(d: &Path, classes: &Path, args: &[&str]) -> Output {
    std::process::Command::new("java")
        .args(["-Djava.awt.headless=true", "-cp"])
        .arg(classes)
        .arg(format!("{PACKAGE}.Tick1"))
        .args(args)
        .current_dir(d)
        .output()
        .expect("java")
}

/// The pixels (RGB) the student's program writes for `scene` at `bounces`.
fn student_render(d: &Path, classes: &Path, scene: &Path, bounces: &str) -> Vec<u8> {
    let out = d.join("student.png");
    let _ = std::fs::remove_file(&out);
    let run = tick1(d, classes, &["-i", s(scene), "-o", s(&out), "-b", bounces]);
    assert!(run.status.success(), "{}", stderr(&run));
    rgb(&read_png(&out))
}

/// The pixels `whitted render --course year` writes for `scene` at `bounces`.
fn whitted_render(d: &Path, year: &str, scene: &Path, bounces: &str) -> Vec<u8> {
    let run = whitted(
        d,
        &[
            "render",
            "-q",
            "--course",
            year,
            "-i",
            s(scene),
            "-b",
            bounces,
            "-o",
            "whitted.png",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    rgb(&read_png(&d.join("whitted.png")))
}

fn rgb(png: &Png) -> Vec<u8> {
    match png.color {
        png::ColorType::Rgb => png.data.clone(),
        png::ColorType::Rgba => png.data.chunks(4).flat_map(|p| p[..3].to_vec()).collect(),
        other => panic!("unexpected colour type {other:?}"),
    }
}

/// How many pixels of two RGB images differ.
fn differing(a: &[u8], b: &[u8]) -> usize {
    assert_eq!(a.len(), b.len(), "sizes differ");
    a.chunks(3).zip(b.chunks(3)).filter(|(a, b)| a != b).count()
}

/// The course's own images, rendered by a student's three files on our skeleton of each year:
/// 0 differing pixels. 2019-20's test1 also tells the year's shadow bias (24 pixels).
#[test]
fn each_year_s_student_on_its_clean_room_skeleton_renders_the_course_s_own_images() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    for (year, folder) in [
        ("2019-20", "2019-20"),
        ("2020-21", "2020-21"),
        ("2021-22", "2021-24"),
        ("2023-24", "2021-24"),
    ] {
        let classes = compile(d, year, year, &fixture(year, "ab123", &[])).expect("compiles");
        for test in ["test1", "test2"] {
            let scene = root().join(format!("scenes/courses/{folder}/{test}.xml"));
            let ours = student_render(d, &classes, &scene, "2");
            let course = rgb(&read_png(
                &root().join(format!("reference/courses/{folder}/{test}_reference.png")),
            ));
            assert_eq!(differing(&ours, &course), 0, "{year} {test}");
        }
    }
    // A 2020-21 student (shadow rays along N) misses 2019-20's image by the 24 pixels the year's
    // rule makes: the comparison above can fail.
    let classes = compile(
        d,
        "2020-on-2019",
        "2019-20",
        &fixture("2020-21", "ab123", &[]),
    )
    .expect("compiles");
    let scene = root().join("scenes/courses/2019-20/test1.xml");
    let course = rgb(&read_png(
        &root().join("reference/courses/2019-20/test1_reference.png"),
    ));
    assert_eq!(
        differing(&student_render(d, &classes, &scene, "2"), &course),
        24
    );
}

/// The years without published images (2017-18's tick2.xml, 2018-19's tick1.xml), and every
/// year at 0, 1 and 3 bounces: the student's files on our skeleton render whitted's image of that
/// year, byte for byte.
#[test]
fn each_year_s_student_on_its_clean_room_skeleton_renders_whitted_s_image_of_the_year() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let tick2 = root().join("scenes/tick2.xml");
    let tick1_2018 = root().join("scenes/courses/2018-19/tick1.xml");
    let test1 = root().join("scenes/courses/2021-24/test1.xml");
    for (year, scene) in [
        ("2017-18", &tick2),
        ("2018-19", &tick1_2018),
        ("2019-20", &root().join("scenes/courses/2019-20/test2.xml")),
        ("2021-22", &test1),
        ("2023-24", &test1),
    ] {
        let classes = compile(d, year, year, &fixture(year, "ab123", &[])).expect("compiles");
        for bounces in ["0", "1", "3"] {
            let ours = student_render(d, &classes, scene, bounces);
            let whitted = whitted_render(d, year, scene, bounces);
            assert_eq!(differing(&ours, &whitted), 0, "{year} -b {bounces}");
        }
    }
}

/// Real submissions lean on what the course's classes do (docs/grade.md, "Easy to get wrong"):
/// each leaning submission renders on our skeleton as the course's classes make it render.
#[test]
fn submissions_that_lean_on_the_course_s_classes_behave_as_the_course_s_classes_make_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let year = "2021-22";
    let scene = root().join("scenes/courses/2021-24/test1.xml");
    let course_image = rgb(&read_png(
        &root().join("reference/courses/2021-24/test1_reference.png"),
    ));
    let fixture_with = |from: &str, to: &str| {
        let mut files = fixture(year, "ab123", &[]);
        let renderer = &mut files[1].1;
        assert!(renderer.contains(from), "the fixture has {from}");
        *renderer = renderer.replace(from, to);
        files
    };
    // A miss's location is null: a shadow test that reads it and catches the exception is
    // right; had the empty hit held a zero vector, |0 - P| < d would shadow every lit point.
    let null_location = fixture_with(
        "boolean inShadow = blocker.getObjectHit() != null && blocker.getDistance() < distanceToLight;",
        "boolean inShadow; \
         try { inShadow = blocker.getLocation().subtract(shadowOrigin).magnitude() < distanceToLight; } \
         catch (NullPointerException miss) { inShadow = false; }",
    );
    let classes = compile(d, "null", year, &null_location).expect("compiles");
    assert_eq!(
        differing(&student_render(d, &classes, &scene, "2"), &course_image),
        0
    );
    // Without the catch, the first shadow ray that meets nothing throws, and the program dies
    // without an image (status 1), as on the course's classes.
    let unguarded = fixture_with(
        "boolean inShadow = blocker.getObjectHit() != null && blocker.getDistance() < distanceToLight;",
        "boolean inShadow = blocker.getLocation().subtract(shadowOrigin).magnitude() < distanceToLight;",
    );
    let classes = compile(d, "unguarded", year, &unguarded).expect("compiles");
    let out = d.join("unguarded.png");
    let run = tick1(d, &classes, &["-i", s(&scene), "-o", s(&out)]);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("NullPointerException"),
        "{}",
        stderr(&run)
    );
    assert!(!out.exists());
    // findClosestIntersection does not filter: a plane that returns the hit behind the ray is
    // kept (its distance is the smallest), as whitted's `plane-behind` renders it.
    let behind = compile(
        d,
        "behind",
        year,
        &fixture(year, "ab123", &["plane-behind"]),
    )
    .expect("compiles");
    let ours = student_render(d, &behind, &scene, "2");
    assert!(differing(&ours, &course_image) > 1000);
    let program = format!("java -cp '{}' {PACKAGE}.Tick1", s(&behind));
    let check = whitted(
        d,
        &["check", "--course", year, "--program", &program, "--json"],
    );
    let said = String::from_utf8_lossy(&check.stdout).to_string();
    assert!(said.contains("\"plane-behind\""), "{said}");
    // The loader: materials from attributes with the sphere's defaults for planes too, numbers
    // that do not parse are the default, the plane's normal normalised (the student's Plane
    // uses it as given), the last ambient light winning.
    let quirks = write_scene(
        d,
        "quirks.xml",
        "<scene>\n  <ambient-light colour=\"#101010\" intensity=\"2\"/>\n  \
         <point-light x=\"1\" y=\"up\" z=\"1\" colour=\"#FFFFFF.\" intensity=\"\"/>\n  <sphere x=\" 0.2 \" y=\"0\" z=\"4\" radius=\"1\" colour=\"#3060e0\" kS=\"x\"/>\n  \
         <plane x=\"0\" y=\"-1\" z=\"0\" nx=\"0\" ny=\"4.22\" nz=\"-2.18\" colour=\"#22AA22\" reflectivity=\"0.5\"/>\n  \
         <ambient-light colour=\"#555555\" intensity=\"0.5\"/>\n</scene>\n",
    );
    let strict = write_scene(
        d,
        "strict.xml",
        "<scene>\n  <point-light x=\"1\" y=\"0\" z=\"1\" colour=\"#FFFFFF\" intensity=\"100\"/>\n  \
         <sphere x=\"0.2\" y=\"0\" z=\"4\" radius=\"1\" colour=\"#3060E0\" kD=\"0.8\" kS=\"1.2\" alphaS=\"10\" reflectivity=\"0.3\"/>\n  \
         <plane x=\"0\" y=\"-1\" z=\"0\" nx=\"0\" ny=\"4.22\" nz=\"-2.18\" colour=\"#22AA22\" kD=\"0.8\" kS=\"1.2\" alphaS=\"10\" reflectivity=\"0.5\"/>\n  \
         <ambient-light colour=\"#555555\" intensity=\"0.5\"/>\n</scene>\n",
    );
    let classes = compile(d, "fixture", year, &fixture(year, "ab123", &[])).expect("compiles");
    let whitted = whitted_render(d, year, &strict, "2");
    assert_eq!(
        differing(&student_render(d, &classes, &quirks, "2"), &whitted),
        0
    );
    // What the course's loader refuses, ours refuses: an unknown element, a short colour.
    for (name, xml) in [
        (
            "unknown.xml",
            "<scene><sphere colour=\"#ffffff\"/><widget/></scene>",
        ),
        ("short.xml", "<scene><sphere colour=\"#fff\"/></scene>"),
        ("root.xml", "<world><sphere colour=\"#ffffff\"/></world>"),
    ] {
        let bad = write_scene(d, name, xml);
        let run = tick1(d, &classes, &["-i", s(&bad), "-o", "bad.png"]);
        assert_eq!(run.status.code(), Some(1), "{name}: {}", stderr(&run));
        assert!(!d.join("bad.png").exists(), "{name}");
    }
}

/// Each skeleton offers exactly its year's members: what the course's classes do not offer
/// does not compile here either, and each year's additions compile from their year only.
#[test]
fn each_skeleton_offers_exactly_its_year_s_members() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // (a statement in a student's Renderer, the years whose classes offer it)
    let calls: [(&str, &[&str]); 10] = [
        ("double l = new Vector3(1).magnitude();", &["2017-18", "2018-19", "2021-22", "2023-24"]),
        ("Vector3 v = new Vector3(1).normalize();", &[]),
        ("double l = new Vector3(1).length();", &[]),
        ("double x = new ColorRGB(1).dot(new ColorRGB(1));", &[]),
        ("ColorRGB c = new ColorRGB(new Vector3(1));", &[]),
        ("java.util.List<SceneObject> o = new Scene().getObjects();", &[]),
        ("ColorRGB c = new ColorRGB(1).power(2).inv().add(1.0);", &["2018-19", "2021-22", "2023-24"]),
        ("Vector3 v = new Vector3(1).add(1.0);", &["2018-19", "2021-22", "2023-24"]),
        ("boolean z = new ColorRGB(1).subtract(1.0).isZero();", &["2023-24"]),
        ("boolean t = new Plane(new Vector3(0), new Vector3(0, 1, 0), new ColorRGB(1)).isTransmissive();", &["2023-24"]),
    ];
    for year in ["2017-18", "2018-19", "2021-22", "2023-24"] {
        let files = fixture(year, "ab123", &[]);
        for (n, (call, offered)) in calls.iter().enumerate() {
            let mut files = files.clone();
            files[1].1 = files[1].1.replacen(
                "    public BufferedImage render(Scene scene) {\n",
                &format!("    public BufferedImage render(Scene scene) {{\n        {call}\n"),
                1,
            );
            let compiled = compile(d, &format!("{year}-{n}"), year, &files);
            assert_eq!(
                compiled.is_ok(),
                offered.contains(&year),
                "{year}: {call}: {compiled:?}"
            );
        }
    }
    // The loader's constructors are the year's: a T3 Sphere (7 arguments) does not compile
    // against T4's loader, nor a T4 one (8) against T3's.
    let t3 = fixture("2021-22", "ab123", &[]);
    assert!(compile(d, "t3-on-t4", "2023-24", &t3).is_err());
    let t4 = fixture("2023-24", "ab123", &[]);
    assert!(compile(d, "t4-on-t3", "2021-22", &t4).is_err());
}

/// Tick1's command line as docs/grade.md gives it: pairs, 255 for a usage error, 1 for a
/// bounce count that is no number; `-r` from 2023-24 only, with its bounds.
#[test]
fn each_year_s_tick1_reads_its_command_line_as_the_course_s_does() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let scene = root().join("scenes/courses/2021-24/test2.xml");
    let t4 = compile(d, "t4", "2023-24", &fixture("2023-24", "ab123", &[])).expect("compiles");
    let t3 = compile(d, "t3", "2021-22", &fixture("2021-22", "ab123", &[])).expect("compiles");
    let t2 = compile(d, "t2", "2018-19", &fixture("2018-19", "ab123", &[])).expect("compiles");
    let run = tick1(
        d,
        &t4,
        &[
            "-i",
            s(&scene),
            "-o",
            "small.png",
            "-r",
            "size=64x48!",
            "-b",
            "1",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let small = read_png(&d.join("small.png"));
    assert_eq!((small.width, small.height), (64, 48));
    for bad in ["64", "0x48", "4097x10", "10x4096"] {
        let run = tick1(d, &t4, &["-i", s(&scene), "-o", "x.png", "-r", bad]);
        assert_eq!(run.status.code(), Some(255), "-r {bad}");
        assert!(
            stderr(&run).contains(&format!("unsupported resolution: {bad}")),
            "{}",
            stderr(&run)
        );
    }
    let run = tick1(d, &t3, &["-i", s(&scene), "-o", "x.png", "-r", "64x48"]);
    assert_eq!(run.status.code(), Some(255));
    assert!(
        stderr(&run).contains("Unknown option: -r"),
        "{}",
        stderr(&run)
    );
    let run = tick1(d, &t3, &["-i", s(&scene), "-o"]);
    assert_eq!(run.status.code(), Some(255));
    let run = tick1(d, &t3, &["-i", s(&scene), "-o", "x.png", "-b", "two"]);
    assert_eq!(run.status.code(), Some(1));
    assert!(!d.join("x.png").exists());
    // The size is the year's (800x600 from 2021-22), and from 2018-19 the scene is announced.
    let run = tick1(
        d,
        &t3,
        &[
            "--input",
            s(&scene),
            "--output",
            "big.png",
            "--bounces",
            "0",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let big = read_png(&d.join("big.png"));
    assert_eq!((big.width, big.height), (800, 600));
    assert!(
        String::from_utf8_lossy(&run.stdout).starts_with(&format!("Loading scene '{}'", s(&scene)))
    );
    let run = tick1(d, &t2, &["-i", s(&scene), "-o", "t2.png", "-b", "0"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(read_png(&d.join("t2.png")).width, 640);
}

/// `grade --write-skeleton` writes the year's classes, which a student's files compile against,
/// into a new folder, and never into an existing one.
#[test]
fn the_year_s_skeleton_is_written_out_whole_and_never_over_a_folder() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let run = whitted(
        d,
        &[
            "grade",
            "--write-skeleton",
            "--course",
            "2018-19",
            "-o",
            "sk",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let folder = d.join("sk/src/uk/ac/cam/cl/gfxintro/crsid/tick1");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .expect("written")
        .flatten()
        .map(|e| e.path())
        .collect();
    assert_eq!(paths.len(), 12);
    let vector = std::fs::read_to_string(folder.join("Vector3.java")).expect("Vector3");
    assert!(vector.contains("public Vector3 inv()") && !vector.contains("isZero"));
    for (name, text) in fixture("2018-19", "crsid", &[]) {
        let path = folder.join(name);
        std::fs::write(&path, text).expect("write");
        paths.push(path);
    }
    let javac = std::process::Command::new("javac")
        .args(["-proc:none", "-d"])
        .arg(d.join("classes"))
        .args(&paths)
        .output()
        .expect("javac");
    assert!(javac.status.success(), "{}", stderr(&javac));
    let again = whitted(
        d,
        &[
            "grade",
            "--write-skeleton",
            "--course",
            "2018-19",
            "-o",
            "sk",
        ],
    );
    assert_eq!(again.status.code(), Some(2));
    assert!(
        stderr(&again).contains("already exists"),
        "{}",
        stderr(&again)
    );
}
