//! What an EXR records about the render that made it (docs/aovs.md, Header attributes): the
//! program, the command that reproduces its pixels, the capture date when asked for.

use std::time::SystemTime;

use crate::output::exr::ExrMetadata;
use crate::plan::RenderPlan;
use whitted_core::aov;
use whitted_core::fingerprint::fingerprint;

/// The header metadata of `plan`'s EXR. `scene_name` is the scene file as given (or the
/// embedded scene's name), `scene_bytes` its content; `light_names` in layer order.
pub fn metadata(
    plan: &RenderPlan,
    scene_name: &str,
    scene_bytes: &[u8],
    light_names: Vec<String>,
) -> ExrMetadata {
    let catalogue = aov::all_layers(&light_names, plan.frame.trace().bounces);
    let aovs = aov::selection_spec(plan.frame.layers(), &catalogue);
    let command = render_command(plan, &aovs, Some(scene_name));
    // The scene's content, not its path: parts rendered on machines that mount the scene in
    // different places are still one render.
    let options = render_command(plan, &aovs, None);
    let scene = fingerprint(&[scene_bytes]);
    ExrMetadata {
        software: format!("whitted {}", env!("CARGO_PKG_VERSION")),
        identity: fingerprint(&[scene.as_bytes(), options.as_bytes()]),
        scene,
        comments: format!("scene: {scene_name}; command: {command}"),
        bounces: plan.frame.trace().bounces,
        spp: plan.frame.spp(),
        shadows: plan.frame.trace().shadows,
        light_names,
        capture_date: plan.stamp_date.then(|| capture_date(SystemTime::now())),
        world_to_ndc: plan.frame.camera().world_to_ndc(),
        course: plan.frame.course(),
    }
}

/// The command that reproduces these pixels: every option that changes them, in canonical
/// form. Output paths, threads and verbosity are left out, so that the same render written
/// elsewhere, or with another thread count, has the same bytes. The region is left out too:
/// a region's header is the full render's, which is what lets `merge` reproduce it. With no
/// `scene_name`, the scene is left out too. `aovs` is the canonical `--aovs` of the layers
/// (`aov::selection_spec`), so that `direct,Z` and `Z,direct` are one render.
fn render_command(plan: &RenderPlan, aovs: &str, scene_name: Option<&str>) -> String {
    let quote = |a: &str| {
        if a.contains(char::is_whitespace) {
            format!("'{a}'")
        } else {
            a.to_string()
        }
    };
    let frame = &plan.frame;
    let mut parts = vec!["whitted render".to_string()];
    let course = frame.course();
    if !course.is_default() {
        parts.push(format!("--course {course}"));
    }
    match scene_name {
        Some(_) if plan.embedded_scene && course.is_default() => {
            parts.push("(embedded tick2.xml)".to_string())
        }
        Some(_) if plan.embedded_scene => parts.push(format!("({})", course.default_scene().1)),
        Some(name) => parts.push(format!("--input {}", quote(name))),
        None => {}
    }
    parts.extend([
        format!("--bounces {}", frame.trace().bounces),
        format!(
            "--width {} --height {}",
            frame.camera().width,
            frame.camera().height
        ),
        format!("--spp {}", frame.spp()),
    ]);
    if !frame.trace().shadows {
        parts.push("--no-shadows".into());
    }
    parts.push(format!("--aovs {}", quote(aovs)));
    if plan.exr_options.half {
        parts.push("--half".into());
    }
    parts.push(format!(
        "--compression {}",
        plan.exr_options.compression.name()
    ));
    parts.join(" ")
}

/// `YYYY:MM:DD hh:mm:ss` in UTC, as OpenEXR's `capDate` wants (with `utcOffset` 0).
fn capture_date(now: SystemTime) -> String {
    let secs = now
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let (year, month, day) = whitted_core::calendar::civil_from_days(days as i64);
    format!(
        "{year:04}:{month:02}:{day:02} {:02}:{:02}:{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn capture_dates_are_civil_utc() {
        let at = |secs| capture_date(SystemTime::UNIX_EPOCH + Duration::from_secs(secs));
        assert_eq!(at(0), "1970:01:01 00:00:00");
        assert_eq!(at(951_782_400), "2000:02:29 00:00:00");
        assert_eq!(at(1_795_000_000), "2026:11:18 11:06:40");
    }
}
