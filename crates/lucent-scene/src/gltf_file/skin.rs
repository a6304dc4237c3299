//! Skinned meshes posed as the file places their joints (the rest pose a viewer shows before
//! any animation runs): each vertex moved by the blend, by `WEIGHTS_0`, of the matrices
//! `joint's world matrix · its inverse bind matrix` of the joints `JOINTS_0` names. The
//! result is in world space, so the node's own transform is not applied (glTF 2.0 §3.7.3).

use super::accessor::{read_floats, read_matrices};
use glam::{Mat3, Mat4, Vec3};
use gltf::mesh::Semantic;
use lucent::shape::Mesh;

/// The world matrix of every node of `doc`: its parent's times its own. A node with no parent
/// is a root; one found on a cycle of parents is taken as a root (the nodes then do not form
/// a tree, which the importer reports).
pub(super) fn node_worlds(doc: &gltf::Document, local: impl Fn(&gltf::Node) -> Mat4) -> Vec<Mat4> {
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let mut parent = vec![None; nodes.len()];
    for n in &nodes {
        for c in n.children() {
            parent[c.index()].get_or_insert(n.index());
        }
    }
    let mut worlds: Vec<Option<Mat4>> = vec![None; nodes.len()];
    for start in 0..nodes.len() {
        // Up to the nearest node whose world is known (or a root), then back down.
        let mut chain = vec![start];
        while let Some(p) = parent[*chain.last().expect("not empty")] {
            if worlds[p].is_some() || chain.contains(&p) || chain.len() > nodes.len() {
                break;
            }
            chain.push(p);
        }
        let top = *chain.last().expect("not empty");
        let mut world = parent[top]
            .and_then(|p| worlds[p])
            .unwrap_or(Mat4::IDENTITY);
        for &i in chain.iter().rev() {
            if worlds[i].is_none() {
                world *= local(&nodes[i]);
                worlds[i] = Some(world);
            } else {
                world = worlds[i].expect("known");
            }
        }
    }
    worlds
        .into_iter()
        .map(|w| w.unwrap_or(Mat4::IDENTITY))
        .collect()
}

/// `mesh` (primitive `prim`, read in its own space) posed by `skin`, whose joints are placed by
/// `worlds` (see [`node_worlds`]): positions, normals (by the inverse transpose) and
/// tangents.
pub(super) fn pose(
    buffers: &[Vec<u8>],
    prim: &gltf::Primitive,
    skin: &gltf::Skin,
    worlds: &[Mat4],
    mesh: &mut Mesh,
) -> Result<(), String> {
    let n = mesh.positions.len();
    let attribute = |semantic: Semantic, what: &str| -> Result<Vec<f32>, String> {
        let a = prim
            .get(&semantic)
            .ok_or_else(|| format!("it is skinned but has no {what}"))?;
        let (v, _) = read_floats(buffers, &a, &[4])?;
        if v.len() != 4 * n {
            return Err(format!(
                "its {what} has {} elements for {n} vertices",
                v.len() / 4
            ));
        }
        Ok(v)
    };
    let joints = attribute(Semantic::Joints(0), "JOINTS_0")?;
    let weights = attribute(Semantic::Weights(0), "WEIGHTS_0")?;
    let joint_nodes: Vec<usize> = skin.joints().map(|j| j.index()).collect();
    let inverse_binds = match skin.inverse_bind_matrices() {
        Some(a) => read_matrices(buffers, &a)?,
        None => vec![Mat4::IDENTITY; joint_nodes.len()],
    };
    if inverse_binds.len() < joint_nodes.len() {
        return Err(format!(
            "skin {} has {} joints but {} inverse bind matrices",
            skin.index(),
            joint_nodes.len(),
            inverse_binds.len()
        ));
    }
    let matrices: Vec<Mat4> = joint_nodes
        .iter()
        .zip(&inverse_binds)
        .map(|(&node, ibm)| worlds[node] * *ibm)
        .collect();
    let mut blended = Vec::with_capacity(n);
    for (v, (j, w)) in joints
        .chunks_exact(4)
        .zip(weights.chunks_exact(4))
        .enumerate()
    {
        let total: f32 = w.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return Err(format!(
                "vertex {v}'s joint weights do not add up to a positive number"
            ));
        }
        let mut m = Mat4::ZERO;
        for (&joint, &weight) in j.iter().zip(w) {
            if weight == 0.0 {
                continue;
            }
            let k = joint as usize;
            let joint_matrix = matrices.get(k).ok_or_else(|| {
                format!(
                    "vertex {v} names joint {k}; skin {} has {}",
                    skin.index(),
                    matrices.len()
                )
            })?;
            m += *joint_matrix * (weight / total);
        }
        blended.push(m);
    }
    for (p, m) in mesh.positions.iter_mut().zip(&blended) {
        *p = m.transform_point3(*p);
        if !p.is_finite() {
            return Err("a skinned position is not finite".into());
        }
    }
    let mut normals = Vec::with_capacity(mesh.normals.len());
    for (nrm, m) in mesh.normals.iter().zip(&blended) {
        let inverse_transpose = Mat3::from_mat4(*m).inverse().transpose();
        normals.push((inverse_transpose * *nrm).try_normalize().unwrap_or(*nrm));
    }
    mesh.normals = normals;
    for (t, m) in mesh.tangents.iter_mut().zip(&blended) {
        let turned = m.transform_vector3(t.truncate());
        *t = turned.try_normalize().unwrap_or(Vec3::X).extend(t.w);
    }
    Ok(())
}
