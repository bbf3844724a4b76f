//! One pixel's ray tree in the course's model: the camera ray, every vertex of its mirror
//! chain (object, distance, P, N, material), every light's terms there (d, I, L, N.L, R.V,
//! diffuse, specular, and the shadow ray with what blocks it), and the fold that gives the
//! beauty. It is the renderer's own trace, observed (`trace::observe`), so the numbers are the
//! numbers the image is made of.

pub mod compare;
pub mod json;

use glam::DVec3;

use whitted_core::accel::Accelerator;
use whitted_core::error::{Error, Result};
use whitted_core::frame::{Acceleration, Frame, FrameSpec};
use whitted_core::geometry::Ray;
use whitted_core::model::Model;
use whitted_core::sample::Sample;
use whitted_core::scene::Scene;
use whitted_core::trace::observe::{FoldStep, LightRecord, Observer, VertexRecord};
use whitted_core::trace::trace_observed;

/// A light's terms at a vertex (with what shadows it), and the light's name.
#[derive(Debug, Clone, PartialEq)]
pub struct LightTerms {
    pub name: String,
    pub record: LightRecord,
}

/// A vertex and its lights.
#[derive(Debug, Clone, PartialEq)]
pub struct Vertex {
    pub record: VertexRecord,
    pub lights: Vec<LightTerms>,
}

/// The whole tree of one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Explanation {
    pub pixel: (u32, u32),
    pub camera_ray: Ray,
    pub vertices: Vec<Vertex>,
    /// Where the chain left the scene, if it did: (depth, ray).
    pub miss: Option<(u32, Ray)>,
    /// What a ray that leaves the scene sees under the model traced.
    pub background: DVec3,
    /// The beauty's fold, far end first.
    pub fold: Vec<FoldStep>,
    /// Every layer's value for this sample (the pixel, at one sample per pixel).
    pub sample: Sample,
    /// The beauty as `render` stores it in the EXR (f32).
    pub stored: [f32; 3],
}

/// Collects what the trace reports.
struct Recorder<'a> {
    scene: &'a Scene,
    pending: Vec<LightTerms>,
    vertices: Vec<Vertex>,
    miss: Option<(u32, Ray)>,
    fold: Vec<FoldStep>,
}

impl Observer for Recorder<'_> {
    const RECORDS_OCCLUDERS: bool = true;

    fn light(&mut self, record: LightRecord) {
        self.pending.push(LightTerms {
            name: self.scene.lights[record.light].name.clone(),
            record,
        });
    }

    fn vertex(&mut self, record: VertexRecord) {
        let lights = std::mem::take(&mut self.pending);
        self.vertices.push(Vertex { record, lights });
    }

    fn miss(&mut self, depth: u32, ray: Ray) {
        self.miss = Some((depth, ray));
    }

    fn fold(&mut self, step: FoldStep) {
        self.fold.push(step);
    }
}

/// Explains pixel (x, y) of `scene` rendered as `spec` says (one sample at the pixel centre)
/// under `model`'s rules: the course's ([`whitted_core::model::Tick`]), or a student's mistakes.
pub fn explain(
    model: &impl Model,
    scene: &Scene,
    spec: &FrameSpec,
    x: u32,
    y: u32,
) -> Result<Explanation> {
    let frame = Frame::new(scene, spec)?;
    if x >= frame.camera().width || y >= frame.camera().height {
        return Err(Error::Usage(format!(
            "the pixel {x},{y} is outside the {}x{} image",
            frame.camera().width,
            frame.camera().height
        )));
    }
    // `Mistakes::frame_spec` asks for brute force where the model needs it.
    let accel = match frame.acceleration() {
        Acceleration::Bvh => Accelerator::build(&scene.objects),
        Acceleration::BruteForce => Accelerator::brute_force(&scene.objects),
    };
    let camera_ray = frame.camera().pixel_centre_ray(x, y);
    let mut sample = Sample::empty(scene.lights.len(), frame.trace().bounces);
    let mut recorder = Recorder {
        scene,
        pending: Vec::new(),
        vertices: Vec::new(),
        miss: None,
        fold: Vec::new(),
    };
    trace_observed::<true>(
        model,
        scene,
        &accel,
        camera_ray,
        frame.trace(),
        &mut sample,
        &mut recorder,
    );
    let stored = sample.beauty.to_array().map(|v| {
        if v.is_finite() {
            v.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32
        } else {
            0.0
        }
    });
    Ok(Explanation {
        pixel: (x, y),
        camera_ray,
        vertices: recorder.vertices,
        miss: recorder.miss,
        background: model.background(),
        fold: recorder.fold,
        sample,
        stored,
    })
}

impl Explanation {
    /// The fold of docs/rendering.md's Reflection as the trace evaluated it, far end first.
    pub fn fold(&self) -> Vec<String> {
        let background = self
            .miss
            .map(|(depth, _)| format!("depth {depth}: background {}", vector(self.background)));
        let steps = self.fold.iter().map(|step| match step.reflectivity {
            Some(r) => format!(
                "depth {}: {} * (1 - {r}) + {} * {r} = {}",
                step.depth,
                vector(step.colour),
                vector(step.reflected),
                vector(step.result)
            ),
            None => format!(
                "depth {}: {} (the chain ends here)",
                step.depth,
                vector(step.colour)
            ),
        });
        background.into_iter().chain(steps).collect()
    }
}

/// A vector as `(x, y, z)` with every digit.
pub fn vector(v: DVec3) -> String {
    format!("({}, {}, {})", v.x, v.y, v.z)
}
