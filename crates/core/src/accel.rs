//! Finding the nearest object without testing every object: a bounding volume hierarchy
//! (binned SAH) over the bounded shapes, with unbounded planes tested one by one.
//!
//! It must give exactly the brute-force answer of `model::search::closest_hit`, including ties:
//! the same intersection code runs on every candidate, and candidates are ranked by
//! (distance, file index), which is what "earlier object wins ties" means. A box is only ever
//! skipped when no sphere in it can be *reported* hit by the brute-force formula, including the
//! hits that formula reports outside the sphere on badly conditioned rays: see `accel/margin.rs`.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

mod aabb;
mod build;
mod flatten;
mod margin;
#[cfg(test)]
mod tests;

use aabb::Aabb;
use build::{build, Extent, Record, PARALLEL_BIN_CHUNK};
use flatten::flatten;
use margin::{near_zone, RayMargin};

use crate::geometry::{Hit, Ray, Shape, SphereTerms};
use crate::model::{search, Model};
use crate::scene::Object;

/// A shape without bounds (a plane) and its file index.
type Unbounded = (usize, Shape);

#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    bounds: Aabb,
    /// Leaf: first index into `items`; interior: index of the left child (right is +1).
    first: u32,
    /// Leaf: number of items (> 0); interior: 0.
    count: u32,
}

/// The acceleration structure for one scene's objects.
#[derive(Debug, Clone, PartialEq)]
pub struct Accelerator {
    nodes: Vec<Node>,
    /// Object indices, grouped by leaf.
    items: Vec<u32>,
    /// The spheres of `items` as (centre, radius squared), in the same order: a leaf's
    /// spheres sit side by side in memory instead of scattered through the scene's objects.
    spheres: Vec<(DVec3, f64)>,
    /// Objects without bounds (planes) with their file index, in file order: tested for
    /// every ray by the brute-force search itself.
    unbounded: Vec<Unbounded>,
    /// Rays starting in here need no margin of their own: every stored box is already grown
    /// by one that covers them (`accel/margin.rs`).
    near_zone: Aabb,
}

/// The nearest of two candidate hits by (distance, object index): the brute-force order.
fn nearer(best: Option<Hit>, candidate: Hit) -> Option<Hit> {
    match best {
        Some(b) if (b.distance, b.object) <= (candidate.distance, candidate.object) => Some(b),
        _ => Some(candidate),
    }
}

impl Accelerator {
    /// Builds the hierarchy over `objects`' bounded shapes (the spheres).
    pub fn build(objects: &[Object]) -> Self {
        // Whole-scene passes run on every core (rayon keeps the order).
        let unbounded: Vec<Unbounded> = objects
            .par_iter()
            .enumerate()
            .filter_map(|(i, o)| match o.shape {
                Shape::Plane { .. } => Some((i, o.shape)),
                Shape::Sphere { .. } => None,
            })
            .collect();
        // A record per object, written straight into place; then each plane's slot is given
        // to the last record (planes from the last down, so the record moved is a sphere's).
        // The records' order changes no answer, only the order within leaves.
        let mut records: Vec<Record> = objects
            .par_iter()
            .enumerate()
            .map(|(i, o)| Record::of(i as u32, &o.shape))
            .collect();
        for &(i, _) in unbounded.iter().rev() {
            records.swap_remove(i);
        }
        if records.is_empty() {
            return Accelerator {
                nodes: Vec::new(),
                items: Vec::new(),
                spheres: Vec::new(),
                unbounded,
                near_zone: Aabb::EMPTY,
            };
        }
        let extent = records
            .par_chunks(PARALLEL_BIN_CHUNK)
            .map(Extent::of)
            .reduce(|| Extent::EMPTY, Extent::merge);
        let tree = build(&mut records, 0, extent);
        let (near_zone, margin) = near_zone(extent.bounds);
        let (items, spheres) = records
            .par_iter()
            .map(|r| (r.object, (r.centre, r.radius * r.radius)))
            .unzip();
        Accelerator {
            nodes: flatten(tree, margin),
            items,
            spheres,
            unbounded,
            near_zone,
        }
    }

    /// Tests every object in order: the reference the hierarchy must agree with.
    pub fn brute_force(objects: &[Object]) -> Self {
        Accelerator {
            nodes: Vec::new(),
            items: Vec::new(),
            spheres: Vec::new(),
            unbounded: objects.iter().map(|o| o.shape).enumerate().collect(),
            near_zone: Aabb::EMPTY,
        }
    }

    /// Whether every object is tested in order on every ray (no sphere is in the hierarchy):
    /// exact for any model's rules.
    pub fn is_exhaustive(&self) -> bool {
        self.spheres.is_empty()
    }

    /// The nearest hit along `ray` under `model`'s rules, exactly as
    /// `model::search::closest_hit` finds it over every object. The hierarchy is only correct
    /// for models it is exact for (`Model::hierarchy_exact`); others use `brute_force`.
    pub fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit> {
        let unbounded = self.unbounded.iter().map(|(i, s)| (*i, s));
        let mut best = search::closest_hit(model, unbounded, ray);
        if self.nodes.is_empty() {
            return best;
        }
        let terms = SphereTerms::of(ray);
        // A root that is a leaf (a handful of spheres) needs no box test at all.
        if self.nodes[0].count > 0 {
            return self.nearest_in_leaf(model, 0..self.items.len(), ray, &terms, best);
        }
        let prepared = RayMargin::new(ray, self.nodes[0].bounds, self.near_zone);
        let mut stack: SmallVec<[(u32, f64); 64]> = SmallVec::new();
        if let Some(t) = prepared.entry(self.nodes[0].bounds) {
            stack.push((0, t));
        }
        while let Some((index, entry)) = stack.pop() {
            // Equal distances must still be visited: a tie may go to a lower index.
            if best.is_some_and(|b| entry > b.distance) {
                continue;
            }
            let node = self.nodes[index as usize];
            if node.count > 0 {
                let range = node.first as usize..(node.first + node.count) as usize;
                best = self.nearest_in_leaf(model, range, ray, &terms, best);
                continue;
            }
            let children = [node.first, node.first + 1]
                .map(|c| (c, prepared.entry(self.nodes[c as usize].bounds)));
            // Push the farther child first so the nearer one is searched first.
            let (near, far) = match (children[0].1, children[1].1) {
                (Some(a), Some(b)) if b < a => (children[1], children[0]),
                _ => (children[0], children[1]),
            };
            for (c, t) in [far, near] {
                if let Some(t) = t {
                    stack.push((c, t));
                }
            }
        }
        best
    }

    /// `best` or a nearer hit among the spheres of `range` (leaf order is not file order:
    /// ties are settled by `nearer`).
    fn nearest_in_leaf(
        &self,
        model: &impl Model,
        range: std::ops::Range<usize>,
        ray: &Ray,
        terms: &SphereTerms,
        mut best: Option<Hit>,
    ) -> Option<Hit> {
        for (&(centre, radius_squared), &i) in
            self.spheres[range.clone()].iter().zip(&self.items[range])
        {
            if let Some(distance) = model.sphere_root(ray, terms, centre, radius_squared) {
                let hit = Hit {
                    object: i as usize,
                    distance,
                };
                best = nearer(best, hit);
            }
        }
        best
    }

    /// Whether anything lies along `ray` strictly nearer than `max_distance`.
    pub fn occluded(&self, model: &impl Model, ray: &Ray, max_distance: f64) -> bool {
        let unbounded = self.unbounded.iter().map(|(i, s)| (*i, s));
        if search::occluded(model, unbounded, ray, max_distance) {
            return true;
        }
        if self.nodes.is_empty() {
            return false;
        }
        let terms = SphereTerms::of(ray);
        let blocks = |&(centre, radius_squared): &(DVec3, f64)| {
            model
                .sphere_root(ray, &terms, centre, radius_squared)
                .is_some_and(|s| s < max_distance)
        };
        if self.nodes[0].count > 0 {
            return self.spheres.iter().any(blocks);
        }
        let prepared = RayMargin::new(ray, self.nodes[0].bounds, self.near_zone);
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = self.nodes[index as usize];
            match prepared.entry(node.bounds) {
                Some(t) if t < max_distance => {}
                _ => continue,
            }
            if node.count > 0 {
                let range = node.first as usize..(node.first + node.count) as usize;
                if self.spheres[range].iter().any(blocks) {
                    return true;
                }
            } else {
                stack.extend([node.first, node.first + 1]);
            }
        }
        false
    }
}
