//! The built tree -> the node array the searches walk: depth first, the two children of a node
//! side by side (so a node needs only the first's index), written on every core.

use super::aabb::Aabb;
use super::build::{Subtree, SubtreeKind};
use super::Node;

/// Subtrees with fewer nodes than this are written on the current thread.
const PARALLEL_NODES: usize = 4096;

/// The nodes of `tree`, root first. Every box is stored grown by `margin`, the near zone's
/// share of the per-ray margin (`accel/margin.rs`).
pub(super) fn flatten(tree: Subtree, margin: f64) -> Vec<Node> {
    let mut nodes = vec![node(&Aabb::EMPTY, 0.0); tree.nodes];
    let (root, below) = nodes.split_at_mut(1);
    write(&mut root[0], tree, below, 1, margin);
    nodes
}

/// Writes `tree`'s node into `slot` and the nodes below it into `below`, which starts at
/// index `at` of the whole array.
fn write(slot: &mut Node, tree: Subtree, below: &mut [Node], at: usize, margin: f64) {
    match tree.kind {
        SubtreeKind::Leaf { first, count } => *slot = leaf(&tree.bounds, first, count, margin),
        SubtreeKind::Split(left, right) => {
            *slot = node(&tree.bounds, margin);
            slot.first = at as u32;
            write_pair(below, at, *left, *right, margin);
        }
    }
}

/// Writes two children into `slots` (index `at` of the whole array): the pair first, then
/// every node below the left child, then every node below the right one.
fn write_pair(slots: &mut [Node], at: usize, left: Subtree, right: Subtree, margin: f64) {
    let (pair, below) = slots.split_at_mut(2);
    let (left_slot, right_slot) = pair.split_at_mut(1);
    let (below_left, below_right) = below.split_at_mut(left.nodes - 1);
    let left_at = at + 2;
    let right_at = left_at + below_left.len();
    if left.nodes.min(right.nodes) >= PARALLEL_NODES {
        rayon::join(
            || write(&mut left_slot[0], left, below_left, left_at, margin),
            || write(&mut right_slot[0], right, below_right, right_at, margin),
        );
    } else {
        write(&mut left_slot[0], left, below_left, left_at, margin);
        write(&mut right_slot[0], right, below_right, right_at, margin);
    }
}

fn node(bounds: &Aabb, margin: f64) -> Node {
    Node {
        bounds: bounds.grown(margin),
        first: 0,
        count: 0,
    }
}

fn leaf(bounds: &Aabb, first: usize, count: usize, margin: f64) -> Node {
    Node {
        first: first as u32,
        count: count as u32,
        ..node(bounds, margin)
    }
}
