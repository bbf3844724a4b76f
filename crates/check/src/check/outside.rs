//! What lies outside the catalogue, located (docs/check.md, "Beyond the catalogue"): when no
//! catalogued candidate explains the images well, the differing pixels the best one leaves
//! unexplained are looked up in the reference's own trace, which knows the object each pixel
//! shows, and said by kind of object, with whether the student's are darker or brighter. A
//! mistake nobody catalogued is thus said to be one, and where, rather than dressed up as
//! catalogued ones: differences on every plane and nothing else point at what planes share
//! (their material, as an edited loader or skeleton class sets it).

use crate::check::case::Case;
use crate::check::difference::pixel_difference;
use crate::mistakes::{Mistakes, Variant};
use whitted_core::error::Result;
use whitted_core::geometry::Shape;

/// A kind that holds this share of what is left is the story's place.
const MOSTLY: f64 = 0.8;

/// What the reference shows where a difference is left.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Sphere,
    Plane,
    Background,
}

impl Kind {
    fn words(self) -> &'static str {
        match self {
            Kind::Sphere => "spheres",
            Kind::Plane => "planes",
            Kind::Background => "the background",
        }
    }
}

/// The differing pixels the best explanation leaves, located.
#[derive(Debug, Clone, PartialEq)]
pub struct Outside {
    /// Their share of the differing pixels.
    pub share: f64,
    /// Per kind of object, its share of them (largest first).
    pub on: Vec<(Kind, f64)>,
    /// Of them, the share where the student's pixel is darker than the reference's.
    pub darker: f64,
}

impl Outside {
    /// Locates what `top` (the best catalogued explanation, perhaps none) leaves of `cases`'
    /// sampled differing pixels; None when it leaves nothing.
    pub fn of(cases: &[Case], top: Mistakes) -> Result<Option<Outside>> {
        let (mut left, mut all, mut darker) = (0.0, 0.0, 0.0);
        let mut on = vec![
            (Kind::Sphere, 0.0),
            (Kind::Plane, 0.0),
            (Kind::Background, 0.0),
        ];
        for case in cases {
            let sample = &case.sample;
            let wrong = &sample.positions[..sample.wrong];
            if wrong.is_empty() {
                continue;
            }
            let frame = case.renderer.frame(top)?;
            let bytes = case.renderer.bytes_at(&Variant::from(top), &frame, wrong)?;
            let weight = sample.wrong_weight;
            let unexplained: Vec<usize> = (0..wrong.len())
                .filter(|&j| pixel_difference(&bytes, &sample.student, j) > 1)
                .collect();
            all += weight * wrong.len() as f64;
            let at: Vec<(u32, u32)> = unexplained.iter().map(|&j| wrong[j]).collect();
            let objects = case.renderer.objects_at(&at)?;
            for (&j, object) in unexplained.iter().zip(objects) {
                left += weight;
                let kind = kind_of(case, object);
                if let Some(slot) = on.iter_mut().find(|(k, _)| *k == kind) {
                    slot.1 += weight;
                }
                let sum = |bytes: &[u8]| bytes.iter().map(|&b| u32::from(b)).sum::<u32>();
                let (x, y) = wrong[j];
                let i = (y * case.student.width + x) as usize;
                if sum(&case.student.bytes[3 * i..3 * i + 3])
                    < sum(&case.reference.bytes[3 * i..3 * i + 3])
                {
                    darker += weight;
                }
            }
        }
        if left == 0.0 || all == 0.0 {
            return Ok(None);
        }
        on.retain(|(_, w)| *w > 0.0);
        on.iter_mut().for_each(|(_, w)| *w /= left);
        on.sort_by(|a, b| b.1.total_cmp(&a.1));
        Ok(Some(Outside {
            share: left / all,
            on,
            darker: darker / left,
        }))
    }

    /// The kind of object it lies on, where it lies on one (`located`).
    pub fn kind(&self) -> Option<Kind> {
        self.on
            .first()
            .filter(|&&(_, w)| w >= MOSTLY)
            .map(|&(k, _)| k)
    }

    /// Whether it lies on one kind of object: a story of its own, beside which the
    /// catalogued explanation of the rest can be trusted for the progress.
    pub fn located(&self) -> bool {
        self.on.first().is_some_and(|&(_, w)| w >= MOSTLY)
    }

    /// The report's line.
    pub fn sentence(&self) -> String {
        let pct = |x: f64| format!("{:.0}%", 100.0 * x);
        let on: Vec<String> = self
            .on
            .iter()
            .map(|(k, w)| format!("{} on {}", pct(*w), k.words()))
            .collect();
        let tone = match self.darker {
            d if d >= MOSTLY => ", darker than the course's",
            d if d <= 1.0 - MOSTLY => ", brighter than the course's",
            _ => "",
        };
        let story = match self.on.first() {
            Some(&(Kind::Plane, w)) if w >= MOSTLY => {
                "; what every plane shares and the catalogue does not name: their material \
                 (kD, kS, the exponent, the reflectivity) as the loader or the Plane class sets \
                 it; an edited SceneLoader or skeleton class is one of the likely stories"
            }
            Some(&(Kind::Sphere, w)) if w >= MOSTLY => {
                "; what every sphere shares and the catalogue does not name: their material as \
                 the loader or the Sphere class sets it, or Sphere.intersectionWith"
            }
            Some(&(Kind::Background, w)) if w >= MOSTLY => {
                "; the colour of a ray that hits nothing"
            }
            _ => "",
        };
        format!(
            "outside the catalogue: {} of the differing pixels no catalogued mistake reproduces \
             ({}{tone}){story}",
            pct(self.share),
            on.join(", ")
        )
    }
}

/// The entries of `top` the story outside the catalogue absorbs, where what `top` leaves lies
/// on `kind`: those whose gain, the sampled differing pixels `top` reproduces (within 1 LSB)
/// and `top` less the entry does not, lies mostly on `kind` or is nothing at all. Such an
/// entry may lower the cost on that kind's pixels by bringing them nearer, yet it reproduces
/// nothing the off-catalogue difference does not already claim: it is not needed, and naming
/// it would report a mistake the code need not have (an edited loader's planes read as
/// `no-gate`).
pub fn absorbed(cases: &[Case], top: Mistakes, kind: Kind) -> Result<Mistakes> {
    let mut found = Mistakes::NONE;
    for (bug, smaller) in top.bugs().into_iter().zip(top.one_smaller()) {
        let (mut on_kind, mut elsewhere) = (0.0, 0.0);
        for case in cases {
            let sample = &case.sample;
            let wrong = &sample.positions[..sample.wrong];
            if wrong.is_empty() {
                continue;
            }
            let bytes = |m: Mistakes| -> Result<Vec<u8>> {
                case.renderer
                    .bytes_at(&Variant::from(m), &case.renderer.frame(m)?, wrong)
            };
            let (with, without) = (bytes(top)?, bytes(smaller)?);
            let gained: Vec<usize> = (0..wrong.len())
                .filter(|&j| {
                    pixel_difference(&with, &sample.student, j) <= 1
                        && pixel_difference(&without, &sample.student, j) > 1
                })
                .collect();
            let at: Vec<(u32, u32)> = gained.iter().map(|&j| wrong[j]).collect();
            for object in case.renderer.objects_at(&at)? {
                if kind_of(case, object) == kind {
                    on_kind += sample.wrong_weight;
                } else {
                    elsewhere += sample.wrong_weight;
                }
            }
        }
        if elsewhere <= (1.0 - MOSTLY) * (on_kind + elsewhere) {
            found = found.with(bug);
        }
    }
    Ok(found)
}

/// The kind of object the reference shows at a pixel that shows `object`.
fn kind_of(case: &Case, object: Option<usize>) -> Kind {
    match object.map(|o| &case.renderer.scene.objects[o].shape) {
        Some(Shape::Sphere { .. }) => Kind::Sphere,
        Some(_) => Kind::Plane,
        None => Kind::Background,
    }
}
