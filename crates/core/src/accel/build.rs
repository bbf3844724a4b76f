//! Building the hierarchy: binned SAH splits, large halves in parallel, the result the same
//! for any scheduling.

use glam::DVec3;
use rayon::prelude::*;

use super::aabb::{cube, sphere_half_side, Aabb};
use crate::geometry::Shape;

/// Leaves hold at most this many objects unless their centres coincide.
pub(super) const MAX_LEAF: usize = 8;

/// SAH bins per split.
const BINS: usize = 16;

/// A sphere as the builder moves it around: compact, and with what the leaves keep.
#[derive(Debug, Clone, Copy)]
pub(super) struct Record {
    pub(super) centre: DVec3,
    pub(super) radius: f64,
    /// Of its stored box (`aabb::sphere_half_side`).
    half_side: f64,
    /// Its index in the scene's objects.
    pub(super) object: u32,
}

impl Record {
    /// The record of object number `object`; a plane's is empty (no box), to be removed before
    /// the build.
    pub(super) fn of(object: u32, shape: &Shape) -> Record {
        match *shape {
            Shape::Sphere { centre, radius } => Record {
                centre,
                radius,
                half_side: sphere_half_side(centre, radius),
                object,
            },
            Shape::Plane { .. } => Record {
                centre: DVec3::NAN,
                radius: f64::NAN,
                half_side: f64::NAN,
                object,
            },
        }
    }

    fn bounds(&self) -> Aabb {
        cube(self.centre, self.half_side)
    }
}

/// A hierarchy under construction: built in parallel as a tree, then flattened.
pub(super) struct Subtree {
    pub(super) bounds: Aabb,
    pub(super) kind: SubtreeKind,
    /// Nodes in it, itself included: where each part goes in the flat array.
    pub(super) nodes: usize,
}

pub(super) enum SubtreeKind {
    /// A range of the record array, which partitioning has left in leaf order.
    Leaf {
        first: usize,
        count: usize,
    },
    Split(Box<Subtree>, Box<Subtree>),
}

/// Nodes with more records than four of these chunks are binned in parallel, chunk by chunk.
pub(super) const PARALLEL_BIN_CHUNK: usize = 16_384;

/// Below this many objects a subtree is built on the current thread.
const PARALLEL_BUILD: usize = 1024;

/// The bounds of a set of boxes and of their centres: what a split decision needs.
#[derive(Debug, Clone, Copy)]
pub(super) struct Extent {
    pub(super) bounds: Aabb,
    centroids: Aabb,
}

impl Extent {
    pub(super) const EMPTY: Extent = Extent {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    fn add(self, r: &Record) -> Extent {
        Extent {
            bounds: self.bounds.grow(r.bounds()),
            centroids: self.centroids.grow_point(r.centre),
        }
    }

    pub(super) fn merge(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.grow(other.bounds),
            centroids: self.centroids.grow(other.centroids),
        }
    }

    pub(super) fn of(records: &[Record]) -> Extent {
        records.iter().fold(Extent::EMPTY, Extent::add)
    }
}

/// Builds the subtree over `records` (whose extent is `extent`), splitting by the surface area
/// heuristic; large halves are built in parallel. Each level makes two passes over its records
/// (binning, partitioning): the children's extents come from the bins. The result does not
/// depend on scheduling.
pub(super) fn build(records: &mut [Record], offset: usize, extent: Extent) -> Subtree {
    let size = extent.centroids.max - extent.centroids.min;
    let axis = if size.x >= size.y && size.x >= size.z {
        0
    } else if size.y >= size.z {
        1
    } else {
        2
    };
    let split = (records.len() > MAX_LEAF && size[axis] > 0.0)
        .then(|| best_split(records, extent, axis))
        .flatten();
    let Some(split) = split else {
        return Subtree {
            bounds: extent.bounds,
            kind: SubtreeKind::Leaf {
                first: offset,
                count: records.len(),
            },
            nodes: 1,
        };
    };
    let left = partition(records, &split);
    let (l, r) = records.split_at_mut(left);
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
        nodes: 1 + l.nodes + r.nodes,
        kind: SubtreeKind::Split(Box::new(l), Box::new(r)),
    }
}

/// Moves the records that go left to the front (as the bins were filled), in place; returns
/// how many. Every record is swapped whichever way it goes: the side is a coin toss for the
/// branch predictor, and an unconditional swap costs less than a mispredicted branch.
fn partition(records: &mut [Record], split: &Split) -> usize {
    let mut left = 0;
    for i in 0..records.len() {
        let goes_left = split.bin_of(records[i].centre) < split.bin;
        records.swap(left, i);
        left += usize::from(goes_left);
    }
    left
}

/// A chosen split: records whose centre falls in a bin below `bin` go left.
struct Split {
    axis: usize,
    start: f64,
    scale: f64,
    bin: usize,
    left: Extent,
    right: Extent,
}

impl Split {
    fn bin_of(&self, centre: DVec3) -> usize {
        (((centre[self.axis] - self.start) * self.scale) as usize).min(BINS - 1)
    }
}

/// The extents and counts of the records in each bin.
type Bins = [(Extent, usize); BINS];

const EMPTY_BINS: Bins = [(Extent::EMPTY, 0); BINS];

fn merge_bins(mut a: Bins, b: &Bins) -> Bins {
    for (x, y) in a.iter_mut().zip(b) {
        *x = (x.0.merge(y.0), x.1 + y.1);
    }
    a
}

/// The bins of `records`.
fn fill(records: &[Record], split: &Split) -> Bins {
    let mut bins = EMPTY_BINS;
    for r in records {
        let bin = &mut bins[split.bin_of(r.centre)];
        *bin = (bin.0.add(r), bin.1 + 1);
    }
    bins
}

/// The SAH-best split of `records` along `axis`, if splitting beats a leaf.
fn best_split(records: &[Record], extent: Extent, axis: usize) -> Option<Split> {
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
    // The top levels hold most of the records: bin them on every core.
    let bins = if records.len() >= 4 * PARALLEL_BIN_CHUNK {
        records
            .par_chunks(PARALLEL_BIN_CHUNK)
            .map(|chunk| fill(chunk, &split))
            .reduce(|| EMPTY_BINS, |a, b| merge_bins(a, &b))
    } else {
        fill(records, &split)
    };
    // Extents and counts left of each boundary, then sweep from the right for the cost.
    let mut left = EMPTY_BINS;
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
    if cost >= extent.bounds.area() * records.len() as f64 {
        return None;
    }
    split.bin = bin;
    split.left = left[bin].0;
    split.right = right;
    Some(split)
}
