//! Binned SAH construction (Wald 2007, "On fast construction of SAH-based bounding volume
//! hierarchies"): at each node, primitive centroids are dropped into bins along each axis, and
//! the split between bins with the lowest surface-area cost is taken; a node becomes a leaf
//! when no split is cheaper than testing all its primitives.
//!
//! One pass over a node's primitives fills the bins of all three axes; each bin keeps the box
//! of its primitives, so the children's boxes come out of the bins, and the pass that
//! partitions the primitives finds the boxes of the children's centroids.

use super::{Bvh, Node};
use crate::Aabb;
use glam::{Vec3A, Vec4};

/// Most bins per axis.
pub const MAX_BINS: usize = 32;

/// Settings of the build.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    /// Bins per axis (2 to [`MAX_BINS`]).
    pub bins: usize,
    /// Cost of visiting a node relative to testing one block of primitives.
    pub traversal_cost: f32,
    /// Primitives tested together (8 for SIMD triangle packs): a leaf of `n` primitives costs
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

/// A box in SIMD registers, for the builder's inner loops.
#[derive(Clone, Copy)]
struct Box3 {
    lo: Vec3A,
    hi: Vec3A,
}

impl Box3 {
    const EMPTY: Box3 = Box3 {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn union(self, o: Box3) -> Box3 {
        Box3 {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Box3 {
        Box3 {
            lo: self.lo.min(p),
            hi: self.hi.max(p),
        }
    }

    fn area(self) -> f32 {
        if self.lo.cmpgt(self.hi).any() {
            return 0.0;
        }
        let e = self.hi - self.lo;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    fn aabb(self) -> Aabb {
        Aabb::new(self.lo.into(), self.hi.into())
    }
}

/// A primitive as the builder moves it around: its box with its index in the corners' fourth
/// lanes, 32 bytes (Embree's layout). The passes over a node stream these; with the
/// centre stored beside them they were twice the size, and the top levels of a large mesh's
/// build waited on memory.
#[derive(Clone, Copy)]
struct Ref {
    lo: Vec4,
    hi: Vec4,
}

impl Ref {
    fn new(bounds: Box3, index: u32) -> Ref {
        Ref {
            lo: bounds.lo.extend(f32::from_bits(index & 0xffff | INDEX_TAG)),
            hi: bounds.hi.extend(f32::from_bits(index >> 16 | INDEX_TAG)),
        }
    }

    #[inline(always)]
    fn bounds(&self) -> Box3 {
        Box3 {
            lo: Vec3A::from_vec4(self.lo),
            hi: Vec3A::from_vec4(self.hi),
        }
    }

    /// The box's centre, [`Aabb::center`] bit for bit; an empty or infinite box has no usable
    /// centre, and any bin will do: the origin.
    #[inline(always)]
    fn center(&self) -> Vec3A {
        let b = self.bounds();
        let c = 0.5 * (b.lo + b.hi);
        if c.is_finite() { c } else { Vec3A::ZERO }
    }

    fn index(&self) -> u32 {
        let half = |w: f32| w.to_bits() & !INDEX_TAG;
        half(self.lo.w) | half(self.hi.w) << 16
    }
}

/// Set in the bits of a [`Ref`]'s index lanes (the index's low 16 bits in the lower corner's,
/// its high 16 in the upper's), so that they are normal floats: the box arithmetic runs over
/// all four lanes, and a small number's bits are a subnormal, on which every operation took a
/// microcode assist (the build ran at half speed).
const INDEX_TAG: u32 = 0x4000_0000;

/// A bin: how many primitives fell in and the box of their boxes.
#[derive(Clone, Copy)]
struct Bin {
    count: u32,
    bounds: Box3,
}

const EMPTY_BIN: Bin = Bin {
    count: 0,
    bounds: Box3::EMPTY,
};

/// A node waiting to be built: its range of primitives and what is known of them.
struct Work {
    node: usize,
    start: usize,
    end: usize,
    depth: usize,
    bounds: Box3,
    centroids: Box3,
}

/// A chosen split: the axis, the first bin on the right, and the children's boxes.
struct Split {
    axis: usize,
    bin: usize,
    cost: f32,
    left: Box3,
    right: Box3,
}

/// A split position with the two halves' boxes.
type Halves = (usize, (Box3, Box3), (Box3, Box3));

/// One task of the build: a range of the primitives (from slot `base`) and the nodes of its
/// subtree, the subtree's root first.
struct Builder<'a> {
    refs: &'a mut [Ref],
    base: usize,
    nodes: Vec<Node>,
    options: BuildOptions,
}

/// Nodes with at least this many primitives build their two subtrees in parallel. Smaller
/// ones are not worth a task; larger values leave a core idle near the top of the tree.
const PARALLEL_MIN: usize = 8192;

impl Bvh {
    /// Builds over `boxes` (primitive `i` has box `boxes[i]`), in parallel on rayon's threads;
    /// the tree is the same on any number of threads, and the same as a serial build's.
    pub fn build(boxes: &[Aabb], options: &BuildOptions) -> Self {
        Self::build_from(boxes.len(), |i| boxes[i], options)
    }

    /// [`Bvh::build`] over `count` primitives whose boxes `box_of` gives (no list of boxes
    /// is made: on a large mesh, first touches of fresh memory were a fifth of the build).
    pub fn build_from(
        count: usize,
        box_of: impl Fn(usize) -> Aabb + Sync,
        options: &BuildOptions,
    ) -> Self {
        Self::build_forking(count, box_of, options, PARALLEL_MIN)
    }

    /// [`Bvh::build_from`], forking subtrees of at least `parallel_min` primitives.
    fn build_forking(
        count: usize,
        box_of: impl Fn(usize) -> Aabb + Sync,
        options: &BuildOptions,
        parallel_min: usize,
    ) -> Self {
        use rayon::prelude::*;
        if count == 0 {
            return Self::default();
        }
        let mut refs: Vec<Ref> = (0..count)
            .into_par_iter()
            .map(|i| {
                // A NaN box belongs to a primitive no ray can hit: it must not spoil the unions.
                let b = box_of(i).or_empty_if_nan();
                let bounds = Box3 {
                    lo: b.min.into(),
                    hi: b.max.into(),
                };
                Ref::new(bounds, i as u32)
            })
            .collect();
        let options = BuildOptions {
            bins: options.bins.clamp(2, MAX_BINS),
            ..*options
        };
        let (bounds, centroids) = refs
            .par_chunks(parallel_min.max(1))
            .map(range_bounds)
            .reduce(
                || (Box3::EMPTY, Box3::EMPTY),
                |a, b| (a.0.union(b.0), a.1.union(b.1)),
            );
        let root = Work {
            node: 0,
            start: 0,
            end: count,
            depth: 0,
            bounds,
            centroids,
        };
        let nodes = match subtree(&mut refs, 0, options, root, parallel_min) {
            Piece::Nodes(nodes) => nodes,
            fork => {
                let mut nodes = vec![empty_node(); fork.len()];
                fork.lay_out(&mut nodes, 0, 1);
                nodes
            }
        };
        let prims = refs.par_iter().map(Ref::index).collect();
        Self { nodes, prims }
    }
}

/// A subtree as the build's tasks left it: the nodes one task built, its root first; or a
/// node whose halves were built by two tasks.
enum Piece {
    Nodes(Vec<Node>),
    Fork {
        root: Node,
        len: usize,
        halves: Box<(Piece, Piece)>,
    },
}

impl Piece {
    fn len(&self) -> usize {
        match self {
            Piece::Nodes(nodes) => nodes.len(),
            Piece::Fork { len, .. } => *len,
        }
    }

    /// Writes the subtree as the serial build lays it out (a node's two children side by
    /// side, the left child's descendants, then the right's), its root at `out[at]` and its
    /// descendants from `out[descendants]`: every node is copied once, into one allocation.
    fn lay_out(&self, out: &mut [Node], at: usize, descendants: usize) {
        match self {
            Piece::Nodes(nodes) => {
                // Node `i > 0` lands at `descendants + i - 1`.
                let moved = |n: &Node| match n.count {
                    0 => Node {
                        first: n.first + descendants as u32 - 1,
                        ..*n
                    },
                    _ => *n,
                };
                out[at] = moved(&nodes[0]);
                for (o, n) in out[descendants..].iter_mut().zip(&nodes[1..]) {
                    *o = moved(n);
                }
            }
            Piece::Fork { root, halves, .. } => {
                out[at] = Node {
                    first: descendants as u32,
                    count: 0,
                    ..*root
                };
                let (left, right) = &**halves;
                let below = descendants + 2;
                left.lay_out(out, descendants, below);
                right.lay_out(out, descendants + 1, below + left.len() - 1);
            }
        }
    }
}

/// The subtree over `refs` (primitive slots from `base`), forking its halves into two tasks
/// while they hold at least `parallel_min` primitives.
fn subtree(
    refs: &mut [Ref],
    base: usize,
    options: BuildOptions,
    root: Work,
    parallel_min: usize,
) -> Piece {
    let count = root.end - root.start;
    let serial = count < parallel_min;
    let capacity = if serial {
        2 * count / options.max_leaf_size.max(1) + 1
    } else {
        1
    };
    let mut b = Builder {
        refs,
        base,
        nodes: Vec::with_capacity(capacity),
        options,
    };
    b.nodes.push(empty_node());
    if serial {
        b.build_serially(root);
        return Piece::Nodes(b.nodes);
    }
    let Some((mid, left, right)) = b.split_node(&root) else {
        return Piece::Nodes(b.nodes);
    };
    let Builder { refs, nodes, .. } = b;
    let (l, r) = refs.split_at_mut(mid);
    let child = |refs: &[Ref], (bounds, centroids): (Box3, Box3)| Work {
        node: 0,
        start: 0,
        end: refs.len(),
        depth: root.depth + 1,
        bounds,
        centroids,
    };
    let (lw, rw) = (child(l, left), child(r, right));
    let halves = rayon::join(
        || subtree(l, base, options, lw, parallel_min),
        || subtree(r, base + mid, options, rw, parallel_min),
    );
    Piece::Fork {
        root: nodes[0],
        len: 1 + halves.0.len() + halves.1.len(),
        halves: Box::new(halves),
    }
}

/// The box of the boxes, and of the centroids, of `refs`.
fn range_bounds(refs: &[Ref]) -> (Box3, Box3) {
    refs.iter().fold((Box3::EMPTY, Box3::EMPTY), |(b, c), r| {
        (b.union(r.bounds()), c.grow(r.center()))
    })
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
    /// Builds the subtree of `root` (node 0) in this task. Iterative, so that deep trees cannot
    /// overflow the call stack.
    fn build_serially(&mut self, root: Work) {
        let mut work = vec![root];
        while let Some(w) = work.pop() {
            if let Some((mid, left, right)) = self.split_node(&w) {
                let first = self.nodes.len();
                self.nodes.push(empty_node());
                self.nodes.push(empty_node());
                self.nodes[w.node].first = first as u32;
                self.nodes[w.node].count = 0;
                let depth = w.depth + 1;
                work.push(Work {
                    node: first + 1,
                    start: mid,
                    end: w.end,
                    depth,
                    bounds: right.0,
                    centroids: right.1,
                });
                work.push(Work {
                    node: first,
                    start: w.start,
                    end: mid,
                    depth,
                    bounds: left.0,
                    centroids: left.1,
                });
            }
        }
    }

    /// The box of the boxes, and of the centroids, of `refs[start..end]`.
    fn range_bounds(&self, start: usize, end: usize) -> (Box3, Box3) {
        range_bounds(&self.refs[start..end])
    }

    /// Sets the node's box; makes it a leaf and returns `None`, or partitions its primitives and
    /// returns where the right half starts, with each half's box and centroid box.
    fn split_node(&mut self, w: &Work) -> Option<Halves> {
        let bounds = w.bounds.aabb();
        let n = &mut self.nodes[w.node];
        n.min = bounds.min.to_array();
        n.max = bounds.max.to_array();
        n.first = (self.base + w.start) as u32;
        n.count = (w.end - w.start) as u32;

        let count = w.end - w.start;
        if count <= 1 {
            return None;
        }
        let extent = w.centroids.hi - w.centroids.lo;
        let too_big = count > self.options.max_leaf_size;
        if extent.max_element() <= 0.0 {
            // All centroids coincide: no plane separates them. Split the list in halves only
            // when the leaf would be too large.
            return too_big.then(|| self.halves(w.start, w.end, w.start + count / 2));
        }
        if w.depth >= self.options.max_sah_depth {
            return Some(self.median_split(w.start, w.end, extent.max_position()));
        }
        // Every split costs at least the traversal: when that is no cheaper than the leaf, no
        // split can win, and the bins need not be filled (most nodes near the leaves).
        if !too_big && self.options.traversal_cost >= self.blocks(count as u32) {
            return None;
        }
        match self.best_split(w) {
            Some(split) if split.cost < self.blocks(count as u32) || too_big => {
                let (mid, lc, rc) =
                    self.partition(w.start, w.end, split.axis, split.bin, w.centroids);
                if mid == w.start || mid == w.end {
                    Some(self.median_split(w.start, w.end, extent.max_position()))
                } else {
                    Some((mid, (split.left, lc), (split.right, rc)))
                }
            }
            None if too_big => Some(self.median_split(w.start, w.end, extent.max_position())),
            _ => None,
        }
    }

    /// Tests needed for `n` primitives.
    fn blocks(&self, n: u32) -> f32 {
        n.div_ceil(self.options.block.max(1) as u32) as f32
    }

    /// The bins per axis of centroids `c` in a node whose centroids start at `lo`, with
    /// `scale = bins / extent` (0 along a flat axis).
    #[inline(always)]
    fn bins_of(&self, c: Vec3A, lo: Vec3A, scale: Vec3A) -> [usize; 3] {
        // Truncated in SIMD, where NaN and out-of-range values become `i32::MIN`; then
        // clamped, which also keeps the top edge (`bins`) in the last bin. (Rust's saturating
        // `as usize` per lane took a quarter of the build.)
        let k = (c - lo) * scale;
        let k = wide::f32x4::new([k.x, k.y, k.z, 0.0]).fast_trunc_int();
        let top = wide::i32x4::splat(self.options.bins as i32 - 1);
        let k = k.max(wide::i32x4::ZERO).min(top).to_array();
        [k[0] as usize, k[1] as usize, k[2] as usize]
    }

    fn scale(&self, centroids: Box3) -> Vec3A {
        let e = centroids.hi - centroids.lo;
        let nb = self.options.bins as f32;
        Vec3A::select(e.cmpgt(Vec3A::ZERO), Vec3A::splat(nb) / e, Vec3A::ZERO)
    }

    /// The cheapest split over all axes and bin boundaries, by the SAH:
    /// `cost = traversal + (area(L)·tests(L) + area(R)·tests(R)) / area(node)`, in units of one test.
    fn best_split(&self, w: &Work) -> Option<Split> {
        // Arrays of the bins in use only: filling and sweeping unused ones was a sixth of
        // the build.
        if self.options.bins <= 16 {
            self.best_split_in::<16>(w)
        } else {
            self.best_split_in::<MAX_BINS>(w)
        }
    }

    /// [`Builder::best_split`] with room for `N` bins per axis.
    fn best_split_in<const N: usize>(&self, w: &Work) -> Option<Split> {
        let nb = self.options.bins;
        let (lo, scale) = (w.centroids.lo, self.scale(w.centroids));
        let mut bins = [[EMPTY_BIN; N]; 3];
        for r in &self.refs[w.start..w.end] {
            let k = self.bins_of(r.center(), lo, scale);
            for axis in 0..3 {
                let bin = &mut bins[axis][k[axis]];
                bin.count += 1;
                bin.bounds = bin.bounds.union(r.bounds());
            }
        }
        let parent_area = w.bounds.area().max(f32::MIN_POSITIVE);
        let mut best: Option<Split> = None;
        for (axis, bins) in bins.iter().enumerate() {
            if scale[axis] == 0.0 {
                continue;
            }
            // Right-hand sums: `right[k]` covers bins `k..`.
            let mut right = [EMPTY_BIN; N];
            let mut acc = EMPTY_BIN;
            for k in (1..nb).rev() {
                acc = merge(acc, bins[k]);
                right[k] = acc;
            }
            let mut left = EMPTY_BIN;
            for k in 1..nb {
                left = merge(left, bins[k - 1]);
                let r = right[k];
                if left.count == 0 || r.count == 0 {
                    continue;
                }
                let cost = self.options.traversal_cost
                    + (left.bounds.area() * self.blocks(left.count)
                        + r.bounds.area() * self.blocks(r.count))
                        / parent_area;
                if best.as_ref().is_none_or(|b| cost < b.cost) {
                    best = Some(Split {
                        axis,
                        bin: k,
                        cost,
                        left: left.bounds,
                        right: r.bounds,
                    });
                }
            }
        }
        best
    }

    /// Moves the primitives whose centroid falls left of bin `bin` along `axis` to the front;
    /// returns where the rest starts, and the boxes of the two sides' centroids.
    fn partition(
        &mut self,
        start: usize,
        end: usize,
        axis: usize,
        bin: usize,
        centroids: Box3,
    ) -> (usize, Box3, Box3) {
        let (lo, scale) = (centroids.lo, self.scale(centroids));
        let (mut left, mut right) = (Box3::EMPTY, Box3::EMPTY);
        let top = self.options.bins as i32 - 1;
        // Without a branch on the side (Lomuto's scheme, every primitive swapped to the left
        // end, which advances only past the left ones): the side of a primitive is a coin
        // toss to the branch predictor, and its misses were a third of the build. The halves
        // hold the same primitives as before, in another order.
        let refs = &mut self.refs[start..end];
        let mut i = 0;
        for j in 0..refs.len() {
            let c = refs[j].center();
            let is_left = bin_on_axis(c[axis], lo[axis], scale[axis], top) < bin;
            let side = glam::BVec3A::splat(is_left);
            left.lo = Vec3A::select(side, left.lo.min(c), left.lo);
            left.hi = Vec3A::select(side, left.hi.max(c), left.hi);
            right.lo = Vec3A::select(side, right.lo, right.lo.min(c));
            right.hi = Vec3A::select(side, right.hi, right.hi.max(c));
            refs.swap(i, j);
            i += usize::from(is_left);
        }
        let i = start + i;
        (i, left, right)
    }

    /// Splits at the median centroid along `axis`.
    fn median_split(&mut self, start: usize, end: usize, axis: usize) -> Halves {
        let mid = start + (end - start) / 2;
        self.refs[start..end].select_nth_unstable_by(mid - start, |a, b| {
            a.center()[axis].total_cmp(&b.center()[axis])
        });
        self.halves(start, end, mid)
    }

    /// `mid` with the boxes of the two halves.
    fn halves(&self, start: usize, end: usize, mid: usize) -> Halves {
        (
            mid,
            self.range_bounds(start, mid),
            self.range_bounds(mid, end),
        )
    }
}

/// [`Builder::bins_of`] along one axis, in scalar code with the same answer (the partition
/// needs one axis).
#[inline(always)]
fn bin_on_axis(c: f32, lo: f32, scale: f32, top: i32) -> usize {
    let k = (c - lo) * scale;
    // As the vector truncation: NaN and values out of `i32`'s range become `i32::MIN`.
    let k = if k > -2_147_483_648.0 && k < 2_147_483_648.0 {
        k as i32
    } else {
        i32::MIN
    };
    k.clamp(0, top) as usize
}

fn merge(a: Bin, b: Bin) -> Bin {
    Bin {
        count: a.count + b.count,
        bounds: a.bounds.union(b.bounds),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_ref_keeps_its_index_and_centre() {
        let bounds = Box3 {
            lo: Vec3A::new(-1.0, 2.0, 3.0),
            hi: Vec3A::new(1.0, 2.5, 7.0),
        };
        for index in [0, 1, 0xffff, 0x1_0000, 123_456_789, u32::MAX] {
            let r = Ref::new(bounds, index);
            assert_eq!(r.index(), index);
            assert_eq!(
                Vec3::from(r.center()),
                Aabb::new(bounds.lo.into(), bounds.hi.into()).center()
            );
        }
        assert_eq!(Ref::new(Box3::EMPTY, 5).center(), Vec3A::ZERO);
    }

    /// Uniform values in `[0, 1]` from an xorshift generator seeded with `seed`.
    fn uniforms(seed: u32) -> impl FnMut() -> f32 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as f32 / u32::MAX as f32
        }
    }

    /// Boxes of `n` random small triangles in a unit cube, with a cluster of coincident ones.
    fn random_boxes(n: usize) -> Vec<Aabb> {
        let mut next = uniforms(0x9e37_79b9);
        (0..n)
            .map(|i| {
                let c = if i % 97 == 0 {
                    Vec3::splat(0.5)
                } else {
                    Vec3::new(next(), next(), next())
                };
                let e = Vec3::new(next(), next(), next()) * 0.01;
                Aabb::new(c - e, c + e)
            })
            .collect()
    }

    #[test]
    fn a_parallel_build_lays_out_the_serial_tree_on_any_number_of_threads() {
        let boxes = random_boxes(20_000);
        let options = BuildOptions::default();
        let serial = Bvh::build_forking(boxes.len(), |i| boxes[i], &options, usize::MAX);
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            for parallel_min in [64, 1000, PARALLEL_MIN] {
                let forked = pool.install(|| {
                    Bvh::build_forking(boxes.len(), |i| boxes[i], &options, parallel_min)
                });
                assert_eq!(
                    forked.nodes, serial.nodes,
                    "{threads} threads, {parallel_min}"
                );
                assert_eq!(
                    forked.prims, serial.prims,
                    "{threads} threads, {parallel_min}"
                );
            }
        }
        assert!(serial.nodes.len() > 1000);
    }

    #[test]
    fn one_axis_bins_as_all_three_do() {
        let b = Builder {
            refs: &mut [],
            base: 0,
            nodes: Vec::new(),
            options: BuildOptions::default(),
        };
        let top = b.options.bins as i32 - 1;
        let specials = [
            0.0,
            -0.0,
            -0.5,
            -1.0,
            -3.0e9,
            0.999_999,
            1.0,
            7.5,
            15.999,
            16.0,
            17.0,
            2.0e9,
            3.0e9,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut next = uniforms(0x2545_f491);
        let random = (0..10_000).map(|_| next() * 40.0 - 10.0);
        for c in specials.into_iter().chain(random) {
            for (lo, scale) in [(0.0, 1.0), (-2.5, 3.2), (1.0, 0.0), (0.0, 1e30)] {
                let all = b.bins_of(Vec3A::splat(c), Vec3A::splat(lo), Vec3A::splat(scale));
                assert_eq!(bin_on_axis(c, lo, scale, top), all[0], "{c} {lo} {scale}");
            }
        }
    }
}
