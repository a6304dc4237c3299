//! Packets: up to eight rays of one beam traced together through its cut of a triangle tree.
//!
//! Any-ray-active traversal (Wald et al. 2001, "Interactive rendering with coherent ray
//! tracing"): the packet visits a node when any of its active rays enters it, and each node
//! is fetched once for the packet. Each ray still meets a node's eight boxes with its own
//! slab test and a pack's eight triangles with its own watertight test — the single-ray
//! kernels, the same arithmetic — so its `t`, weights and triangle are the single ray's, bit
//! for bit: a ray tests every leaf it would enter alone (it enters the same boxes with a
//! `t_max` never below its own), maybe some more, and the nearest hit with the tie rule (the
//! lower index at equal `t`) does not depend on which others are tested or in which order.
//! What a packet saves is the walk: one stack, one fetch and one sort per node for all rays.

use super::lanes::LANES;
#[cfg(target_arch = "x86_64")]
use super::simd::Avx;
use super::simd::{Simd, Sse};
use super::traverse::{ClosestLeaf, RayPre, STACK_SIZE};
use super::triangles::{NearestInPacks, PackRay, PackedHit};
use super::{Cut, NodeW, VIRTUAL, WIDTH, WideTriangleBvh};
use crate::aabb::CULL_SLACK;
use crate::{Ray, TraversalStats};
use arrayvec::ArrayVec;

/// Most rays in a packet.
pub const PACKET: usize = LANES;

/// A subtree on the packet's stack: (child, count, the rays that entered it, the nearest entry
/// distance among them).
type Entry = (u32, u32, u32, f32);

impl WideTriangleBvh {
    /// [`WideTriangleBvh::closest_hit_in`] for up to [`PACKET`] rays of the beam `cut` was
    /// made for at once, ray `i` in `(0, t_max[i]]` (no triangle left out): the hits each ray
    /// finds alone, bit for bit. Extra rays beyond `PACKET` are not traced.
    pub fn closest_hits_in(
        &self,
        cut: &Cut,
        rays: &[Ray],
        t_max: &[f32],
        stats: &mut TraversalStats,
    ) -> [Option<PackedHit>; PACKET] {
        if cut.misses {
            return [None; PACKET];
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = Avx::detect() {
            // SAFETY: `packet_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.packet_avx2(avx, &cut.nodes, rays, t_max, stats) };
        }
        self.packet(Sse, &cut.nodes, rays, t_max, stats)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn packet_avx2(
        &self,
        s: Avx,
        entry: &[NodeW],
        rays: &[Ray],
        t_max: &[f32],
        stats: &mut TraversalStats,
    ) -> [Option<PackedHit>; PACKET] {
        self.packet(s, entry, rays, t_max, stats)
    }

    #[inline(always)]
    fn packet<S: Simd>(
        &self,
        s: S,
        entry: &[NodeW],
        rays: &[Ray],
        t_max: &[f32],
        stats: &mut TraversalStats,
    ) -> [Option<PackedHit>; PACKET] {
        let n = rays.len().min(PACKET).min(t_max.len());
        let mut leaves: ArrayVec<NearestInPacks<S>, PACKET> = rays[..n]
            .iter()
            .map(|r| NearestInPacks {
                s,
                packs: &self.packs,
                pre: PackRay::new(r),
                skip: None,
                best: None,
            })
            .collect();
        let mut tm = [0.0f32; PACKET];
        tm[..n].copy_from_slice(&t_max[..n]);
        let bvh = &self.bvh;
        // Rays that cannot be traced take no part: they miss.
        let traceable = rays[..n]
            .iter()
            .enumerate()
            .fold(0u32, |m, (i, r)| m | (u32::from(r.is_traceable()) << i));
        if let Some((first, count)) = bvh.root_leaf {
            for (i, leaf) in leaves.iter_mut().enumerate() {
                if traceable & (1 << i) != 0 && bvh.bounds.hit(&rays[i], tm[i]).is_some() {
                    leaf.visit(first, count, &mut tm[i], stats);
                }
            }
        } else if !bvh.nodes.is_empty() {
            let pre: ArrayVec<RayPre, PACKET> = rays[..n].iter().map(RayPre::new).collect();
            let mut stack: ArrayVec<Entry, STACK_SIZE> = ArrayVec::new();
            let (mut child, mut count) = (0u32, if entry.is_empty() { 0 } else { VIRTUAL });
            let mut active = ((1u32 << n) - 1) & traceable;
            let mut visited = 0u64;
            'walk: loop {
                if count == 0 || count == VIRTUAL {
                    // One visit per ray tested, as the single-ray walk counts them.
                    visited += u64::from(active.count_ones());
                    let node = if count == 0 {
                        &bvh.nodes[child as usize]
                    } else {
                        &entry[child as usize]
                    };
                    let mut rays_of = [0u32; WIDTH];
                    let mut key = [f32::INFINITY; WIDTH];
                    let mut m = active;
                    while m != 0 {
                        let i = m.trailing_zeros() as usize;
                        m &= m - 1;
                        let (mut mask, near) = pre[i].enter(s, node, tm[i]);
                        if mask == 0 {
                            continue;
                        }
                        let near = s.store(near);
                        while mask != 0 {
                            let c = mask.trailing_zeros() as usize;
                            mask &= mask - 1;
                            rays_of[c] |= 1 << i;
                            key[c] = key[c].min(near.0[c]);
                        }
                    }
                    let mut next: ArrayVec<Entry, WIDTH> = (0..WIDTH)
                        .filter(|&c| rays_of[c] != 0)
                        .map(|c| (node.child[c], node.count[c], rays_of[c], key[c]))
                        .collect();
                    if !next.is_empty() {
                        // Nearest first; the rest on the stack, farthest deepest.
                        for i in 1..next.len() {
                            let mut j = i;
                            while j > 0 && next[j - 1].3 > next[j].3 {
                                next.swap(j - 1, j);
                                j -= 1;
                            }
                        }
                        stack.extend(next[1..].iter().rev().copied());
                        (child, count, active) = (next[0].0, next[0].1, next[0].2);
                        continue;
                    }
                } else {
                    let mut m = active;
                    while m != 0 {
                        let i = m.trailing_zeros() as usize;
                        m &= m - 1;
                        leaves[i].visit(child, count, &mut tm[i], stats);
                    }
                }
                // The next subtree some ray of it may still find a nearer hit (or a tie) in.
                loop {
                    let Some((c, k, rays, near)) = stack.pop() else {
                        break 'walk;
                    };
                    let mut m = rays;
                    let mut wanted = 0;
                    while m != 0 {
                        let i = m.trailing_zeros() as usize;
                        m &= m - 1;
                        if near <= tm[i] * CULL_SLACK {
                            wanted |= 1 << i;
                        }
                    }
                    if wanted != 0 {
                        (child, count, active) = (c, k, wanted);
                        break;
                    }
                }
            }
            stats.nodes_visited += visited;
        }
        let mut out = [None; PACKET];
        for (o, leaf) in out.iter_mut().zip(leaves) {
            *o = leaf.best;
        }
        out
    }
}
