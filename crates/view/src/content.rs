//! What the viewer shows, and where it comes from: the image, its reference, the ray tracer a
//! click asks (when the scene is known) and, in check mode, the check's report. `Source`
//! names the files; `Source::load` reads them, once at the start and again whenever
//! `--watch` sees one change.

use std::path::{Path, PathBuf};

use serde_json::Value;

use whitted_check::check::pass_rule::PassRule;
use whitted_check::check::{check_image, print::json::case_json, student_png, which_course, words};
use whitted_check::mistakes::Mistakes;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::fingerprint::fingerprint;
use whitted_core::frame::FrameSpec;
use whitted_core::scene::{self, Scene};
use whitted_io::input::{self, raster, Attribute, Image};

/// Where the viewer's images come from.
#[derive(Debug, Clone)]
pub enum Source {
    /// `whitted view IMAGE [--reference REF] [-i SCENE]`.
    View {
        image: PathBuf,
        reference: Option<PathBuf>,
        scene: Option<PathBuf>,
    },
    /// `whitted check IMAGE.png [-i SCENE] --view`: the student's image against the reference
    /// rendered at its size.
    Check {
        image: PathBuf,
        scene: Option<PathBuf>,
        bounces: u32,
        /// When the image passes (`--tolerance`, `--max-beyond`).
        rule: PassRule,
        /// `--course` (None: read from the image's size and the scene, as `check` does).
        course: Option<Course>,
    },
}

/// The scene and frame a pixel's ray tree is traced in, and the mistakes of the second tree
/// (the check's top diagnosis; none outside check mode).
#[derive(Debug, Clone)]
pub struct Tracer {
    pub scene: Scene,
    pub frame: FrameSpec,
    pub mistakes: Mistakes,
    /// Where the image's pixel (0, 0) is in the frame: a farm node's region EXR holds a
    /// part of it.
    pub origin: [u32; 2],
}

/// Everything one load read.
pub struct Content {
    pub main: Image,
    pub reference: Option<Image>,
    pub tracer: Option<Tracer>,
    /// The check's report, as `whitted check --json` prints it.
    pub check: Option<Value>,
    /// The names the page shows for the image and the reference.
    pub labels: [String; 2],
}

impl Source {
    /// The files whose change means a reload.
    pub fn watched(&self) -> Vec<PathBuf> {
        match self {
            Source::View {
                image, reference, ..
            } => std::iter::once(image).chain(reference).cloned().collect(),
            Source::Check { image, .. } => vec![image.clone()],
        }
    }

    /// What a load reads, for the page to say while it runs.
    pub fn describe(&self) -> String {
        match self {
            Source::View {
                image,
                reference: None,
                ..
            } => file_name(image),
            Source::View {
                image,
                reference: Some(reference),
                ..
            } => format!("{} and {}", file_name(image), file_name(reference)),
            Source::Check { image, .. } => format!("{} (and checking it)", file_name(image)),
        }
    }

    /// Reads (and in check mode checks) the files.
    pub fn load(&self) -> Result<Content> {
        match self {
            Source::View {
                image,
                reference,
                scene,
            } => load_view(image, reference.as_deref(), scene.as_deref()),
            Source::Check {
                image,
                scene,
                bounces,
                rule,
                course,
            } => load_check(image, scene.as_deref(), *bounces, *rule, *course),
        }
    }
}

fn file_name(path: &Path) -> String {
    path.display().to_string()
}

fn load_view(image: &Path, reference: Option<&Path>, scene: Option<&Path>) -> Result<Content> {
    let main = input::read(image)?;
    let other = match reference {
        None => None,
        Some(path) => Some(conform(&main, input::read(path)?).map_err(|why| {
            Error::Usage(format!(
                "{} cannot be compared with {}: {why}",
                path.display(),
                image.display()
            ))
        })?),
    };
    let tracer = recorded_tracer(&main, image, scene)?;
    Ok(Content {
        main,
        reference: other,
        tracer,
        check: None,
        labels: [
            file_name(image),
            reference.map_or_else(String::new, file_name),
        ],
    })
}

fn load_check(
    image: &Path,
    scene: Option<&Path>,
    bounces: u32,
    rule: PassRule,
    course: Option<Course>,
) -> Result<Content> {
    let student = student_png::read(image)?;
    let scene_bytes = scene.map(scene::read_file).transpose()?;
    let size = (student.width, student.height);
    let chosen = which_course::for_image(course, size, scene_bytes.as_deref())?;
    let input = scene::input::input_of(scene, scene_bytes, chosen.course)?;
    let (case, findings) = check_image(
        &input.scene,
        &input.name,
        bounces,
        rule,
        student,
        chosen.course,
    )?;
    let (width, height) = (case.student.width, case.student.height);
    let as_image = |bytes: &[u8]| raster::rgb8(width as usize, height as usize, bytes);
    let mistakes = case
        .diagnosis
        .first()
        .map_or(Mistakes::NONE, |d| d.mistakes);
    let mut report = case_json(&case, Some(&findings));
    // What each named mistake is, for the panel (the JSON of `check` names them by id).
    let named: serde_json::Map<String, Value> = case
        .diagnosis
        .iter()
        .flat_map(|d| d.mistakes.bugs())
        .map(|b| {
            (
                b.id().to_string(),
                Value::from(b.description(chosen.course)),
            )
        })
        .collect();
    report["descriptions"] = Value::Object(named);
    report["course"] = Value::from(chosen.course.name());
    if let Some(why) = chosen.why {
        report["course_chosen_because"] = Value::from(why);
    }
    // The check's own sentence for a passing image that hides a mistake.
    if let Some(line) = words::passes_but_hidden(&case) {
        report["hidden_text"] = Value::from(line);
    }
    Ok(Content {
        main: as_image(&case.student.bytes),
        reference: Some(as_image(&case.reference.bytes)),
        check: Some(report),
        tracer: Some(Tracer {
            scene: input.scene,
            frame: FrameSpec {
                course: chosen.course,
                ..FrameSpec::tick(width, height, bounces, true)
            },
            mistakes,
            origin: [0, 0],
        }),
        labels: [file_name(image), format!("reference ({})", input.name)],
    })
}

fn text_attribute<'a>(image: &'a Image, name: &str) -> Option<&'a str> {
    match image.attribute(name)? {
        Attribute::Text(t) => Some(t.as_str()),
        _ => None,
    }
}

/// The tracer of a whitted EXR whose recorded scene (`render/scene`, a fingerprint of the
/// scene file's bytes) is `scene`, or the embedded tick2 scene when none is given and it is
/// that one. A scene that is not the recorded one is refused: its trees would explain another
/// image. Files without the record (PNGs, other programs' EXRs) have no tracer unless a scene
/// is given, and then only as a course render of that size.
fn recorded_tracer(image: &Image, path: &Path, scene: Option<&Path>) -> Result<Option<Tracer>> {
    let recorded = text_attribute(image, "render/scene");
    // The year the EXR was rendered under: its rules and scene format trace its trees.
    let course = image.course(path)?;
    let embedded = course.default_scene().0.as_bytes();
    let input = match (scene, recorded) {
        (Some(scene), _) => scene::input::load_input(Some(scene), course)?,
        (None, Some(print)) if print == fingerprint(&[embedded]) => {
            scene::input::load_input(None, course)?
        }
        (None, _) => return Ok(None),
    };
    if let Some(print) = recorded {
        if print != fingerprint(&[&input.bytes]) {
            return Err(Error::Usage(format!(
                "{} was not rendered from {}: its recorded scene fingerprint is {print}",
                path.display(),
                input.name
            )));
        }
    }
    let bounces = match image.attribute("render/bounces") {
        Some(Attribute::Integer(b)) => u32::try_from(*b).ok(),
        _ => None,
    }
    .unwrap_or(FrameSpec::default().bounces);
    // The writer's own attribute (docs/aovs.md), not the free-text command in `comments`.
    let shadows = match image.attribute("render/shadows") {
        Some(Attribute::Integer(on)) => *on != 0,
        _ => FrameSpec::default().shadows,
    };
    let window = image.display_window;
    let side = |axis: usize| {
        u32::try_from(window.max[axis] - window.min[axis] + 1)
            .map_err(|_| Error::Usage(format!("{}: no render has that size", path.display())))
    };
    let frame = FrameSpec {
        course,
        ..FrameSpec::tick(side(0)?, side(1)?, bounces, shadows)
    };
    whitted_core::frame::Frame::new(&input.scene, &frame)?;
    let data = image.data_window;
    let offset = |axis: usize| u32::try_from(data.min[axis] - window.min[axis]).ok();
    let (Some(x), Some(y)) = (offset(0), offset(1)) else {
        // Pixels outside the frame: no tree to show for them.
        return Ok(None);
    };
    Ok(Some(Tracer {
        scene: input.scene,
        frame,
        mistakes: Mistakes::NONE,
        origin: [x, y],
    }))
}

/// The reference with the image's channels in the image's order, so that every layer the page
/// asks for has one layout in both (the page reads the reference with the image's channel
/// list). It must have the same size and the same layers; an alpha channel it lacks is 1 (a
/// PNG without alpha is opaque), any other missing channel is refused, and its extra channels
/// are not shown.
fn conform(main: &Image, mut reference: Image) -> std::result::Result<Image, String> {
    if (main.width, main.height) != (reference.width, reference.height) {
        return Err(format!(
            "it is {}x{}, the image {}x{}",
            reference.width, reference.height, main.width, main.height
        ));
    }
    let names =
        |image: &Image| -> Vec<String> { image.layers().into_iter().map(|l| l.name).collect() };
    let (ours, theirs) = (names(main), names(&reference));
    if ours != theirs {
        let missing: Vec<&String> = ours.iter().filter(|n| !theirs.contains(n)).collect();
        let extra: Vec<&String> = theirs.iter().filter(|n| !ours.contains(n)).collect();
        return Err(format!(
            "its layers differ (missing: {missing:?}; not in the image: {extra:?})"
        ));
    }
    let mut channels = Vec::with_capacity(main.channels.len());
    for wanted in &main.channels {
        let found = reference
            .channels
            .iter()
            .position(|c| c.name == wanted.name);
        let channel = match found {
            Some(i) => reference.channels.swap_remove(i),
            None if whitted_io::input::suffix(&wanted.name) == "A" => whitted_io::input::Channel {
                name: wanted.name.clone(),
                pixel_type: wanted.pixel_type,
                values: vec![1.0; main.width * main.height],
            },
            None => return Err(format!("it has no channel {}", wanted.name)),
        };
        channels.push(channel);
    }
    reference.channels = channels;
    Ok(reference)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reference_takes_the_images_channel_layout() {
        let mut rgba = raster::rgb8(1, 1, &[10, 20, 30]);
        rgba.channels.push(whitted_io::input::Channel {
            name: "A".into(),
            pixel_type: "uint8",
            values: vec![0.5],
        });
        rgba.channels.swap(0, 2); // B G R A, as a file may store them
        let rgb = raster::rgb8(1, 1, &[40, 50, 60]);
        let conformed = conform(&rgba, rgb.clone()).expect("conforms");
        let names: Vec<&str> = conformed.channels.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["B", "G", "R", "A"]);
        assert_eq!(conformed.channels[0].values, [60.0 / 255.0]);
        assert_eq!(conformed.channels[3].values, [1.0]);
        // The other way round, the alpha is not shown.
        assert_eq!(conform(&rgb, rgba).expect("conforms").channels.len(), 3);
        let other_size = raster::rgb8(2, 1, &[0; 6]);
        assert!(conform(&rgb, other_size).is_err());
        let mut no_green = raster::rgb8(1, 1, &[1, 2, 3]);
        no_green.channels.remove(1);
        assert_eq!(
            conform(&rgb, no_green).err().as_deref(),
            Some("it has no channel G")
        );
    }
}
