//! Finding the nearest object without testing every object: a bounding volume hierarchy
//! (binned SAH) over the bounded shapes, with unbounded planes tested one by one.
//!
//! It must give exactly the brute-force answer of `geometry::closest_hit`, including ties:
//! the same intersection code runs on every candidate, and candidates are ranked by
//! (distance, file index), which is what "earlier object wins ties" means. A box is only ever
//! skipped when no sphere in it can be *reported* hit by the brute-force formula, including the
//! hits that formula reports outside the sphere on badly conditioned rays: see [`RayMargin`].

use glam::DVec3;
use rayon::iter::Either;
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::geometry::{Hit, Ray, Shape};
use crate::scene::Object;

/// Leaves hold at most this many objects unless their centres coincide.
const MAX_LEAF: usize = 8;

/// SAH bins per split.
const BINS: usize = 16;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    fn grow(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    fn grow_point(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    fn contains(self, p: DVec3) -> bool {
        (self.min.x <= p.x && p.x <= self.max.x)
            && (self.min.y <= p.y && p.y <= self.max.y)
            && (self.min.z <= p.z && p.z <= self.max.z)
    }

    fn area(self) -> f64 {
        let d = (self.max - self.min).max(DVec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Parameter where the ray enters the box grown by the ray's margin on every side, or
    /// `None` if it misses it or the box lies wholly behind the origin. Growing the box by m is
    /// moving the origin by -m towards `min` and +m towards `max`: the same three subtractions
    /// per slab as an ungrown test.
    fn entry(self, ray: &RayMargin) -> Option<f64> {
        let t1 = (self.min - ray.origin_plus_margin) * ray.inverse;
        let t2 = (self.max - ray.origin_minus_margin) * ray.inverse;
        // f64::min/max ignore a NaN operand (0 * inf on a slab plane), keeping the test
        // conservative.
        let near = t1.x.min(t2.x).max(t1.y.min(t2.y)).max(t1.z.min(t2.z));
        let far = t1.x.max(t2.x).min(t1.y.max(t2.y)).min(t1.z.max(t2.z));
        (near <= far && far >= 0.0).then_some(near)
    }
}

/// The box around a bounded shape; `None` for unbounded shapes. The half-side exceeds the
/// radius by 2^-40 of the coordinates' size, far more than the rounding of `centre +- pad`
/// (2^-53 of it), so the stored box contains the exact sphere. Hits the formula reports
/// *outside* the sphere are the per-ray margin's job ([`RayMargin`]), not the box's.
fn bounds(shape: &Shape) -> Option<Aabb> {
    match *shape {
        Shape::Sphere { centre, radius } => {
            let pad = radius + (centre.abs().max_element() + radius) * REPRESENTATION_SLACK;
            Some(Aabb {
                min: centre - DVec3::splat(pad),
                max: centre + DVec3::splat(pad),
            })
        }
        Shape::Plane { .. } => None,
    }
}

/// 2^-40: relative slack for storing a box's corners in f64 (whose rounding is 2^-53).
const REPRESENTATION_SLACK: f64 = 1.0 / (1u64 << 40) as f64;

/// 2^-23 (1.2e-7): how far outside a sphere, relative to `wmax` below, the brute-force formula
/// can report a hit. See [`RayMargin`].
const CONDITIONING_BOUND: f64 = 1.0 / (1u64 << 23) as f64;

/// A ray prepared for box tests: `1 / direction`, and the margin every box is grown by for it.
///
/// Why a margin. For a sphere (C, r) and a ray (O, D), write w = O - C and u = 1 + 2^-53 (unit
/// roundoff e = 2^-53). The formula of rendering.md computes `disc = b^2 - 4ac` with
/// `b = 2 D.w`, `c = w.w - r^2`. Each of those dot products and products carries a rounding
/// error of at most a few e times the size of its terms (`|D.w| <= |D||w|`), so the computed
/// disc differs from the exact one by |err| <= 4 |D|^2 (|w|^2 + r^2) * k e with k < 16 (three
/// terms per dot product, the squares, the products and the final subtraction; the
/// subtraction `O - C` itself is exact to e of |w|). The exact disc is `4 a (r^2 - h^2)`, h the
/// distance from C to the ray's line, so a reported hit (disc >= 0) needs
/// `h^2 <= r^2 + E`, E = |err| / (4a) <= 16 e (|w|^2 + r^2) (the renderer's rays are unit,
/// a = 1 to within 3e). The reported root then lies sqrt(disc)/(2a) before the closest
/// approach, so the reported point Q = O + sD is at distance <= sqrt(r^2 + E) + (rounding of
/// s, a few e |w|) from C, and sqrt(r^2 + E) <= r + sqrt(E) <= r + 4 sqrt(e) (|w| + r). With
/// sqrt(e) = 1.05e-8, every reported point is within
/// r + 4.3e-8 (|w| + r) + (a few e |w|) < r + 2^-23 wmax
/// of C, where wmax is the distance from O to the farthest corner of the root box, which
/// contains every sphere, so wmax >= |w| + r for each of them. Growing every box by
/// `2^-23 wmax` therefore keeps every reported hit point inside the boxes that hold its
/// sphere (with room to spare for the slab test's own rounding, a few e of `wmax`), so:
/// - a box the ray misses holds no sphere the formula reports hit: skipping it is exact;
/// - a reported hit at s lies in the grown box, so the box's entry parameter is <= s: the
///   `entry > best` cut in `closest_hit` and the `entry < max_distance` test in `occluded`
///   never drop a hit brute force would keep.
///
/// The margin also carries 2^-40 of the origin's largest coordinate, so that storing
/// `origin +- margin` (rounded to 2^-53 of the origin) cannot eat into it.
///
/// For camera rays in a scene of size ~10 the margin is ~1e-6 and costs nothing; for a shadow
/// ray starting 1e7 away it is ~1.2, which is what exactness costs there. A ray with a NaN or
/// infinite origin or direction gets a non-finite margin, but the formula reports no hit at
/// all for such a ray (its disc or root is NaN), so whatever the box test does is exact; an
/// infinite margin from a finite ray (coordinates near f64::MAX) makes every box pass.
struct RayMargin {
    origin_plus_margin: DVec3,
    origin_minus_margin: DVec3,
    inverse: DVec3,
}

impl RayMargin {
    /// The ray with its own margin, or none when it starts in the near zone, whose margin the
    /// stored boxes already have.
    fn new(ray: &Ray, root: Aabb, near_zone: Aabb) -> Self {
        let inverse = DVec3::ONE / ray.direction;
        if near_zone.contains(ray.origin) {
            return RayMargin {
                origin_plus_margin: ray.origin,
                origin_minus_margin: ray.origin,
                inverse,
            };
        }
        let far_corner = (ray.origin - root.min)
            .abs()
            .max((ray.origin - root.max).abs());
        // The L1 length bounds the Euclidean one from above and needs no square root.
        let margin = far_corner.element_sum() * CONDITIONING_BOUND
            + ray.origin.abs().max_element() * REPRESENTATION_SLACK;
        RayMargin {
            origin_plus_margin: ray.origin + DVec3::splat(margin),
            origin_minus_margin: ray.origin - DVec3::splat(margin),
            inverse,
        }
    }
}

/// The near zone of a root box and the margin that covers every ray starting in it. The zone
/// is the root box stretched to take in the camera at the origin, then grown by its longest
/// side S on every side: camera rays and rays from the scene's surfaces start in it. From
/// such an origin the far corner of the root is at most 2S away per axis, 6S in the L1
/// length, so the margin is 2^-23 * 6S, plus the representation slack of the zone's
/// coordinates (for storing the grown boxes and the origins). Rays from elsewhere add their
/// own margin on top, which only grows the boxes more.
fn near_zone(root: Aabb) -> (Aabb, f64) {
    let root = root.grow_point(DVec3::ZERO);
    let side = (root.max - root.min).max_element();
    let zone = Aabb {
        min: root.min - DVec3::splat(side),
        max: root.max + DVec3::splat(side),
    };
    let size = zone.min.abs().max(zone.max.abs()).max_element();
    let margin = 6.0 * side * CONDITIONING_BOUND + size * REPRESENTATION_SLACK;
    (zone, margin)
}

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
    /// The shapes of `items`, in the same order: a leaf's shapes sit side by side in memory
    /// instead of scattered through the scene's objects.
    shapes: Vec<Shape>,
    /// Objects without bounds (planes), in file order: tested for every ray.
    unbounded: Vec<u32>,
    /// Rays starting in here need no margin of their own: every stored box is already grown
    /// by one that covers them ([`RayMargin`]).
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
    /// Builds the hierarchy over `objects`' bounded shapes.
    pub fn build(objects: &[Object]) -> Self {
        // Whole-scene passes run on every core (rayon keeps the order).
        let (mut boxes, unbounded): (Vec<(u32, Aabb)>, Vec<u32>) = objects
            .par_iter()
            .enumerate()
            .partition_map(|(i, o)| match bounds(&o.shape) {
                Some(b) => Either::Left((i as u32, b)),
                None => Either::Right(i as u32),
            });
        let mut accel = Accelerator {
            nodes: Vec::with_capacity(2 * boxes.len() / MAX_LEAF + 1),
            items: Vec::with_capacity(boxes.len()),
            shapes: Vec::new(),
            unbounded,
            near_zone: Aabb::EMPTY,
        };
        if !boxes.is_empty() {
            let extent = boxes
                .par_chunks(PARALLEL_BIN_CHUNK)
                .map(Extent::of)
                .reduce(|| Extent::EMPTY, Extent::merge);
            let tree = build(&mut boxes, 0, extent);
            let (near_zone, margin) = near_zone(extent.bounds);
            accel.near_zone = near_zone;
            accel.items = boxes.par_iter().map(|(i, _)| *i).collect();
            accel.nodes.push(Node {
                bounds: Aabb::EMPTY,
                first: 0,
                count: 0,
            });
            accel.fill(0, tree, margin);
        }
        accel.shapes = accel
            .items
            .iter()
            .map(|&i| objects[i as usize].shape)
            .collect();
        accel
    }

    /// Writes `tree` into the already reserved node `index`, its nodes depth first; the two
    /// children of a node sit next to each other, so a node needs only the first's index.
    /// Every box is stored grown by `margin`, the near zone's share of [`RayMargin`].
    fn fill(&mut self, index: usize, tree: Subtree, margin: f64) {
        self.nodes[index].bounds = Aabb {
            min: tree.bounds.min - DVec3::splat(margin),
            max: tree.bounds.max + DVec3::splat(margin),
        };
        match tree.kind {
            SubtreeKind::Leaf { first, count } => {
                self.nodes[index].first = first as u32;
                self.nodes[index].count = count as u32;
            }
            SubtreeKind::Split(left, right) => {
                let children = self.nodes.len();
                for _ in 0..2 {
                    self.nodes.push(Node {
                        bounds: Aabb::EMPTY,
                        first: 0,
                        count: 0,
                    });
                }
                self.nodes[index].first = children as u32;
                self.fill(children, *left, margin);
                self.fill(children + 1, *right, margin);
            }
        }
    }

    /// Tests every object in order: the reference the hierarchy must agree with.
    pub fn brute_force(objects: &[Object]) -> Self {
        Accelerator {
            nodes: Vec::new(),
            items: Vec::new(),
            shapes: Vec::new(),
            unbounded: (0..objects.len() as u32).collect(),
            near_zone: Aabb::EMPTY,
        }
    }

    /// The nearest hit along `ray`, exactly as `geometry::closest_hit` finds it.
    pub fn closest_hit(&self, objects: &[Object], ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let test = |best: Option<Hit>, i: u32| match objects[i as usize].shape.intersect(ray) {
            Some(distance) => nearer(
                best,
                Hit {
                    object: i as usize,
                    distance,
                },
            ),
            None => best,
        };
        for &i in &self.unbounded {
            best = test(best, i);
        }
        if self.nodes.is_empty() {
            return best;
        }
        let prepared = RayMargin::new(ray, self.nodes[0].bounds, self.near_zone);
        let mut stack: SmallVec<[(u32, f64); 64]> = SmallVec::new();
        if let Some(t) = self.nodes[0].bounds.entry(&prepared) {
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
                for (shape, &i) in self.shapes[range.clone()].iter().zip(&self.items[range]) {
                    if let Some(distance) = shape.intersect(ray) {
                        best = nearer(
                            best,
                            Hit {
                                object: i as usize,
                                distance,
                            },
                        );
                    }
                }
                continue;
            }
            let children = [node.first, node.first + 1]
                .map(|c| (c, self.nodes[c as usize].bounds.entry(&prepared)));
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

    /// Whether anything lies along `ray` strictly nearer than `max_distance`.
    pub fn occluded(&self, objects: &[Object], ray: &Ray, max_distance: f64) -> bool {
        let blocks = |i: u32| {
            objects[i as usize]
                .shape
                .intersect(ray)
                .is_some_and(|s| s < max_distance)
        };
        if self.unbounded.iter().any(|&i| blocks(i)) {
            return true;
        }
        if self.nodes.is_empty() {
            return false;
        }
        let prepared = RayMargin::new(ray, self.nodes[0].bounds, self.near_zone);
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = self.nodes[index as usize];
            match node.bounds.entry(&prepared) {
                Some(t) if t < max_distance => {}
                _ => continue,
            }
            if node.count > 0 {
                let range = node.first as usize..(node.first + node.count) as usize;
                let hit = |shape: &Shape| shape.intersect(ray).is_some_and(|s| s < max_distance);
                if self.shapes[range].iter().any(hit) {
                    return true;
                }
            } else {
                stack.extend([node.first, node.first + 1]);
            }
        }
        false
    }
}

/// A hierarchy under construction: built in parallel as a tree, then flattened.
struct Subtree {
    bounds: Aabb,
    kind: SubtreeKind,
}

enum SubtreeKind {
    /// A range of the box array, which partitioning has left in leaf order.
    Leaf {
        first: usize,
        count: usize,
    },
    Split(Box<Subtree>, Box<Subtree>),
}

/// Nodes with more boxes than four of these chunks are binned in parallel, chunk by chunk.
const PARALLEL_BIN_CHUNK: usize = 16_384;

/// Below this many objects a subtree is built on the current thread.
const PARALLEL_BUILD: usize = 1024;

/// The bounds of a set of boxes and of their centres: what a split decision needs.
#[derive(Debug, Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centroids: Aabb,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    fn add(self, b: &Aabb) -> Extent {
        Extent {
            bounds: self.bounds.grow(*b),
            centroids: self.centroids.grow_point(centre(b)),
        }
    }

    fn merge(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.grow(other.bounds),
            centroids: self.centroids.grow(other.centroids),
        }
    }

    fn of(boxes: &[(u32, Aabb)]) -> Extent {
        boxes.iter().fold(Extent::EMPTY, |e, (_, b)| e.add(b))
    }
}

fn centre(b: &Aabb) -> DVec3 {
    (b.min + b.max) / 2.0
}

/// Builds the subtree over `boxes` (whose extent is `extent`), splitting by the surface area
/// heuristic; large halves are built in parallel. Each level makes two passes over its boxes
/// (binning, partitioning): the children's extents come from the bins. The result does not
/// depend on scheduling.
fn build(boxes: &mut [(u32, Aabb)], offset: usize, extent: Extent) -> Subtree {
    let size = extent.centroids.max - extent.centroids.min;
    let axis = if size.x >= size.y && size.x >= size.z {
        0
    } else if size.y >= size.z {
        1
    } else {
        2
    };
    let split = (boxes.len() > MAX_LEAF && size[axis] > 0.0)
        .then(|| best_split(boxes, extent, axis))
        .flatten();
    let Some(split) = split else {
        return Subtree {
            bounds: extent.bounds,
            kind: SubtreeKind::Leaf {
                first: offset,
                count: boxes.len(),
            },
        };
    };
    let left = partition(boxes, &split);
    let (l, r) = boxes.split_at_mut(left);
    let right_offset = offset + l.len();
    let (l, r) = if l.len().min(r.len()) >= PARALLEL_BUILD {
        rayon::join(
            || build(l, offset, split.left),
            || build(r, right_offset, split.right),
        )
    } else {
        (
            build(l, offset, split.left),
            build(r, right_offset, split.right),
        )
    };
    Subtree {
        bounds: extent.bounds,
        kind: SubtreeKind::Split(Box::new(l), Box::new(r)),
    }
}

/// Moves the boxes that go left to the front (as the bins were filled), in place like
/// quicksort's partition; returns how many.
fn partition(boxes: &mut [(u32, Aabb)], split: &Split) -> usize {
    let goes_left = |b: &(u32, Aabb)| split.bin_of(&b.1) < split.bin;
    let (mut left, mut right) = (0, boxes.len());
    while left < right {
        if goes_left(&boxes[left]) {
            left += 1;
        } else {
            right -= 1;
            boxes.swap(left, right);
        }
    }
    left
}

/// A chosen split: boxes whose centre falls in a bin below `bin` go left.
struct Split {
    axis: usize,
    start: f64,
    scale: f64,
    bin: usize,
    left: Extent,
    right: Extent,
}

impl Split {
    fn bin_of(&self, b: &Aabb) -> usize {
        (((centre(b)[self.axis] - self.start) * self.scale) as usize).min(BINS - 1)
    }
}

/// The SAH-best split of `boxes` along `axis`, if splitting beats a leaf.
fn best_split(boxes: &[(u32, Aabb)], extent: Extent, axis: usize) -> Option<Split> {
    let start = extent.centroids.min[axis];
    let scale = BINS as f64 / (extent.centroids.max[axis] - start);
    let mut split = Split {
        axis,
        start,
        scale,
        bin: 0,
        left: Extent::EMPTY,
        right: Extent::EMPTY,
    };
    let fill = |chunk: &[(u32, Aabb)]| {
        let mut bins = [(Extent::EMPTY, 0usize); BINS];
        for (_, b) in chunk {
            let bin = &mut bins[split.bin_of(b)];
            bin.0 = bin.0.add(b);
            bin.1 += 1;
        }
        bins
    };
    // The top levels hold most of the boxes: bin them on every core.
    let bins = if boxes.len() >= 4 * PARALLEL_BIN_CHUNK {
        boxes.par_chunks(PARALLEL_BIN_CHUNK).map(fill).reduce(
            || [(Extent::EMPTY, 0usize); BINS],
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(b) {
                    *x = (x.0.merge(y.0), x.1 + y.1);
                }
                a
            },
        )
    } else {
        fill(boxes)
    };
    // Extents and counts left of each boundary, then sweep from the right for the cost.
    let mut left = [(Extent::EMPTY, 0usize); BINS];
    for i in 1..BINS {
        left[i] = (
            left[i - 1].0.merge(bins[i - 1].0),
            left[i - 1].1 + bins[i - 1].1,
        );
    }
    let (mut right, mut right_count) = (Extent::EMPTY, 0);
    let mut best: Option<(f64, usize, Extent)> = None;
    for i in (1..BINS).rev() {
        right = right.merge(bins[i].0);
        right_count += bins[i].1;
        let (left_extent, left_count) = left[i];
        if left_count == 0 || right_count == 0 {
            continue;
        }
        let cost = left_extent.bounds.area() * left_count as f64
            + right.bounds.area() * right_count as f64;
        if best.is_none_or(|(c, _, _)| cost < c) {
            best = Some((cost, i, right));
        }
    }
    let (cost, bin, right) = best?;
    // Splitting pays if its expected work is below testing every object here.
    if cost >= extent.bounds.area() * boxes.len() as f64 {
        return None;
    }
    split.bin = bin;
    split.left = left[bin].0;
    split.right = right;
    Some(split)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{closest_hit, normalise, occluded};
    use crate::scene::Material;

    /// A small deterministic generator, so the test needs no randomness crate.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    fn scene(n: usize, seed: u64) -> Vec<Object> {
        let mut rng = Lcg(seed);
        let mut objects: Vec<Object> = (0..n)
            .map(|_| Object {
                shape: Shape::Sphere {
                    centre: DVec3::new(
                        rng.range(-5.0, 5.0),
                        rng.range(-5.0, 5.0),
                        rng.range(2.0, 12.0),
                    ),
                    radius: rng.range(0.05, 0.8),
                },
                material: Material::sphere(DVec3::ONE),
            })
            .collect();
        // Duplicates make exact ties; a plane makes the unbounded list non-empty.
        objects.push(objects[3].clone());
        objects.push(objects[0].clone());
        objects.insert(
            5,
            Object {
                shape: Shape::Plane {
                    point: DVec3::new(0.0, -3.0, 0.0),
                    normal: DVec3::Y,
                },
                material: Material::plane(DVec3::ONE),
            },
        );
        objects
    }

    #[test]
    fn agrees_with_brute_force_on_random_rays_including_ties() {
        for (n, seed) in [(10, 1), (200, 2), (2000, 3)] {
            let objects = scene(n, seed);
            let accel = Accelerator::build(&objects);
            let brute = Accelerator::brute_force(&objects);
            let mut rng = Lcg(seed + 100);
            for _ in 0..3000 {
                let origin = DVec3::new(
                    rng.range(-6.0, 6.0),
                    rng.range(-6.0, 6.0),
                    rng.range(-2.0, 14.0),
                );
                let direction = normalise(DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                ));
                let ray = Ray::new(origin, direction);
                let expected = closest_hit(&objects, &ray);
                assert_eq!(accel.closest_hit(&objects, &ray), expected);
                assert_eq!(brute.closest_hit(&objects, &ray), expected);
                let d = rng.range(0.1, 20.0);
                assert_eq!(
                    accel.occluded(&objects, &ray, d),
                    occluded(&objects, &ray, d)
                );
            }
        }
    }

    /// Spheres with radii down to 1e-4 in a cluster, and rays from up to 1e7 away aimed at
    /// points near them: the badly conditioned case where the formula reports hits outside the
    /// sphere. The hierarchy must report exactly those hits too.
    fn long_rays(seed: u64, rays: usize) -> (Vec<Object>, Vec<(Ray, f64)>) {
        let mut rng = Lcg(seed);
        let objects: Vec<Object> = (0..300)
            .map(|_| Object {
                shape: Shape::Sphere {
                    centre: DVec3::new(
                        rng.range(-3.0, 3.0),
                        rng.range(-3.0, 3.0),
                        rng.range(2.0, 8.0),
                    ),
                    radius: 10f64.powf(rng.range(-4.0, -1.0)),
                },
                material: Material::sphere(DVec3::ONE),
            })
            .collect();
        let cases = (0..rays)
            .map(|_| {
                let Shape::Sphere { centre, radius } =
                    objects[(rng.next() * objects.len() as f64) as usize].shape
                else {
                    unreachable!("only spheres")
                };
                let far = 10f64.powf(rng.range(0.0, 7.0));
                let origin = centre
                    + far
                        * normalise(DVec3::new(
                            rng.range(-1.0, 1.0),
                            rng.range(-1.0, 1.0),
                            rng.range(-1.0, 1.0),
                        ));
                // Aim within a few radii of the centre, and up to 0.3 away at long range.
                let spread = radius * 3.0 + far * 3e-8;
                let target = centre
                    + DVec3::new(
                        rng.range(-spread, spread),
                        rng.range(-spread, spread),
                        rng.range(-spread, spread),
                    );
                let ray = Ray::new(origin, normalise(target - origin));
                (ray, far * rng.range(0.5, 1.5))
            })
            .collect();
        (objects, cases)
    }

    #[test]
    fn agrees_with_brute_force_on_long_badly_conditioned_rays() {
        let (objects, cases) = long_rays(11, 20_000);
        let accel = Accelerator::build(&objects);
        let mut outside = 0;
        for (ray, max_distance) in &cases {
            let expected = closest_hit(&objects, ray);
            assert_eq!(accel.closest_hit(&objects, ray), expected, "{ray:?}");
            assert_eq!(
                accel.occluded(&objects, ray, *max_distance),
                occluded(&objects, ray, *max_distance),
                "{ray:?}"
            );
            if let Some(hit) = expected {
                let Shape::Sphere { centre, radius } = objects[hit.object].shape else {
                    unreachable!("only spheres")
                };
                let miss_by = (ray.at(hit.distance) - centre).length() - radius;
                outside += usize::from(miss_by > radius * 1e-4 + 1e-9);
            }
        }
        // The case this guards: hits reported well outside their sphere, which a box padded
        // by a fixed fraction of the radius would cull.
        assert!(outside > 100, "only {outside} hits outside their sphere");
    }

    #[test]
    fn reported_hits_stay_within_the_conditioning_bound() {
        // The margin's argument, checked: how far outside its sphere a reported hit lies,
        // relative to |O - C| + r, stays below CONDITIONING_BOUND with room to spare.
        let (objects, cases) = long_rays(12, 20_000);
        let mut worst: f64 = 0.0;
        for (ray, _) in &cases {
            for object in &objects {
                let Shape::Sphere { centre, radius } = object.shape else {
                    unreachable!("only spheres")
                };
                if let Some(s) = object.shape.intersect(ray) {
                    let outside = (ray.at(s) - centre).length() - radius;
                    let scale = (ray.origin - centre).length() + radius;
                    worst = worst.max(outside / scale);
                }
            }
        }
        assert!(worst > 1e-9, "no badly conditioned hit was generated");
        assert!(worst < CONDITIONING_BOUND / 2.0, "worst ratio {worst:e}");
    }

    #[test]
    fn duplicate_spheres_tie_to_the_first_in_file_order() {
        let objects = scene(50, 7);
        let accel = Accelerator::build(&objects);
        let Shape::Sphere { centre, .. } = objects[0].shape else {
            panic!("sphere")
        };
        let ray = Ray::new(DVec3::new(centre.x, centre.y, -20.0), DVec3::Z);
        let hit = accel.closest_hit(&objects, &ray).expect("hits");
        assert_eq!(hit, closest_hit(&objects, &ray).expect("hits"));
        assert!(
            hit.object < objects.len() - 1,
            "the later duplicate must not win"
        );
    }

    #[test]
    fn builds_a_real_hierarchy() {
        let objects = scene(5000, 9);
        let accel = Accelerator::build(&objects);
        assert_eq!(accel.items.len(), objects.len() - 1);
        assert_eq!(accel.unbounded, [5]);
        let leaves: Vec<&Node> = accel.nodes.iter().filter(|n| n.count > 0).collect();
        assert!(leaves.len() > 5000 / 8, "{} leaves", leaves.len());
        assert!(leaves.iter().all(|n| n.count <= 16));
    }
}
