//! Octrees (Glassner 1984): "each box contains eight smaller ones; check smaller ones only if
//! hit larger one".
//!
//! The root is the scene's bounding cube. A cell holding more than `leaf_size` primitives is
//! split at its centre into eight octants, down to a depth limit; a primitive is referenced by
//! every leaf its box overlaps. A ray visits the cells it crosses front to back and stops after
//! the first cell in which it found a hit lying inside that cell; a mailbox makes sure a
//! primitive referenced by several cells is tested once per ray.

use crate::aabb::CULL_SLACK;
use crate::mailbox::Mailbox;
use crate::{Aabb, Accelerator, Ray, TraversalStats};
use arrayvec::ArrayVec;
use glam::Vec3;

/// Marks an interior cell in [`Cell::count`].
const INTERIOR: u32 = u32::MAX;

/// One cell: its box, and either its eight children (`first..first + 8`) or its primitive
/// references (`refs[first..first + count]`).
#[derive(Clone, Copy, Debug)]
struct Cell {
    bounds: Aabb,
    first: u32,
    count: u32,
}

/// Settings of the octree build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OctreeOptions {
    /// A cell with more primitives than this is split (depth permitting).
    pub leaf_size: usize,
    /// The deepest level; `None` picks `⌈log8(n)⌉ + 2`. At most 12 either way.
    pub max_depth: Option<usize>,
}

impl Default for OctreeOptions {
    fn default() -> Self {
        Self {
            leaf_size: 8,
            max_depth: None,
        }
    }
}

/// An octree over primitive boxes.
#[derive(Clone, Debug, Default)]
pub struct Octree {
    cells: Vec<Cell>,
    refs: Vec<u32>,
    /// Primitives with an infinite box: no cube holds them, so every ray tests them.
    unbounded: Vec<u32>,
    primitives: usize,
}

impl Octree {
    /// Builds with the default options.
    pub fn new(boxes: &[Aabb]) -> Self {
        Self::build(boxes, &OctreeOptions::default())
    }

    /// Builds over `boxes`.
    pub fn build(boxes: &[Aabb], options: &OctreeOptions) -> Self {
        let finite = |b: &Aabb| b.min.is_finite() && b.max.is_finite();
        let unbounded: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| !finite(&boxes[i as usize]) && !boxes[i as usize].has_nan())
            .collect();
        let bounds = boxes
            .iter()
            .filter(|b| finite(b))
            .fold(Aabb::EMPTY, |a, b| a.union(*b));
        if bounds.is_empty() {
            return Self {
                unbounded,
                primitives: boxes.len(),
                ..Self::default()
            };
        }
        // A cube around the bounds, so that cells stay cubes.
        let half = 0.5 * bounds.extent().max_element();
        let center = bounds.center();
        // The union guards against rounding leaving a face of the bounds just outside the cube.
        let root = Aabb::new(center - Vec3::splat(half), center + Vec3::splat(half)).union(bounds);
        let max_depth = options
            .max_depth
            .unwrap_or_else(|| (boxes.len().max(1) as f64).log(8.0).ceil() as usize + 2)
            .min(12);

        let mut tree = Self {
            cells: vec![],
            refs: vec![],
            unbounded,
            primitives: boxes.len(),
        };
        let all: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| finite(&boxes[i as usize]))
            .collect();
        tree.cells.push(Cell {
            bounds: root,
            first: 0,
            count: 0,
        });
        let mut work = vec![(0usize, all, 0usize)];
        while let Some((cell, prims, depth)) = work.pop() {
            let bounds = tree.cells[cell].bounds;
            let children = (prims.len() > options.leaf_size && depth < max_depth)
                .then(|| split(bounds, &prims, boxes))
                .filter(|kids| kids.iter().any(|(_, p)| p.len() < prims.len()));
            match children {
                Some(kids) => {
                    let first = tree.cells.len();
                    tree.cells[cell].first = first as u32;
                    tree.cells[cell].count = INTERIOR;
                    for (i, (b, p)) in kids.into_iter().enumerate() {
                        tree.cells.push(Cell {
                            bounds: b,
                            first: 0,
                            count: 0,
                        });
                        work.push((first + i, p, depth + 1));
                    }
                }
                None => {
                    tree.cells[cell].first = tree.refs.len() as u32;
                    tree.cells[cell].count = prims.len() as u32;
                    tree.refs.extend(prims);
                }
            }
        }
        tree
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Number of levels below and including the root.
    pub fn depth(&self) -> usize {
        fn walk(cells: &[Cell], i: usize) -> usize {
            let c = &cells[i];
            if c.count == INTERIOR {
                1 + (0..8)
                    .map(|k| walk(cells, c.first as usize + k))
                    .max()
                    .unwrap_or(0)
            } else {
                1
            }
        }
        if self.cells.is_empty() {
            0
        } else {
            walk(&self.cells, 0)
        }
    }

    /// Bytes held by cells and references.
    pub fn memory_bytes(&self) -> usize {
        self.cells.len() * size_of::<Cell>()
            + (self.refs.len() + self.unbounded.len()) * size_of::<u32>()
    }

    /// Offers the unbounded primitives first (as a leaf with no far wall), then visits the
    /// leaves `ray` enters before `t_max`, front to back, calling
    /// `visit_leaf(refs, exit, t_max, stats)` on each until it returns `true`.
    fn walk<F>(
        &self,
        ray: &Ray,
        t_max: &mut f32,
        stats: &mut TraversalStats,
        mut visit_leaf: F,
    ) -> bool
    where
        F: FnMut(&[u32], f32, &mut f32, &mut TraversalStats) -> bool,
    {
        if !self.unbounded.is_empty()
            && visit_leaf(&self.unbounded, f32::NEG_INFINITY, t_max, stats)
        {
            return true;
        }
        let Some(root) = self.cells.first() else {
            return false;
        };
        let Some((t0, t1)) = root.bounds.hit_interval(ray, *t_max) else {
            return false;
        };
        // Each level pushes at most 8 cells (a ray crosses at most 4 octants of a cell).
        let mut stack: ArrayVec<(usize, f32, f32), { 8 * 13 }> = ArrayVec::new();
        stack.push((0, t0, t1));
        while let Some((cell, entry, exit)) = stack.pop() {
            // With the box test's own slack: an entry rounded up must not hide a tie.
            if entry > *t_max * CULL_SLACK {
                continue;
            }
            stats.nodes_visited += 1;
            let c = &self.cells[cell];
            if c.count != INTERIOR {
                let refs = &self.refs[c.first as usize..(c.first + c.count) as usize];
                if visit_leaf(refs, exit, t_max, stats) {
                    return true;
                }
                continue;
            }
            // Children the ray enters, pushed farthest first so the nearest is visited next.
            let mut kids: [(usize, f32, f32); 8] = [(0, 0.0, 0.0); 8];
            let mut n = 0;
            for k in 0..8 {
                let child = c.first as usize + k;
                if let Some((a, b)) = self.cells[child].bounds.hit_interval(ray, *t_max) {
                    kids[n] = (child, a, b);
                    n += 1;
                }
            }
            kids[..n].sort_unstable_by(|x, y| y.1.total_cmp(&x.1));
            stack.extend(kids[..n].iter().copied());
        }
        false
    }
}

/// True when the closed boxes share a point.
fn overlaps(a: Aabb, b: Aabb) -> bool {
    a.min.cmple(b.max).all() && b.min.cmple(a.max).all()
}

/// The eight octants of `bounds` and the primitives overlapping each.
fn split(bounds: Aabb, prims: &[u32], boxes: &[Aabb]) -> Vec<(Aabb, Vec<u32>)> {
    let c = bounds.center();
    (0..8)
        .map(|k| {
            let pick = |bit: usize, axis: usize| {
                if k & bit == 0 {
                    (bounds.min[axis], c[axis])
                } else {
                    (c[axis], bounds.max[axis])
                }
            };
            let ((x0, x1), (y0, y1), (z0, z1)) = (pick(1, 0), pick(2, 1), pick(4, 2));
            let b = Aabb::new(Vec3::new(x0, y0, z0), Vec3::new(x1, y1, z1));
            (
                b,
                prims
                    .iter()
                    .copied()
                    .filter(|&p| overlaps(b, boxes[p as usize]))
                    .collect(),
            )
        })
        .collect()
}

impl Accelerator for Octree {
    fn closest_hit<F>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        Mailbox::with(self.primitives, |mailbox| {
            let mut hit = false;
            self.walk(ray, &mut t_max, stats, |refs, exit, t_max, stats| {
                for &p in refs {
                    if mailbox.first_visit(p) {
                        stats.primitives_tested += 1;
                        hit |= leaf(p, t_max);
                    }
                }
                // A hit inside this cell is nearer than anything in the cells beyond it; one on
                // (or, by rounding, near) the far wall may tie with one in the next cell.
                hit && *t_max * CULL_SLACK < exit
            });
            hit
        })
    }

    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        let mut t_max = t_max;
        Mailbox::with(self.primitives, |mailbox| {
            self.walk(ray, &mut t_max, stats, |refs, _, _, stats| {
                refs.iter().any(|&p| {
                    mailbox.first_visit(p) && {
                        stats.primitives_tested += 1;
                        leaf(p)
                    }
                })
            })
        })
    }
}
