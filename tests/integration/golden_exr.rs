//! Golden EXRs: every scene in `scenes/` re-rendered with every AOV and compared with its
//! reference in `reference/exr/` (written only by `tools/bless`), by `whitted diff` and by
//! OpenImageIO's `idiff`. Tolerance: a value fails when off by more than 1e-6 absolute and
//! 1e-5 relative (docs/aovs.md), which allows for another machine's libm, nothing more.
//! On failure the actual EXR and a heat map are kept in `target/golden-failures/`.

use std::path::Path;

use crate::common::*;

fn render_args() -> Vec<String> {
    let text =
        std::fs::read_to_string(reference("exr/render-args")).expect("reference/exr/render-args");
    text.split_whitespace().map(String::from).collect()
}

fn check_scene(name: &str, dir: &Path) -> Result<(), String> {
    let golden = reference(&format!("exr/{name}.exr"));
    if !golden.exists() {
        return Err(format!("{name}: no reference EXR; run tools/bless"));
    }
    let args = render_args();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let actual = render_exr(
        dir,
        &scene(&format!("{name}.xml")),
        &format!("{name}.exr"),
        &args,
    );
    let heatmap = dir.join(format!("{name}_heatmap.png"));
    let ours = whitted(
        dir,
        &[
            "diff",
            s(&actual),
            s(&golden),
            "--abs",
            "1e-6",
            "--rel",
            "1e-5",
            "--heatmap",
            s(&heatmap),
        ],
    );
    let theirs = idiff_aov(&actual, &golden);
    if ours.status.code() == Some(0) && theirs.status.code() == Some(0) {
        return Ok(());
    }
    let keep = root().join("target/golden-failures");
    std::fs::create_dir_all(&keep).map_err(|e| e.to_string())?;
    let kept_exr = keep.join(format!("{name}.exr"));
    let kept_heatmap = keep.join(format!("{name}_heatmap.png"));
    std::fs::copy(&actual, &kept_exr).map_err(|e| e.to_string())?;
    if heatmap.exists() {
        std::fs::copy(&heatmap, &kept_heatmap).map_err(|e| e.to_string())?;
    }
    Err(format!(
        "{name}: differs from {} (whitted diff exit {:?}, idiff exit {:?}); actual EXR kept at {}, \
         heat map at {}\n{}{}",
        golden.display(),
        ours.status.code(),
        theirs.status.code(),
        kept_exr.display(),
        kept_heatmap.display(),
        String::from_utf8_lossy(&ours.stdout),
        String::from_utf8_lossy(&theirs.stdout),
    ))
}

#[test]
fn every_scene_matches_its_reference_exr() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut names: Vec<String> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        // scenes/check/ holds the tester's suite, which the check tests cover.
        .filter(|p| p.is_file())
        .filter_map(|p| p.file_stem()?.to_str().map(String::from))
        .collect();
    names.sort();
    assert!(names.len() >= 7, "{names:?}");
    let failures: Vec<String> = names
        .iter()
        .filter_map(|n| check_scene(n, dir.path()).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn a_changed_render_is_caught_and_kept_for_inspection() {
    // The same machinery on a deliberately different render must fail and say where.
    let dir = tempfile::tempdir().expect("tempdir");
    let mut args = render_args();
    args.push("--no-shadows".into());
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let actual = render_exr(dir.path(), &scene("tick2.xml"), "changed.exr", &args);
    let golden = reference("exr/tick2.exr");
    let heatmap = dir.path().join("heat.png");
    let run = whitted(
        dir.path(),
        &["diff", s(&actual), s(&golden), "--heatmap", s(&heatmap)],
    );
    assert_eq!(run.status.code(), Some(1));
    let report = String::from_utf8_lossy(&run.stdout).into_owned();
    assert!(
        report.contains("FAIL") && report.lines().any(|l| l.starts_with("shadow_0")),
        "{report}"
    );
    let idiff = run_tool(
        "idiff",
        &[
            "-fail",
            "1e-6",
            "-failrelative",
            "1e-5",
            s(&actual),
            s(&golden),
        ],
        dir.path(),
    );
    assert_ne!(idiff.status.code(), Some(0));
    assert!(heatmap.exists());
}
