//! Binned SAH construction (Wald 2007, "On fast construction of SAH-based bounding volume
//! hierarchies"): at each node, primitive centroids are dropped into bins along each axis, and
//! the split between bins with the lowest surface-area cost is taken; a node becomes a leaf
//! when no split is cheaper than testing all its primitives.

use super::{Bvh, Node};
use crate::Aabb;
use glam::Vec3;

/// Settings of the build.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    /// Bins per axis.
    pub bins: usize,
    /// Cost of visiting a node relative to testing one block of primitives.
    pub traversal_cost: f32,
    /// Primitives tested together (4 for SIMD triangle packs): a leaf of `n` primitives costs
    /// `⌈n / block⌉` tests, so the SAH does not split what one test handles anyway.
    pub block: usize,
    /// Leaves never hold more than this many primitives (unless they all share one centroid).
    pub max_leaf_size: usize,
    /// Below this depth SAH decides; deeper nodes are split at the object median, which bounds
    /// the tree's depth (and the traversal stack) by this plus log2 of the primitive count.
    pub max_sah_depth: usize,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            bins: 16,
            traversal_cost: 1.0,
            block: 1,
            max_leaf_size: 8,
            max_sah_depth: 48,
        }
    }
}

/// A split: the axis and the first bin on the right.
#[derive(Clone, Copy)]
struct Split {
    axis: usize,
    bin: usize,
    cost: f32,
}

struct Builder<'a> {
    boxes: &'a [Aabb],
    centroids: Vec<Vec3>,
    prims: Vec<u32>,
    nodes: Vec<Node>,
    options: BuildOptions,
}

impl Bvh {
    /// Builds over `boxes` (primitive `i` has box `boxes[i]`).
    pub fn build(boxes: &[Aabb], options: &BuildOptions) -> Self {
        if boxes.is_empty() {
            return Self::default();
        }
        // A NaN box belongs to a primitive no ray can hit: it must not spoil the unions.
        let boxes: Vec<Aabb> = boxes.iter().map(|b| b.or_empty_if_nan()).collect();
        let centroids = boxes
            .iter()
            .map(|b| {
                let c = b.center();
                // An empty or infinite box has no usable centre; any bin will do.
                if c.is_finite() { c } else { Vec3::ZERO }
            })
            .collect();
        let mut b = Builder {
            boxes: &boxes,
            centroids,
            prims: (0..boxes.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * boxes.len() / options.max_leaf_size.max(1) + 1),
            options: *options,
        };
        b.nodes.push(empty_node());
        // Work list of (node, start, end, depth): iterative, so deep trees cannot overflow the stack.
        let mut work = vec![(0usize, 0usize, boxes.len(), 0usize)];
        while let Some((node, start, end, depth)) = work.pop() {
            if let Some(mid) = b.split_node(node, start, end, depth) {
                let left = b.nodes.len();
                b.nodes.push(empty_node());
                b.nodes.push(empty_node());
                b.nodes[node].first = left as u32;
                b.nodes[node].count = 0;
                work.push((left + 1, mid, end, depth + 1));
                work.push((left, start, mid, depth + 1));
            }
        }
        Self {
            nodes: b.nodes,
            prims: b.prims,
        }
    }
}

fn empty_node() -> Node {
    Node {
        min: [0.0; 3],
        first: 0,
        max: [0.0; 3],
        count: 0,
    }
}

impl Builder<'_> {
    /// Sets the node's box; makes it a leaf and returns `None`, or partitions its primitives and
    /// returns where the right half starts.
    fn split_node(&mut self, node: usize, start: usize, end: usize, depth: usize) -> Option<usize> {
        let range = &self.prims[start..end];
        let bounds = range
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.union(self.boxes[p as usize]));
        let centroid_bounds = range
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.grow(self.centroids[p as usize]));
        let n = &mut self.nodes[node];
        n.min = bounds.min.to_array();
        n.max = bounds.max.to_array();
        n.first = start as u32;
        n.count = (end - start) as u32;

        let count = end - start;
        if count <= 1 {
            return None;
        }
        let extent = centroid_bounds.extent();
        if extent.max_element() <= 0.0 {
            // All centroids coincide: no plane separates them. Split the list in halves only
            // when the leaf would be too large.
            return (count > self.options.max_leaf_size).then_some(start + count / 2);
        }
        if depth >= self.options.max_sah_depth {
            return Some(self.median_split(start, end, extent.max_position()));
        }
        let best = self.best_split(start, end, bounds, centroid_bounds);
        let leaf_cost = self.blocks(count as u32);
        let too_big = count > self.options.max_leaf_size;
        match best {
            Some(split) if split.cost < leaf_cost || too_big => {
                let mid = self.partition(start, end, split, centroid_bounds);
                if mid == start || mid == end {
                    Some(self.median_split(start, end, extent.max_position()))
                } else {
                    Some(mid)
                }
            }
            None if too_big => Some(self.median_split(start, end, extent.max_position())),
            _ => None,
        }
    }

    /// Tests needed for `n` primitives.
    fn blocks(&self, n: u32) -> f32 {
        n.div_ceil(self.options.block.max(1) as u32) as f32
    }

    fn bin_of(&self, c: Vec3, axis: usize, cb: Aabb) -> usize {
        let bins = self.options.bins;
        let extent = cb.max[axis] - cb.min[axis];
        let k = ((c[axis] - cb.min[axis]) * (bins as f32 / extent)) as usize; // NaN and negatives cast to 0
        k.min(bins - 1)
    }

    /// The cheapest split over all axes and bin boundaries, by the SAH:
    /// `cost = traversal + (area(L)·|L| + area(R)·|R|) / area(node)`, in units of one primitive test.
    fn best_split(&self, start: usize, end: usize, bounds: Aabb, cb: Aabb) -> Option<Split> {
        let bins = self.options.bins;
        let parent_area = bounds.surface_area();
        let mut best: Option<Split> = None;
        let mut bin_boxes = vec![Aabb::EMPTY; bins];
        let mut bin_counts = vec![0u32; bins];
        let mut right_area = vec![0.0f32; bins];
        for axis in 0..3 {
            if cb.max[axis] - cb.min[axis] <= 0.0 {
                continue;
            }
            bin_boxes.fill(Aabb::EMPTY);
            bin_counts.fill(0);
            for &p in &self.prims[start..end] {
                let k = self.bin_of(self.centroids[p as usize], axis, cb);
                bin_boxes[k] = bin_boxes[k].union(self.boxes[p as usize]);
                bin_counts[k] += 1;
            }
            // Sweep from the right: right_area[k] is the area of bins k.. (k ≥ 1).
            let mut acc = Aabb::EMPTY;
            for k in (1..bins).rev() {
                acc = acc.union(bin_boxes[k]);
                right_area[k] = acc.surface_area();
            }
            let (mut left_box, mut left_count) = (Aabb::EMPTY, 0u32);
            let total = (end - start) as u32;
            for k in 1..bins {
                left_box = left_box.union(bin_boxes[k - 1]);
                left_count += bin_counts[k - 1];
                let right_count = total - left_count;
                if left_count == 0 || right_count == 0 {
                    continue;
                }
                let cost = self.options.traversal_cost
                    + (left_box.surface_area() * self.blocks(left_count)
                        + right_area[k] * self.blocks(right_count))
                        / parent_area.max(f32::MIN_POSITIVE);
                if best.is_none_or(|b| cost < b.cost) {
                    best = Some(Split { axis, bin: k, cost });
                }
            }
        }
        best
    }

    /// Moves the primitives left of the split to the front; returns where the rest starts.
    fn partition(&mut self, start: usize, end: usize, split: Split, cb: Aabb) -> usize {
        let (mut i, mut j) = (start, end);
        while i < j {
            if self.bin_of(self.centroids[self.prims[i] as usize], split.axis, cb) < split.bin {
                i += 1;
            } else {
                j -= 1;
                self.prims.swap(i, j);
            }
        }
        i
    }

    /// Splits at the median centroid along `axis`.
    fn median_split(&mut self, start: usize, end: usize, axis: usize) -> usize {
        let mid = start + (end - start) / 2;
        let centroids = &self.centroids;
        self.prims[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
        });
        mid
    }
}
