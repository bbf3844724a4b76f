//! The fast paths give the slow paths' answers: the hierarchy renders what brute force
//! renders, regions merge into the full frame byte for byte, and supersampling keeps the
//! exact tick image at one sample and unblended data layers at many.

use crate::common::*;
use whitted_core::film::Film;
use whitted_core::frame::{Acceleration, FrameSpec};
use whitted_core::render::RenderStats;
use whitted_core::scene::{self, Scene};

/// The benchmark scene of `n` spheres, from the one generator (tools/sphere_grid.py).
fn sphere_grid(n: usize) -> String {
    let run = run_tool("python", &["tools/sphere_grid.py", &n.to_string()], &root());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).expect("utf-8")
}

fn film(scene: &Scene, acceleration: Acceleration, spp: u32) -> (Film, RenderStats) {
    let spec = FrameSpec {
        width: 96,
        height: 72,
        spp,
        bounces: 3,
        acceleration,
        ..FrameSpec::default()
    };
    render_frame(scene, &spec)
}

#[test]
fn hierarchy_and_brute_force_render_identical_films() {
    for source in [
        sphere_grid(144),
        std::fs::read_to_string(scene("tick2.xml")).expect("tick2"),
    ] {
        let scene = scene::parse_str("grid.xml", &source).expect("valid");
        let (fast, fast_stats) = film(&scene, Acceleration::Bvh, 1);
        let (slow, slow_stats) = film(&scene, Acceleration::BruteForce, 1);
        assert_eq!(fast.beauty, slow.beauty);
        assert!(fast.data == slow.data, "AOV layers differ");
        assert_eq!(fast_stats.rays, slow_stats.rays);
    }
}

#[test]
fn regions_merge_byte_identically_to_the_full_frame() {
    let dir = tempfile::tempdir().expect("tempdir");
    let tick2 = scene("tick2.xml");
    let full = render_exr(dir.path(), &tick2, "full.exr", &["--spp", "4"]);
    let parts = [
        ("a.exr", "0,0,640,123"),
        ("b.exr", "0,123,333,480"),
        ("c.exr", "333,123,640,480"),
    ];
    let mut names = Vec::new();
    for (name, region) in parts {
        let part = render_exr(
            dir.path(),
            &tick2,
            name,
            &["--spp", "4", "--region", region],
        );
        names.push(part.to_str().expect("utf-8").to_string());
    }
    let part = read_exr(&dir.path().join("b.exr"));
    assert_eq!((part.width, part.height), (333, 357));
    assert_eq!(part.layer.layer_position, exr::prelude::Vec2(0, 123));

    let mut args = vec!["merge"];
    args.extend(names.iter().map(String::as_str));
    args.extend(["-o", "merged.exr"]);
    let run = whitted(dir.path(), &args);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(
        std::fs::read(full).expect("full")
            == std::fs::read(dir.path().join("merged.exr")).expect("merged")
    );

    // Gaps and overlaps are refused, naming a pixel.
    let run = whitted(
        dir.path(),
        &["merge", &names[0], &names[1], "-o", "gap.exr"],
    );
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("no part covers pixel (333, 123)"),
        "{}",
        stderr(&run)
    );
    let run = whitted(
        dir.path(),
        &[
            "merge",
            &names[0],
            &names[0],
            &names[1],
            &names[2],
            "-o",
            "twice.exr",
        ],
    );
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("both cover pixel (0, 0)"),
        "{}",
        stderr(&run)
    );
    assert!(!dir.path().join("gap.exr").exists() && !dir.path().join("twice.exr").exists());
    let run = whitted(
        dir.path(),
        &["render", "--region", "600,0,700,10", "-o", "x.png"],
    );
    assert_eq!(run.status.code(), Some(2));
}

#[test]
fn supersampling_averages_colour_and_keeps_data_unblended() {
    let scene = scene::parse_str("grid.xml", &sphere_grid(36)).expect("valid");
    let (one, _) = film(&scene, Acceleration::Bvh, 1);
    let (nine, _) = film(&scene, Acceleration::Bvh, 9);
    // With an odd grid the centre sample is the tick ray itself: data layers match exactly.
    for name in ["Z", "P.X", "P.Y", "P.Z", "objectid.X"] {
        assert!(one.channel(name) == nine.channel(name), "{name} differs");
    }
    // Colour is averaged: edges soften, so some pixels change, by bounded amounts.
    let (a, b) = (one.channel("R").expect("R"), nine.channel("R").expect("R"));
    let changed = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert!(changed > a.len() / 20, "only {changed} pixels changed");
    // Object ids stay whole numbers: never a blend of two objects.
    let ids = nine.channel("objectid.X").expect("ids");
    assert!(ids.iter().all(|v| v.fract() == 0.0));
    let mean = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
    assert!(
        (mean(&a) - mean(&b)).abs() < 0.02,
        "the average brightness is kept"
    );
}

#[test]
fn regions_lists_a_balanced_split_that_merges_into_the_frame() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(
        dir.path(),
        &["regions", "--parts", "3", "--width", "64", "--height", "50"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let lines: Vec<String> = String::from_utf8_lossy(&run.stdout)
        .lines()
        .map(str::to_string)
        .collect();
    assert_eq!(lines, ["0,0,64,16", "0,16,64,33", "0,33,64,50"]);
    let tick2 = scene("tick2.xml");
    let mut parts = Vec::new();
    for (i, region) in lines.iter().enumerate() {
        let name = format!("part{i}.exr");
        let size = ["--width", "64", "--height", "50", "--region", region];
        render_exr(dir.path(), &tick2, &name, &size);
        parts.push(name);
    }
    let full = render_exr(
        dir.path(),
        &tick2,
        "full.exr",
        &["--width", "64", "--height", "50"],
    );
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "merged.exr"]);
    assert!(whitted(dir.path(), &args).status.success());
    assert!(
        std::fs::read(full).expect("full")
            == std::fs::read(dir.path().join("merged.exr")).expect("merged")
    );
    let run = whitted(dir.path(), &["regions", "--parts", "60", "--height", "50"]);
    assert_eq!(run.status.code(), Some(2));
}

/// Writes a 4x4 multi-part EXR, one part per (name, value of its R channel).
fn multi_part_exr(path: &std::path::Path, parts: &[(&str, f32)]) {
    use exr::prelude::*;
    let layers = parts
        .iter()
        .map(|&(name, value)| {
            let channel = AnyChannel::new("R", FlatSamples::F32(vec![value; 16]));
            Layer::new(
                (4, 4),
                LayerAttributes::named(name),
                Encoding::FAST_LOSSLESS,
                AnyChannels::sort(smallvec::smallvec![channel]),
            )
        })
        .collect::<Vec<_>>();
    let image = Image::from_layers(
        ImageAttributes::new(IntegerBounds::from_dimensions((4, 4))),
        layers,
    );
    image.write().to_file(path).expect("multi-part EXR");
}

#[test]
fn merge_refuses_standard_output_and_multi_part_inputs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    multi_part_exr(&d.join("two.exr"), &[("a", 0.5), ("b", 0.5)]);
    let run = whitted(d, &["merge", "two.exr", "-o", "out.exr"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("has 2 parts"), "{}", stderr(&run));
    assert!(!d.join("out.exr").exists());
    let run = whitted(d, &["merge", "two.exr", "-o", "-"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("standard output"), "{}", stderr(&run));
}

#[test]
fn the_diff_heat_map_is_of_the_parts_the_comparison_pairs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // The same part names in another order; part `a` differs.
    multi_part_exr(&d.join("actual.exr"), &[("b", 0.5), ("a", 0.9)]);
    multi_part_exr(&d.join("reference.exr"), &[("a", 0.5), ("b", 0.5)]);
    let run = whitted(
        d,
        &[
            "diff",
            "actual.exr",
            "reference.exr",
            "--heatmap",
            "heat.png",
        ],
    );
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let heat = read_png(&d.join("heat.png"));
    assert!(
        heat.data.iter().any(|&b| b != 0),
        "the heat map shows no difference"
    );
}

#[test]
fn parts_asked_for_the_same_layers_in_any_order_merge() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let tick2 = scene("tick2.xml");
    let size = ["--width", "32", "--height", "20"];
    let top = [&size[..], &["--region", "0,0,32,10", "--aovs", "direct,Z"]].concat();
    let bottom = [
        &size[..],
        &["--region", "0,10,32,20", "--aovs", "Z, direct"],
    ]
    .concat();
    render_exr(d, &tick2, "top.exr", &top);
    render_exr(d, &tick2, "bottom.exr", &bottom);
    let run = whitted(d, &["merge", "top.exr", "bottom.exr", "-o", "full.exr"]);
    assert!(run.status.success(), "{}", stderr(&run));
}
