//! Constructive solid geometry: solids combined by union, intersection, difference and merge
//! (POV-Ray's four), nested to any depth, any part turned inside out (`inverse`).
//!
//! A ray is followed along its whole line: every leaf's crossings, in order, tell where the ray
//! is inside which leaf (a leaf is inside at the ray's origin when an odd number of its
//! crossings lie behind it). A leaf's crossing is a surface of the combination when, at that
//! point, every operation above the leaf keeps it:
//!
//! | operation | a surface of child C is kept where |
//! | --- | --- |
//! | union | always (POV-Ray's union keeps the inner surfaces, which glass shows) |
//! | merge | every other child is outside |
//! | intersection | every other child is inside |
//! | difference (first child minus the rest) | C first: every other child outside; C later: the first inside, the others outside |
//!
//! A subtracted child's surface faces the other way (its outside is the result's inside), as
//! does that of any part with `inverse`.

use super::{Crossings, Solid, SolidPoint};
use glam::Vec3;
use lucent_accel::{Aabb, Ray};

/// How a node combines its children.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgOp {
    /// Every child's surfaces; inside any child.
    Union,
    /// Inside every child.
    Intersection,
    /// Inside the first child and outside the others.
    Difference,
    /// Inside any child, with only the outer surfaces.
    Merge,
}

impl CsgOp {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            CsgOp::Union => "union",
            CsgOp::Intersection => "intersection",
            CsgOp::Difference => "difference",
            CsgOp::Merge => "merge",
        }
    }
}

/// A tree of solids, as built ([`Csg::new`] flattens it). (Its leaves are larger than its
/// nodes; it is built once per object, so they are not boxed.)
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum CsgTree {
    /// A closed solid and the material its surface wears.
    Leaf {
        /// The solid, placed in the world.
        solid: Solid,
        /// Index into the scene's materials.
        material: u32,
        /// Inside out.
        inverse: bool,
    },
    /// An operation over two or more children.
    Node {
        /// How the children combine.
        op: CsgOp,
        /// The children, in order (a difference subtracts the others from the first).
        children: Vec<CsgTree>,
        /// Inside out.
        inverse: bool,
    },
}

/// Why a tree cannot be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CsgError {
    /// A leaf that bounds no volume.
    #[error("a {0} bounds no volume, so it cannot be combined (give it its caps)")]
    Open(&'static str),
    /// An operation with fewer than two children.
    #[error("a {0} needs at least two children")]
    TooFew(&'static str),
    /// An unbounded result.
    #[error(
        "the combination is unbounded (everything outside a solid): intersect or subtract it instead"
    )]
    Unbounded,
}

/// One node of the flattened tree.
#[derive(Clone, Debug, PartialEq)]
struct Node {
    /// `None` for a leaf (its index in `leaves` is in `first`).
    op: Option<CsgOp>,
    inverse: bool,
    parent: Option<u32>,
    /// A leaf: its leaf index; an operation: its children's node indices.
    children: Vec<u32>,
}

/// A combination of solids, ready for rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Csg {
    nodes: Vec<Node>,
    /// Each leaf's solid, material and node.
    leaves: Vec<(Solid, u32, u32)>,
    bounds: Aabb,
    /// The material every leaf wears, when they all wear one (shadow rays then see it once).
    uniform: Option<u32>,
}

/// A visible crossing: where, of which leaf, on which part, and whether the leaf's outward
/// normal faces into the combination there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CsgHit {
    /// The ray parameter.
    pub t: f64,
    /// The leaf.
    pub leaf: u32,
    /// The part of the leaf's surface.
    pub part: u8,
    /// The leaf's outward normal points into the result here.
    pub flip: bool,
}

impl Csg {
    /// The tree flattened, checked (closed leaves, two or more children, bounded).
    pub fn new(tree: &CsgTree) -> Result<Self, CsgError> {
        let mut csg = Csg {
            nodes: Vec::new(),
            leaves: Vec::new(),
            bounds: Aabb::EMPTY,
            uniform: None,
        };
        csg.add(tree, None)?;
        csg.bounds = csg.bounds_of(0).ok_or(CsgError::Unbounded)?;
        let first = csg.leaves.first().map(|l| l.1);
        csg.uniform = first.filter(|&m| csg.leaves.iter().all(|l| l.1 == m));
        Ok(csg)
    }

    fn add(&mut self, tree: &CsgTree, parent: Option<u32>) -> Result<u32, CsgError> {
        let id = self.nodes.len() as u32;
        match tree {
            CsgTree::Leaf {
                solid,
                material,
                inverse,
            } => {
                if !solid.is_closed() {
                    return Err(CsgError::Open(solid.shape.name()));
                }
                self.nodes.push(Node {
                    op: None,
                    inverse: *inverse,
                    parent,
                    children: vec![self.leaves.len() as u32],
                });
                self.leaves.push((*solid, *material, id));
            }
            CsgTree::Node {
                op,
                children,
                inverse,
            } => {
                if children.len() < 2 {
                    return Err(CsgError::TooFew(op.name()));
                }
                self.nodes.push(Node {
                    op: Some(*op),
                    inverse: *inverse,
                    parent,
                    children: Vec::new(),
                });
                for c in children {
                    let child = self.add(c, Some(id))?;
                    self.nodes[id as usize].children.push(child);
                }
            }
        }
        Ok(id)
    }

    /// The box about node `n`'s volume; `None` when it is unbounded.
    fn bounds_of(&self, n: u32) -> Option<Aabb> {
        let node = &self.nodes[n as usize];
        if node.inverse {
            return None;
        }
        let Some(op) = node.op else {
            let solid = &self.leaves[node.children[0] as usize].0;
            return solid.is_bounded().then(|| solid.bounds());
        };
        let mut boxes = node.children.iter().map(|&c| self.bounds_of(c));
        match op {
            CsgOp::Union | CsgOp::Merge => boxes.try_fold(Aabb::EMPTY, |b, x| Some(b.union(x?))),
            // A difference lies within its first child; an intersection within any bounded
            // child (an unbounded one, inside out, only cuts).
            CsgOp::Difference => boxes.next().flatten(),
            CsgOp::Intersection => boxes
                .flatten()
                .reduce(|a, b| Aabb::new(a.min.max(b.min), a.max.min(b.max))),
        }
    }

    /// The box about it.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// How many leaves it has.
    pub fn leaves(&self) -> usize {
        self.leaves.len()
    }

    /// Leaf `i`'s material.
    pub fn material(&self, leaf: u32) -> u32 {
        self.leaves[leaf as usize].1
    }

    /// Whether node `n` holds the point whose leaves' insides are `inside`.
    fn holds(&self, n: u32, inside: &[bool]) -> bool {
        let node = &self.nodes[n as usize];
        let held = match node.op {
            None => inside[node.children[0] as usize],
            Some(CsgOp::Union | CsgOp::Merge) => {
                node.children.iter().any(|&c| self.holds(c, inside))
            }
            Some(CsgOp::Intersection) => node.children.iter().all(|&c| self.holds(c, inside)),
            Some(CsgOp::Difference) => {
                let (first, rest) = node.children.split_first().expect("two or more");
                self.holds(*first, inside) && !rest.iter().any(|&c| self.holds(c, inside))
            }
        };
        held != node.inverse
    }

    /// Whether leaf `leaf`'s surface is one of the combination's where the other leaves'
    /// insides are `inside`; and if so, whether its outward normal faces into the result.
    fn kept(&self, leaf: u32, inside: &[bool]) -> Option<bool> {
        let mut node = self.leaves[leaf as usize].2;
        let mut flip = self.nodes[node as usize].inverse;
        while let Some(parent) = self.nodes[node as usize].parent {
            let p = &self.nodes[parent as usize];
            let others = || p.children.iter().filter(|&&c| c != node);
            let keep = match p.op.expect("a parent is an operation") {
                CsgOp::Union => true,
                CsgOp::Merge => !others().any(|&c| self.holds(c, inside)),
                CsgOp::Intersection => others().all(|&c| self.holds(c, inside)),
                CsgOp::Difference => {
                    let first = p.children[0];
                    if node == first {
                        !others().any(|&c| self.holds(c, inside))
                    } else {
                        flip = !flip;
                        self.holds(first, inside)
                            && !others().any(|&c| c != first && self.holds(c, inside))
                    }
                }
            };
            if !keep {
                return None;
            }
            flip ^= p.inverse;
            node = parent;
        }
        Some(flip)
    }

    /// The combination's surfaces along `ray` in `(0, t_max)`, nearest first, until `visit`
    /// returns `true`; whether it did.
    fn walk(&self, ray: &Ray, t_max: f32, mut visit: impl FnMut(CsgHit) -> bool) -> bool {
        let n = self.leaves.len();
        let mut inside = vec![false; n];
        let mut events: Vec<(f64, u32, u8)> = Vec::new();
        let t_max = f64::from(t_max);
        for (i, (solid, _, _)) in self.leaves.iter().enumerate() {
            let all: Crossings = solid.crossings_in(ray, f64::NEG_INFINITY, t_max);
            let behind = all.iter().filter(|c| c.0 <= 0.0).count();
            inside[i] = solid.starts_inside(ray, &all, behind, t_max);
            events.extend(all[behind..].iter().map(|&(t, part)| (t, i as u32, part)));
        }
        events.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        for (t, leaf, part) in events {
            let i = leaf as usize;
            inside[i] = !inside[i];
            if let Some(flip) = self.kept(leaf, &inside)
                && visit(CsgHit {
                    t,
                    leaf,
                    part,
                    flip,
                })
            {
                return true;
            }
        }
        false
    }

    /// The nearest surface of the combination along `ray` in `(0, t_max)`.
    pub fn nearest(&self, ray: &Ray, t_max: f32) -> Option<CsgHit> {
        let mut found = None;
        self.walk(ray, t_max, |h| {
            found = Some(h);
            true
        });
        found
    }

    /// Every surface of the combination along `ray` in `(0, t_max)`, nearest first.
    pub fn surfaces(&self, ray: &Ray, t_max: f32) -> Vec<CsgHit> {
        let mut all = Vec::new();
        self.walk(ray, t_max, |h| {
            all.push(h);
            false
        });
        all
    }

    /// Walks the combination's surfaces along `ray` in `(0, t_max)`, nearest first, calling
    /// `blocker` with each one's leaf's material until it returns `true`; returns whether it
    /// did. A shadow ray sees the part it crosses (a clear sphere cutting a shape lets light
    /// in, as in POV-Ray).
    pub fn blocking(&self, ray: &Ray, t_max: f32, mut blocker: impl FnMut(u32) -> bool) -> bool {
        self.walk(ray, t_max, |h| blocker(self.leaves[h.leaf as usize].1))
    }

    /// Whether every leaf wears `material` (known from the build: asked per shadow ray).
    pub fn all_wear(&self, material: u32) -> bool {
        self.uniform == Some(material)
    }

    /// How many of the combination's surfaces `ray` crosses in `(0, t_max)`.
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        let mut n = 0;
        self.walk(ray, t_max, |_| {
            n += 1;
            false
        });
        n
    }

    /// The surface at `hit` along `ray`, its normal facing out of the combination.
    pub fn surface(&self, ray: &Ray, hit: &CsgHit) -> SolidPoint {
        let mut s = self.leaves[hit.leaf as usize]
            .0
            .surface(ray, hit.t, hit.part);
        if hit.flip {
            s.normal = -s.normal;
        }
        s
    }

    /// Whether `p` lies inside.
    pub fn contains(&self, p: Vec3) -> bool {
        let inside: Vec<bool> = self.leaves.iter().map(|l| l.0.contains(p)).collect();
        self.holds(0, &inside)
    }
}
