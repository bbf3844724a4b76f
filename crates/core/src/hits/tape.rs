//! A pixel's hit searches recorded as one trace asked them ([`Recording`]), answered again
//! for another trace of the same pixel ([`Replay`]).
//!
//! Exact by construction: a search is answered from the tape only when its ray (and a
//! shadow test's reach) is bit for bit one the tape holds; any other is searched. The one
//! condition the tape cannot check is the caller's: the replaying model must intersect by
//! the same rules as the recording one (the same `sphere_root` and `plane_root`), since the
//! same ray under other rules has other hits.

use std::cell::{Cell, RefCell};

use crate::accel::Accelerator;
use crate::geometry::{Hit, Ray};
use crate::hits::Hits;
use crate::model::Model;

/// A ray's bits: equal keys are the same ray (NaNs and signed zeros included).
type RayKey = [u64; 6];

#[inline(always)]
fn key(ray: &Ray) -> RayKey {
    let (o, d) = (ray.origin, ray.direction);
    [o.x, o.y, o.z, d.x, d.y, d.z].map(f64::to_bits)
}

/// Whether two keys are equal, without a call to `memcmp` (which `==` on arrays becomes, at
/// 7% of a check's time).
#[inline(always)]
fn same(a: &RayKey, b: &RayKey) -> bool {
    a.iter().zip(b).fold(0, |diff, (x, y)| diff | (x ^ y)) == 0
}

/// One search and its answer.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Answer {
    Closest(Option<Hit>),
    /// A shadow test: its reach's bits, and whether the ray was blocked.
    Occluded {
        reach: u64,
        blocked: bool,
    },
}

/// The searches of one pixel's trace, in the order it asked them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tape {
    entries: Vec<(RayKey, Answer)>,
}

impl Tape {
    /// How many searches the tape holds.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

/// The most a pixel's tape can hold, in bytes, for a scene with `lights` lights traced to
/// `bounces` reflections: a hit search and a shadow test per light at each vertex. A caller
/// bounds what it records with it (a scene may have any number of lights).
pub fn bytes_per_pixel(lights: usize, bounces: u32) -> u64 {
    let entry = std::mem::size_of::<(RayKey, Answer)>() as u64;
    let searches = (u64::from(bounces) + 1).saturating_mul(lights as u64 + 1);
    searches.saturating_mul(entry)
}

/// Searches with `accel` and records every answer.
pub struct Recording<'a> {
    accel: &'a Accelerator,
    tape: RefCell<Tape>,
}

impl<'a> Recording<'a> {
    pub fn new(accel: &'a Accelerator) -> Self {
        Recording {
            accel,
            tape: RefCell::new(Tape::default()),
        }
    }

    /// The tape so far, leaving this recording empty for the next pixel.
    pub fn take(&self) -> Tape {
        self.tape.take()
    }

    fn record(&self, ray: &Ray, answer: Answer) {
        self.tape.borrow_mut().entries.push((key(ray), answer));
    }
}

impl Hits for Recording<'_> {
    fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit> {
        let hit = self.accel.closest_hit(model, ray);
        self.record(ray, Answer::Closest(hit));
        hit
    }

    fn occluded(&self, model: &impl Model, ray: &Ray, reach: f64) -> bool {
        let blocked = self.accel.occluded(model, ray, reach);
        let reach = reach.to_bits();
        self.record(ray, Answer::Occluded { reach, blocked });
        blocked
    }
}

/// Answers from `tape` the searches it holds, and searches `accel` for any other.
pub struct Replay<'a> {
    accel: &'a Accelerator,
    tape: &'a Tape,
    /// Where the next search is looked for first: a trace that asks what the recorded one
    /// asked, in the same order, finds each at once.
    next: Cell<usize>,
    /// Searches the tape could not answer.
    searched: Cell<usize>,
}

impl<'a> Replay<'a> {
    pub fn new(accel: &'a Accelerator, tape: &'a Tape) -> Self {
        Replay {
            accel,
            tape,
            next: Cell::new(0),
            searched: Cell::new(0),
        }
    }

    /// How many searches the tape could not answer, so far.
    pub fn searched(&self) -> usize {
        self.searched.get()
    }

    /// Counts one search the tape could not answer.
    fn missed(&self) {
        self.searched.set(self.searched.get() + 1);
    }

    /// The recorded answer to the search of `ray` that `matches`, if the tape holds one.
    #[inline(always)]
    fn find(&self, ray: &Ray, matches: impl Fn(&Answer) -> bool) -> Option<Answer> {
        let entries = &self.tape.entries;
        let start = self.next.get().min(entries.len());
        let wanted = key(ray);
        let order = (start..entries.len()).chain(0..start);
        for i in order {
            let (k, answer) = &entries[i];
            if same(k, &wanted) && matches(answer) {
                self.next.set(i + 1);
                return Some(*answer);
            }
        }
        None
    }
}

impl Hits for Replay<'_> {
    #[inline(always)]
    fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit> {
        match self.find(ray, |a| matches!(a, Answer::Closest(_))) {
            Some(Answer::Closest(hit)) => hit,
            _ => {
                self.missed();
                self.accel.closest_hit(model, ray)
            }
        }
    }

    #[inline(always)]
    fn occluded(&self, model: &impl Model, ray: &Ray, reach: f64) -> bool {
        let bits = reach.to_bits();
        let asked = |a: &Answer| matches!(*a, Answer::Occluded { reach, .. } if reach == bits);
        match self.find(ray, asked) {
            Some(Answer::Occluded { blocked, .. }) => blocked,
            _ => {
                self.missed();
                self.accel.occluded(model, ray, reach)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Tick;
    use crate::scene::{parse_str, Scene};
    use crate::trace::observe::Silent;
    use crate::trace::{trace_observed, TraceOptions};

    /// The course's own tick2 scene: mirrors, several lights, a plane.
    const SCENE: &str = crate::scene::EMBEDDED_TICK2;

    /// A trace of a fan of rays with `hits` answering its searches, and its beauty.
    fn beauty(scene: &Scene, hits: &impl Hits, model: &impl Model, ray: Ray) -> glam::DVec3 {
        let options = TraceOptions {
            bounces: 3,
            shadows: true,
        };
        let mut sample = crate::sample::Sample::empty(scene.lights.len(), options.bounces);
        trace_observed::<false>(model, scene, hits, ray, options, &mut sample, &mut Silent);
        sample.beauty
    }

    fn rays() -> Vec<Ray> {
        (0..64)
            .map(|i| {
                let (x, y) = (f64::from(i % 8) / 8.0 - 0.5, f64::from(i / 8) / 8.0 - 0.5);
                Ray::new(
                    glam::DVec3::ZERO,
                    crate::geometry::normalise(glam::DVec3::new(x, y, 1.0)),
                )
            })
            .collect()
    }

    #[test]
    fn the_same_trace_again_is_answered_from_the_tape_alone() {
        let scene = parse_str("tick2.xml", SCENE).expect("scene");
        let accel = Accelerator::build(&scene.objects);
        let recording = Recording::new(&accel);
        let mut longest = 0;
        for ray in rays() {
            let searched = beauty(&scene, &accel, &Tick, ray);
            let recorded = beauty(&scene, &recording, &Tick, ray);
            let tape = recording.take();
            longest = longest.max(tape.len());
            let replay = Replay::new(&accel, &tape);
            let replayed = beauty(&scene, &replay, &Tick, ray);
            assert_eq!(replay.searched(), 0);
            for b in [recorded, replayed] {
                assert_eq!(
                    b.to_array().map(f64::to_bits),
                    searched.to_array().map(f64::to_bits)
                );
            }
        }
        // Some ray hit, was shadow-tested towards both lights and reflected.
        assert!(longest >= 5, "{longest}");
    }

    #[test]
    fn a_ray_the_tape_does_not_hold_is_searched() {
        // Another camera ray's tape answers nothing of this one: every search falls through
        // to the hierarchy, and the beauty is what searching gives.
        let scene = parse_str("tick2.xml", SCENE).expect("scene");
        let accel = Accelerator::build(&scene.objects);
        let recording = Recording::new(&accel);
        let rays = rays();
        beauty(&scene, &recording, &Tick, rays[0]);
        let other = recording.take();
        for &ray in &rays[1..] {
            let replay = Replay::new(&accel, &other);
            let replayed = beauty(&scene, &replay, &Tick, ray);
            assert!(replay.searched() > 0);
            let searched = beauty(&scene, &accel, &Tick, ray);
            assert_eq!(
                replayed.to_array().map(f64::to_bits),
                searched.to_array().map(f64::to_bits)
            );
        }
    }
}
