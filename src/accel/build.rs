//! Building the hierarchy: binned SAH splits, large halves in parallel, the result the same
//! for any scheduling.

use glam::DVec3;
use rayon::prelude::*;

use super::aabb::Aabb;

/// Leaves hold at most this many objects unless their centres coincide.
pub(super) const MAX_LEAF: usize = 8;

/// SAH bins per split.
const BINS: usize = 16;

/// A hierarchy under construction: built in parallel as a tree, then flattened.
pub(super) struct Subtree {
    pub(super) bounds: Aabb,
    pub(super) kind: SubtreeKind,
}

pub(super) enum SubtreeKind {
    /// A range of the box array, which partitioning has left in leaf order.
    Leaf {
        first: usize,
        count: usize,
    },
    Split(Box<Subtree>, Box<Subtree>),
}

/// Nodes with more boxes than four of these chunks are binned in parallel, chunk by chunk.
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

    fn add(self, b: &Aabb) -> Extent {
        self.add_centred(b, centre(b))
    }

    /// `add` for a box whose centre `c` is already known.
    fn add_centred(self, b: &Aabb, c: DVec3) -> Extent {
        Extent {
            bounds: self.bounds.grow(*b),
            centroids: self.centroids.grow_point(c),
        }
    }

    pub(super) fn merge(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.grow(other.bounds),
            centroids: self.centroids.grow(other.centroids),
        }
    }

    pub(super) fn of(boxes: &[(u32, Aabb)]) -> Extent {
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
pub(super) fn build(boxes: &mut [(u32, Aabb)], offset: usize, extent: Extent) -> Subtree {
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

/// Moves the boxes that go left to the front (as the bins were filled), in place; returns how
/// many. Every box is swapped whichever way it goes: the side is a coin toss for the branch
/// predictor, and an unconditional swap costs less than a mispredicted branch.
fn partition(boxes: &mut [(u32, Aabb)], split: &Split) -> usize {
    let mut left = 0;
    for i in 0..boxes.len() {
        let goes_left = split.bin_of(&boxes[i].1) < split.bin;
        boxes.swap(left, i);
        left += usize::from(goes_left);
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
        self.bin_of_centre(centre(b))
    }

    fn bin_of_centre(&self, c: DVec3) -> usize {
        (((c[self.axis] - self.start) * self.scale) as usize).min(BINS - 1)
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
            let c = centre(b);
            let bin = &mut bins[split.bin_of_centre(c)];
            bin.0 = bin.0.add_centred(b, c);
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
