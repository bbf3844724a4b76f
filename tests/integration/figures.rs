//! tools/figures reproduces the handout's figures (and the README's pictures) from renders.

use crate::common::*;

#[test]
fn figures_are_labelled_strips_of_distinct_panels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = std::process::Command::new("bash")
        .arg(root().join("tools/figures"))
        .arg(dir.path())
        .env("WHITTED", env!("CARGO_BIN_EXE_whitted"))
        .output()
        .expect("tools/figures runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    // (file, panels): 320x240 tiles under 24-pixel captions, 8-pixel margins.
    for (file, panels) in [("figure2.png", 4), ("figure3.png", 3), ("figure4.png", 3)] {
        let png = read_png(&dir.path().join(file));
        assert_eq!(
            (png.width, png.height),
            (panels * 320 + (panels + 1) * 8, 240 + 24 + 16),
            "{file}"
        );
        let panel = |i: u32| -> Vec<u8> {
            let x0 = (8 + i * 328) as usize;
            (8 + 24..8 + 24 + 240usize)
                .flat_map(|y| {
                    png.data
                        [(y * png.width as usize + x0) * 3..(y * png.width as usize + x0 + 320) * 3]
                        .to_vec()
                })
                .collect()
        };
        let all: Vec<Vec<u8>> = (0..panels).map(panel).collect();
        for i in 0..all.len() {
            for j in i + 1..all.len() {
                assert_ne!(all[i], all[j], "{file}: panels {i} and {j} are identical");
            }
        }
    }
    // The last panel of figure 4 (2 bounces) is the tick image itself, pixel for pixel.
    let strip = read_png(&dir.path().join("figure4.png"));
    let tick = read_png(&reference("tick2_b2.png"));
    let tick_channels = if tick.color == png::ColorType::Rgba {
        4
    } else {
        3
    };
    // Tiles are box-filtered 2:1 from 640x480; compare one tile pixel with its 2x2 source.
    let (tx, ty) = (160usize, 120usize);
    let x0 = 8 + 2 * 328;
    let got = &strip.data[((8 + 24 + ty) * strip.width as usize + x0 + tx) * 3..][..3];
    for (c, &g) in got.iter().enumerate() {
        let source: f64 = [(0, 0), (1, 0), (0, 1), (1, 1)]
            .iter()
            .map(|(dx, dy)| {
                f64::from(tick.data[((2 * ty + dy) * 640 + 2 * tx + dx) * tick_channels + c])
            })
            .sum::<f64>()
            / 4.0;
        assert!(
            (f64::from(g) - source).abs() <= 1.0,
            "channel {c}: {g} vs {source}"
        );
    }
    for extra in [
        "sheet.png",
        "tick2.png",
        "tonemap_agx.png",
        "mirror_floor.png",
    ] {
        assert!(dir.path().join(extra).exists(), "{extra}");
    }
}
