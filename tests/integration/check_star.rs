//! `whitted check` on Tick 1* (docs/check.md, "Tick 1*"), against our own Java Tick 1*
//! (`tests/java/tick1star`: whitted's clean-room 2023-24 skeleton copied into the package
//! `tick1star`, the finished Tick 1's Sphere and Plane, and a Renderer and BumpySphere written
//! from the handout's method; `-Dseed=N` draws from a seeded generator, `-Dsoft=`, `-Ddof=` and
//! `-Dbump=` choose how it is written). `--program` runs the handout's two scenes once each at
//! 160x120 with 2023-24's `--resolution`; `--star distributed` says whether an image is a draw
//! of the course's process, and of which variant. Test time is kept down by the reduced size
//! (a correct image takes the Java about 6 s, its check about 3 s; a variant's check renders
//! four more expectations, about 20 s) and by fresh seeds few in number: the false-alarm rate
//! is measured on 24 seeds in `star_draw.rs`'s THRESHOLD and checked again here on 4 others.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use serde_json::Value;

use crate::common::*;
use crate::tick1_fixture::fixture_file;

const PACKAGE: &str = "uk.ac.cam.cl.gfxintro.ab123.tick1star";
const YEAR: &str = "2023-24";

/// The Java Tick 1* of 2023-24 compiled once for every test of this process.
pub(crate) fn classes() -> &'static Path {
    static CLASSES: OnceLock<PathBuf> = OnceLock::new();
    CLASSES.get_or_init(|| {
        let d = process_dir("tick1star");
        let course = whitted_core::course::Course::from_name(YEAR).expect("course");
        let src = d.join("src");
        let classes = d.join("classes");
        std::fs::create_dir_all(&classes).expect("classes");
        let folder = src.join(PACKAGE.replace('.', "/"));
        std::fs::create_dir_all(&folder).expect("folder");
        let skeleton = whitted_grade::clean_room_skeleton(course, Some(PACKAGE)).expect("skeleton");
        let mut paths = Vec::new();
        for (path, bytes) in skeleton {
            let path = src.join(path);
            std::fs::write(&path, bytes).expect("write");
            paths.push(path);
        }
        // The student's own files, over the skeleton's (its BumpySphere is a stub).
        let star = |name: &str| {
            let text = std::fs::read_to_string(root().join("tests/java/tick1star").join(name))
                .expect("fixture");
            whitted_grade::for_year(&text, course).expect("template")
        };
        let theirs = [
            (
                "Sphere.java",
                fixture_file("Sphere.java", YEAR, "crsid", &[]),
            ),
            ("Plane.java", fixture_file("Plane.java", YEAR, "crsid", &[])),
            ("Renderer.java", star("Renderer.java")),
            ("BumpySphere.java", star("BumpySphere.java")),
        ];
        for (name, text) in theirs {
            let text = text
                .replace(
                    "package uk.ac.cam.cl.gfxintro.crsid.tick1star;",
                    &format!("package {PACKAGE};"),
                )
                .replace(
                    "package uk.ac.cam.cl.gfxintro.crsid.tick1;",
                    &format!("package {PACKAGE};"),
                );
            let path = folder.join(name);
            std::fs::write(&path, text).expect("write");
            if !paths.contains(&path) {
                paths.push(path);
            }
        }
        javac_into(&classes, &paths);
        classes
    })
}

/// The program as `--program` takes it, with the JVM options `flags`.
fn program(flags: &str) -> String {
    format!(
        "java -Djava.awt.headless=true {flags} -cp '{}' {PACKAGE}.Tick1",
        s(classes())
    )
}

/// Our Java's image of the handout's `scene` (copied with its map into `d`) with `flags`,
/// at `size`.
pub(crate) fn java_image(d: &Path, scene: &str, flags: &[&str], size: &str, out: &str) -> PathBuf {
    let handout = root().join("crates/check/scenes/tick1star");
    for file in [scene, "bumpmap.png"] {
        std::fs::copy(handout.join(file), d.join(file)).expect("copy");
    }
    let run = Command::new("java")
        .arg("-Djava.awt.headless=true")
        .args(flags)
        .arg("-cp")
        .arg(classes())
        .arg(format!("{PACKAGE}.Tick1"))
        .args(["-i", scene, "-o", out, "-b", "2", "-r", size])
        .current_dir(d)
        .output()
        .expect("java");
    assert!(run.status.success(), "{flags:?}: {}", stderr(&run));
    d.join(out)
}

/// `check --course 2023-24 --star distributed --json IMAGE`: its tick1_star object and exit.
fn judge(d: &Path, image: &Path) -> (Value, Option<i32>) {
    let out = whitted(
        d,
        &[
            "check",
            "--course",
            YEAR,
            "--star",
            "distributed",
            "--json",
            s(image),
        ],
    );
    let json: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{}: {}", image.display(), stderr(&out)));
    (json["tick1_star"].clone(), out.status.code())
}

/// The statistic of `process` in a verdict's fits.
fn statistic(star: &Value, process: &str) -> f64 {
    star["fits"]
        .as_array()
        .and_then(|fits| fits.iter().find(|f| f["process"] == process))
        .and_then(|f| f["statistic"].as_f64())
        .unwrap_or_else(|| panic!("no {process} in {star}"))
}

/// `check --program` on our Java Tick 1* with the JVM options `flags`: its JSON and exit.
fn check_program(d: &Path, flags: &str) -> (Value, Option<i32>) {
    let out = whitted(
        d,
        &[
            "check",
            "--course",
            YEAR,
            "--json",
            "--program",
            &program(flags),
        ],
    );
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    (json, out.status.code())
}

#[test]
fn program_runs_each_option_s_handout_scene_once_at_2023_24_s_resolution() {
    let d = tempfile::tempdir().expect("tempdir");
    let started = std::time::Instant::now();
    // Both options done: the distributed image is a draw of the course's process; the bump
    // image has random rays too, judged as a draw of the bumped scene (star_programs.rs).
    let (json, status) = check_program(d.path(), "-Dseed=101");
    let cases = json["cases"].as_array().expect("cases");
    let names: Vec<&str> = cases
        .iter()
        .map(|c| c["case"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(names, ["bump.xml -b 2", "distributed.xml -b 2"]);
    for case in cases {
        assert_eq!(case["status"], "tick1-star", "no timeout: {case}");
        assert_eq!(case["tick1_star"]["width"], 160);
        assert_eq!(case["tick1_star"]["height"], 120);
    }
    assert_eq!(cases[0]["tick1_star"]["option"], "bump");
    assert_eq!(cases[1]["tick1_star"]["verdict"], "course-draw", "{json}");
    assert_eq!(cases[0]["tick1_star"]["verdict"], "bump-draw", "{json}");
    assert_eq!(
        status,
        Some(0),
        "both options drawn from the course's: {json}"
    );
    let plan = json["tick1_star"]["plan"].as_str().expect("plan");
    assert!(plan.contains("--resolution 160x120"), "{plan}");
    assert!(plan.contains("once each"), "{plan}");
    // Option 1 only (the Tick 1 renderer): its bump image is the handout's method, under the
    // parametrisation it chose; the distributed image, hard-edged, is option 2 not done.
    let (json, _) = check_program(d.path(), "-Dsoft=none -Ddof=none -Dbump=z-yx");
    let bump = &json["cases"][0]["tick1_star"];
    assert_eq!(bump["verdict"], "bump-correct", "{json}");
    assert!(
        bump["line"].as_str().is_some_and(|l| l.contains("z-yx")),
        "{bump}"
    );
    assert_eq!(
        json["cases"][1]["tick1_star"]["verdict"], "option-not-done",
        "{json}"
    );
    let (json, _) = check_program(d.path(), "-Dsoft=none -Ddof=none -Dbump=y-xz,inverted");
    let bump = &json["cases"][0]["tick1_star"];
    assert_eq!(bump["verdict"], "bump-mistake", "{json}");
    assert!(
        bump["line"]
            .as_str()
            .is_some_and(|l| l.contains("bump-inverted")),
        "{bump}"
    );
    // Six runs of seconds each and their checks: never a row of timeouts.
    assert!(started.elapsed().as_secs() < 120, "{:?}", started.elapsed());
}

#[test]
fn the_correct_program_is_a_draw_of_the_course_s_process_for_every_seed() {
    let d = tempfile::tempdir().expect("tempdir");
    for seed in [201, 202, 203, 204] {
        let flag = format!("-Dseed={seed}");
        let image = java_image(d.path(), "distributed.xml", &[&flag], "160x120", "ok.png");
        let (star, status) = judge(d.path(), &image);
        assert_eq!(star["verdict"], "course-draw", "seed {seed}: {star}");
        assert_eq!(status, Some(0));
        let t = statistic(&star, "course");
        assert!((0.8..1.45).contains(&t), "seed {seed}: {t}");
    }
}

#[test]
fn each_variant_whitted_renders_is_named_with_its_region() {
    let d = tempfile::tempdir().expect("tempdir");
    let variants = [
        ("-Dsoft=uniform-sphere", "uniform-sphere"),
        ("-Dsoft=light-size", "light-size"),
        ("-Ddof=not-averaged", "dof-not-averaged"),
    ];
    for (flag, name) in variants {
        let image = java_image(
            d.path(),
            "distributed.xml",
            &["-Dseed=301", flag],
            "160x120",
            "v.png",
        );
        let (star, status) = judge(d.path(), &image);
        assert_eq!(status, Some(1), "{flag}: {star}");
        assert_eq!(star["verdict"], "variant-draw", "{flag}: {star}");
        assert!(statistic(&star, "course") > 1.45, "{flag}: {star}");
        assert!(statistic(&star, name) < 1.45, "{flag}: {star}");
        let line = star["line"].as_str().expect("line");
        assert!(line.contains(&format!("but of {name}")), "{line}");
        assert!(line.contains("it shows most at x "), "{line}");
    }
    // The aperture over the whole side each way is named, and passes: the handout's words
    // allow that reading (docs/tick1star.md).
    let image = java_image(
        d.path(),
        "distributed.xml",
        &["-Dseed=301", "-Ddof=aperture-full-side"],
        "160x120",
        "v.png",
    );
    let (star, status) = judge(d.path(), &image);
    assert_eq!(status, Some(0), "{star}");
    assert_eq!(star["verdict"], "accepted-variant-draw", "{star}");
    assert!(statistic(&star, "course") > 1.45, "{star}");
    assert!(statistic(&star, "aperture-full-side") < 1.45, "{star}");
    let line = star["line"].as_str().expect("line");
    assert!(line.contains("a draw of aperture-full-side"), "{line}");
    assert!(line.contains("allow this reading"), "{line}");
}

/// Our Java's distributed image with `flags` and each seed is named `name` by the check,
/// with the course's statistic above the threshold and the variant's own under it.
fn named_for_every_seed(d: &Path, flag: &str, name: &str, seeds: &[u32]) {
    for seed in seeds {
        let seed = format!("-Dseed={seed}");
        let image = java_image(d, "distributed.xml", &[&seed, flag], "160x120", "n.png");
        let (star, status) = judge(d, &image);
        assert_eq!(status, Some(1), "{flag} {seed}: {star}");
        assert_eq!(star["verdict"], "variant-draw", "{flag} {seed}: {star}");
        assert!(statistic(&star, "course") > 1.45, "{flag} {seed}: {star}");
        assert!(statistic(&star, name) < 1.45, "{flag} {seed}: {star}");
        let line = star["line"].as_str().expect("line");
        assert!(
            line.contains(&format!("but of {name}")),
            "{flag} {seed}: {line}"
        );
    }
}

#[test]
fn a_light_drawn_on_its_surface_is_named_for_two_seeds() {
    // The student's `randomInsideUnitSphere().normalised()`.
    let d = tempfile::tempdir().expect("tempdir");
    named_for_every_seed(
        d.path(),
        "-Dsoft=light-surface",
        "light-surface",
        &[501, 502],
    );
}

#[test]
fn shadow_counts_not_averaged_are_named_for_two_seeds() {
    let d = tempfile::tempdir().expect("tempdir");
    named_for_every_seed(
        d.path(),
        "-Dsoft=not-averaged",
        "shadows-not-averaged",
        &[511, 512],
    );
}

#[test]
fn a_specular_term_not_scaled_is_named_for_two_seeds() {
    let d = tempfile::tempdir().expect("tempdir");
    named_for_every_seed(
        d.path(),
        "-Dsoft=specular-not-scaled",
        "specular-not-scaled",
        &[521, 522],
    );
}

#[test]
fn a_focus_taken_as_a_distance_is_named_for_two_seeds() {
    // The student's `ray.evaluateAt(DOF_FOCAL_PLANE)`.
    let d = tempfile::tempdir().expect("tempdir");
    named_for_every_seed(
        d.path(),
        "-Ddof=focal-distance",
        "focal-distance",
        &[531, 532],
    );
}

#[test]
fn an_option_done_without_the_other_is_named_for_two_seeds() {
    let d = tempfile::tempdir().expect("tempdir");
    named_for_every_seed(d.path(), "-Ddof=none", "no-depth-of-field", &[501, 502]);
    named_for_every_seed(d.path(), "-Dsoft=none", "no-soft-shadows", &[503, 504]);
}

/// At 320x240 each process is scored on a grid of every third pixel first (the pre-pass) and
/// only the best in full: the correct program's draw and a variant's are still named, by their
/// full statistics, while the processes far from the image keep their grid's score.
#[test]
fn the_pre_pass_scores_far_processes_on_a_grid_and_names_the_right_one_in_full() {
    let d = tempfile::tempdir().expect("tempdir");
    let stride = |star: &Value, process: &str| -> u64 {
        star["fits"]
            .as_array()
            .and_then(|fits| fits.iter().find(|f| f["process"] == process))
            .and_then(|f| f["stride"].as_u64())
            .unwrap_or_else(|| panic!("no {process} stride in {star}"))
    };
    let ok = java_image(
        d.path(),
        "distributed.xml",
        &["-Dseed=701"],
        "320x240",
        "ok.png",
    );
    let (star, status) = judge(d.path(), &ok);
    assert_eq!(star["verdict"], "course-draw", "{star}");
    assert_eq!(status, Some(0));
    assert_eq!(stride(&star, "course"), 1, "{star}");
    let variant = java_image(
        d.path(),
        "distributed.xml",
        &["-Dseed=702", "-Ddof=not-averaged"],
        "320x240",
        "v.png",
    );
    let (star, status) = judge(d.path(), &variant);
    assert_eq!(status, Some(1), "{star}");
    assert_eq!(star["verdict"], "variant-draw", "{star}");
    assert!(statistic(&star, "dof-not-averaged") < 1.45, "{star}");
    assert_eq!(stride(&star, "dof-not-averaged"), 1, "{star}");
    // The course's process is far from it: scored on the grid alone.
    assert!(statistic(&star, "course") > 2.9, "{star}");
    assert_eq!(stride(&star, "course"), 3, "{star}");
    assert_eq!(stride(&star, "aperture-full-side"), 3, "{star}");
}

#[test]
fn a_bump_normal_of_a_sphere_at_the_origin_is_named_under_two_parametrisations() {
    // The student's `position.normalised()` for n: `check -i bump.xml IMAGE` names the
    // mistake and the parametrisation it was made in.
    let d = tempfile::tempdir().expect("tempdir");
    for param in ["y-xz", "z-yx"] {
        let flag = format!("-Dbump={param},no-centre");
        let image = java_image(
            d.path(),
            "bump.xml",
            &[&flag, "-Dsoft=none", "-Ddof=none"],
            "160x120",
            "b.png",
        );
        let out = whitted(
            d.path(),
            &[
                "check",
                "--course",
                YEAR,
                "-i",
                "bump.xml",
                "--json",
                s(&image),
            ],
        );
        assert_eq!(out.status.code(), Some(1), "{param}: {}", stderr(&out));
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            text.contains("bump-no-centre under parametrisation ") && text.contains(param),
            "{param}: {text}"
        );
    }
}

#[test]
fn the_java_bump_mapping_is_whitted_s_under_every_parametrisation() {
    // Until check judges option 1, this pins that our Java's getNormalAt is the method
    // docs/tick1star.md renders: pixel for pixel, under each parametrisation, and that a
    // mistake renders otherwise.
    let d = tempfile::tempdir().expect("tempdir");
    let render = |param: &str| -> Vec<u8> {
        let out = format!("w_{param}.png");
        let run = whitted(
            d.path(),
            &[
                "render",
                "--course",
                YEAR,
                "-i",
                "bump.xml",
                "-o",
                &out,
                "--bump-param",
                param,
                "--width",
                "160",
                "--height",
                "120",
            ],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        read_png(&d.path().join(out)).data
    };
    let params = [
        "y-zx",
        "y-zx-mirrored",
        "y-xz",
        "y-zx-from-x",
        "z-yx",
        "z-yx-from-x",
    ];
    let mut images = Vec::new();
    for param in params {
        let flag = format!("-Dbump={param}");
        let java = java_image(
            d.path(),
            "bump.xml",
            &[&flag, "-Dsoft=none", "-Ddof=none"],
            "160x120",
            "j.png",
        );
        let theirs = read_png(&java).data;
        assert!(
            theirs == render(param),
            "{param}: our Java differs from whitted's render"
        );
        images.push(theirs);
    }
    // The parametrisations lay the map differently: no two images alike.
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            assert!(images[i] != images[j], "{} = {}", params[i], params[j]);
        }
    }
    let inverted = java_image(
        d.path(),
        "bump.xml",
        &["-Dbump=y-zx,inverted", "-Dsoft=none", "-Ddof=none"],
        "160x120",
        "inv.png",
    );
    assert!(read_png(&inverted).data != images[0]);
}

#[test]
fn an_inverted_relief_says_where_and_what_to_change_and_no_tick1_diagnosis() {
    // The walkthrough's student: BumpySphere.getNormalAt with the relief's sign flipped.
    let d = tempfile::tempdir().expect("tempdir");
    let image = java_image(
        d.path(),
        "bump.xml",
        &["-Dbump=y-zx,inverted", "-Dsoft=none", "-Ddof=none"],
        "160x120",
        "b.png",
    );
    let out = whitted(
        d.path(),
        &["check", "--course", YEAR, "-i", "bump.xml", s(&image)],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    for words in [
        "progress: option 1 (bump mapping) with a mistake",
        "bump-inverted under parametrisation y-zx",
        "where: BumpySphere.getNormalAt",
        "fix: flip the sign of the perturbation",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
    for contradiction in ["diagnosis:", "spheres unknown", "shading unknown"] {
        assert!(!text.contains(contradiction), "{contradiction}: {text}");
    }
}

#[test]
fn list_bugs_has_a_tick1_star_section_with_where_and_fix() {
    let d = tempfile::tempdir().expect("tempdir");
    let out = whitted(d.path(), &["check", "--list-bugs", "--course", YEAR]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Tick 1* option 1 (bump mapping"), "{text}");
    assert!(
        text.contains("bump-colour-as-height") && text.contains("where: BumpySphere.getNormalAt"),
        "{text}"
    );
    let old = whitted(d.path(), &["check", "--list-bugs", "--course", "2016-17"]);
    assert!(!String::from_utf8_lossy(&old.stdout).contains("Tick 1*"));
}

#[test]
fn a_copy_of_distributed_xml_without_star_is_checked_as_option_2() {
    // The walkthrough's student: their own copy of the handout's scene (re-indented), a sharp
    // Tick 1 render of it, and no --star. The Tick 1 check would call it identical.
    let d = tempfile::tempdir().expect("tempdir");
    let xml = std::fs::read_to_string(scene("courses/tick1star/distributed.xml"))
        .expect("distributed.xml");
    std::fs::write(d.path().join("mine.xml"), xml.replace("    ", "\t")).expect("writes");
    let run = whitted(
        d.path(),
        &[
            "render",
            "--course",
            YEAR,
            "-i",
            "mine.xml",
            "-o",
            "sharp.png",
            "--width",
            "160",
            "--height",
            "120",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let out = whitted(
        d.path(),
        &["check", "--course", YEAR, "-i", "mine.xml", "sharp.png"],
    );
    let err = stderr(&out);
    assert!(
        err.contains("mine.xml is the handout's distributed.xml")
            && err.contains("checked as --star distributed"),
        "{err}"
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("option 2 not done"), "{text}");
    assert!(!text.contains("identical"), "{text}");
}

#[test]
fn a_bump_image_checked_with_no_scene_asks_whether_it_is_another_scene() {
    let d = tempfile::tempdir().expect("tempdir");
    let bump = scene("courses/tick1star/bump.xml");
    let run = whitted(
        d.path(),
        &["render", "--course", YEAR, "-i", s(&bump), "-o", "bump.png"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let out = whitted(d.path(), &["check", "--course", YEAR, "bump.png"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("is this another scene? give -i SCENE") && text.contains("-i bump.xml"),
        "{text}"
    );
    // The note and the verdict, and nothing that reads the image as the default scene's.
    assert!(text.contains(": differs (tolerance"), "{text}");
    for contradiction in [
        "progress:",
        "not written yet",
        "reflectivity",
        "candidate",
        "diagnosis:",
        "outside the catalogue",
    ] {
        assert!(!text.contains(contradiction), "{contradiction}: {text}");
    }
    let out = whitted(d.path(), &["check", "--course", YEAR, "--json", "bump.png"]);
    let json: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert!(
        json["another_scene"]
            .as_str()
            .is_some_and(|n| n.contains("is this another scene?")),
        "{json}"
    );
    assert_eq!(json["summary"].as_array().map(Vec::len), Some(1), "{json}");
    assert_eq!(json["diagnosis"], serde_json::json!([]), "{json}");
    assert_eq!(json["passed"], false, "{json}");
}
