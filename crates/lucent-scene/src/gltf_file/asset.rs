//! A glTF file opened: its document parsed and checked, and its buffers read (external ones
//! through `resolve`, no further than they declare).

use super::primitive::{self, Decoded};
use super::{SUPPORTED_EXTENSIONS, accessor, draco, local_matrix, material, skin, source, weights};
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::paths::{LoadOptions, resolve};
use glam::Mat4;
use std::path::{Path, PathBuf};

/// A glTF document with its buffers loaded.
pub(super) struct Asset {
    pub(super) path: PathBuf,
    pub(super) base_dir: PathBuf,
    pub(super) doc: gltf::Document,
    /// The data of each buffer, exactly its declared `byteLength` long.
    pub(super) buffers: Vec<Vec<u8>>,
    /// The texture coordinate set each material's primitives keep (`material::uv_set`).
    pub(super) uv_sets: Vec<u32>,
    /// Every node's world matrix, where skins find their joints.
    pub(super) worlds: Vec<Mat4>,
}

impl Asset {
    /// Reads the file and its buffers (external ones through `resolve`, so `--sandbox` holds).
    pub(super) fn open(
        path: &Path,
        options: &LoadOptions,
        inputs: &mut Fingerprint,
    ) -> Result<Self, LoadError> {
        let bytes = crate::input::read(path)
            .map_err(|e| LoadError::file(path, format!("cannot read the glTF file: {e}")))?;
        inputs.add(&bytes);
        let glb = bytes.starts_with(b"glTF");
        let (json, bin) = if glb {
            let g = source::split_glb(&bytes).map_err(|e| LoadError::file(path, e))?;
            (g.json, g.bin)
        } else {
            (&bytes[..], None)
        };
        let doc = parse_document(json, path, !glb)?;
        let base_dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
        let mut buffers = Vec::with_capacity(doc.buffers().len());
        for buffer in doc.buffers() {
            let i = buffer.index();
            let err = |m: String| LoadError::file(path, format!("buffer {i}: {m}"));
            let (mut data, from) = match buffer.source() {
                gltf::buffer::Source::Bin => match bin {
                    Some(bin) if i == 0 => (bin.to_vec(), "the BIN chunk".to_string()),
                    _ => {
                        return Err(err(
                            "it has no URI, and is not the first buffer of a GLB file with a BIN chunk".into(),
                        ));
                    }
                },
                gltf::buffer::Source::Uri(uri) => match uri.strip_prefix("data:") {
                    Some(rest) => (
                        source::decode_data_uri(rest).map_err(err)?,
                        "its data: URI".to_string(),
                    ),
                    None => {
                        let name = source::file_name_of_uri(uri).map_err(err)?;
                        let file = resolve(&base_dir, &name, options).map_err(err)?;
                        let data = read_buffer_file(&file, buffer.length()).map_err(err)?;
                        inputs.add(&data);
                        (data, format!("`{}`", file.display()))
                    }
                },
            };
            let declared = buffer.length();
            if data.len() < declared {
                return Err(err(format!(
                    "it declares {declared} bytes, but {from} holds {}",
                    data.len()
                )));
            }
            data.truncate(declared);
            buffers.push(data);
        }
        let root = doc.as_json();
        let uv_sets = (0..root.materials.len())
            .map(|i| material::uv_set(root, Some(i)))
            .collect();
        let worlds = skin::node_worlds(&doc, |n| local_matrix(n.transform()));
        Ok(Self {
            path: path.to_path_buf(),
            base_dir,
            doc,
            buffers,
            uv_sets,
            worlds,
        })
    }

    pub(super) fn error(&self, message: impl Into<String>) -> LoadError {
        LoadError::file(&self.path, message)
    }

    /// Primitive `prim` of `mesh` (numbered `label` in messages) as [`primitive::decode`]
    /// reads it, posed by `skin` when given.
    pub(super) fn primitive(
        &self,
        mesh: &gltf::Mesh,
        label: usize,
        prim: &gltf::Primitive,
        skin: Option<&gltf::Skin>,
    ) -> Result<Decoded, String> {
        let decoded = match prim.extension_value("KHR_draco_mesh_compression") {
            Some(ext) => self.draco(label, prim, ext)?,
            None => {
                primitive::decode(&self.buffers, label, prim, self.uv_set(prim), weights(mesh))?
            }
        };
        match (decoded, skin) {
            (Decoded::Triangles(mut m, notes), Some(s)) => {
                skin::pose(&self.buffers, prim, s, &self.worlds, &mut m)
                    .map_err(|e| format!("mesh {label} primitive {}: {e}", prim.index()))?;
                Ok(Decoded::Triangles(m, notes))
            }
            (decoded, _) => Ok(decoded),
        }
    }

    /// Primitive `prim` of mesh `label`, compressed by `KHR_draco_mesh_compression` (its
    /// JSON `ext`): the Draco stream in the buffer view the extension names.
    pub(super) fn draco(
        &self,
        label: usize,
        prim: &gltf::Primitive,
        ext: &serde_json::Value,
    ) -> Result<Decoded, String> {
        let what = format!("mesh {label} primitive {}", prim.index());
        let view = ext
            .get("bufferView")
            .and_then(serde_json::Value::as_u64)
            .and_then(|v| self.doc.views().nth(v as usize))
            .ok_or_else(|| {
                format!("{what}: its KHR_draco_mesh_compression names no buffer view of the file")
            })?;
        let bytes =
            accessor::view_bytes(&self.buffers, &view).map_err(|e| format!("{what}: {e}"))?;
        let attributes = ext.get("attributes").unwrap_or(&serde_json::Value::Null);
        let mesh = draco::decode(bytes, attributes, self.uv_set(prim))
            .map_err(|e| format!("{what}: {e}"))?;
        let mut notes = Vec::new();
        if prim.morph_targets().len() > 0 {
            notes.push(format!(
                "{what}: its morph targets are not applied (Draco-compressed targets are not read)"
            ));
        }
        Ok(Decoded::Triangles(mesh, notes))
    }

    /// The texture coordinate set `prim` keeps: its material's (0 without one).
    pub(super) fn uv_set(&self, prim: &gltf::Primitive) -> u32 {
        prim.material()
            .index()
            .and_then(|i| self.uv_sets.get(i).copied())
            .unwrap_or(0)
    }

    /// See [`GltfFile::embedded_image`]. The JSON is read directly: the crate's
    /// `Image::source` panics on an image with neither a URI nor a buffer view with a MIME
    /// type, which validation lets through.
    pub(super) fn embedded_image(&self, index: usize) -> Result<Vec<u8>, String> {
        let root = self.doc.as_json();
        let image = root.images.get(index).ok_or_else(|| {
            format!(
                "there is no such image (the file has {})",
                root.images.len()
            )
        })?;
        if let Some(uri) = &image.uri {
            return match uri.strip_prefix("data:") {
                Some(rest) => source::decode_data_uri(rest),
                None => Err(format!(
                    "it is the file `{uri}`, not an image inside the glTF file"
                )),
            };
        }
        let view = image
            .buffer_view
            .and_then(|v| self.doc.views().nth(v.value()))
            .ok_or("it has neither a URI nor a buffer view")?;
        accessor::view_bytes(&self.buffers, &view).map(<[u8]>::to_vec)
    }

    /// The nodes of the scene (see the module's documentation) in depth-first order, with their
    /// world matrices, and notes on nodes reached twice (a file whose nodes are not a tree;
    /// such a node is placed the first time only, which also stops cycles).
    pub(super) fn placed_nodes(&self) -> (Vec<(usize, Mat4)>, Vec<String>) {
        let nodes: Vec<gltf::Node> = self.doc.nodes().collect();
        let roots: Vec<usize> = match self
            .doc
            .default_scene()
            .or_else(|| self.doc.scenes().next())
        {
            Some(scene) => scene.nodes().map(|n| n.index()).collect(),
            None => {
                let mut is_child = vec![false; nodes.len()];
                for c in nodes.iter().flat_map(|n| n.children()) {
                    is_child[c.index()] = true;
                }
                (0..nodes.len()).filter(|&i| !is_child[i]).collect()
            }
        };
        let mut seen = vec![false; nodes.len()];
        let mut placed = Vec::new();
        let mut notes = Vec::new();
        // An explicit stack: a hierarchy thousands of nodes deep must not overflow the call stack.
        let mut stack: Vec<(usize, Mat4)> =
            roots.iter().rev().map(|&i| (i, Mat4::IDENTITY)).collect();
        while let Some((i, parent)) = stack.pop() {
            if std::mem::replace(&mut seen[i], true) {
                notes.push(format!(
                    "node {i} is reached twice (the nodes do not form a tree); placed once"
                ));
                continue;
            }
            let world = parent * local_matrix(nodes[i].transform());
            let children: Vec<usize> = nodes[i].children().map(|c| c.index()).collect();
            stack.extend(children.into_iter().rev().map(|c| (c, world)));
            placed.push((i, world));
        }
        (placed, notes)
    }
}

/// The first `declared` bytes of the buffer file `file` (fewer if it is shorter). Only regular
/// files are read, and no more than declared, so a URI naming a device or a huge file cannot
/// exhaust memory.
fn read_buffer_file(file: &Path, declared: usize) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let cannot = |e: std::io::Error| format!("cannot read `{}`: {e}", file.display());
    let (f, _) = crate::input::open(file).map_err(cannot)?;
    let mut data = Vec::new();
    f.take(declared as u64)
        .read_to_end(&mut data)
        .map_err(cannot)?;
    Ok(data)
}

/// The glTF document in `json`: parsed, its required extensions checked, validated. `text`:
/// whether `json` is the whole file (a `.gltf`), so that JSON errors can carry a line.
pub(super) fn parse_document(
    json: &[u8],
    path: &Path,
    text: bool,
) -> Result<gltf::Document, LoadError> {
    let mut root: gltf::json::Root = gltf::json::deserialize::from_slice(json).map_err(|e| {
        // serde_json's message ends with " at line L column C"; the position goes in its field.
        let shown = e.to_string();
        let message = match shown.rfind(" at line ") {
            Some(at) if e.line() > 0 => &shown[..at],
            _ => &shown,
        };
        LoadError {
            file: path.to_path_buf(),
            position: (text && e.line() > 0).then(|| (e.line(), e.column())),
            message: format!("not valid glTF JSON: {message}"),
        }
    })?;
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(LoadError::file(
            path,
            format!("the file requires extension {ext}, which is not supported"),
        ));
    }
    // Extensions lucent reads but the crate does not know (KHR_mesh_quantization, most
    // material extensions) would fail its validation when required: they are checked above.
    root.extensions_required
        .retain(|e| gltf::json::extensions::ENABLED_EXTENSIONS.contains(&e.as_str()));
    forgive_positions(&mut root).map_err(|e| LoadError::file(path, e))?;
    // The specification lets an accessor have neither a buffer view nor sparse values (its
    // elements are zeros; a Draco primitive's accessors are such), which the crate's
    // validation refuses: a copy with a placeholder view is validated, and the document kept
    // as written.
    let viewless = |a: &gltf::json::Accessor| a.buffer_view.is_none() && a.sparse.is_none();
    if !root.buffer_views.is_empty() && root.accessors.iter().any(viewless) {
        let mut check = root.clone();
        for a in check.accessors.iter_mut().filter(|a| viewless(a)) {
            a.buffer_view = Some(gltf::json::Index::new(0));
        }
        gltf::Document::from_json(check).map_err(|e| invalid(path, e))?;
        return Ok(gltf::Document::from_json_without_validation(root));
    }
    gltf::Document::from_json(root).map_err(|e| invalid(path, e))
}

/// The error of a glTF document the crate's validation refuses: its first three problems.
fn invalid(path: &Path, e: gltf::Error) -> LoadError {
    let message = match e {
        gltf::Error::Validation(errors) => {
            let shown: Vec<String> = errors
                .iter()
                .take(3)
                .map(|(at, what)| format!("{at}: {what}"))
                .collect();
            let more = errors.len().saturating_sub(3);
            let more = if more > 0 {
                format!(" (and {more} more)")
            } else {
                String::new()
            };
            format!("the glTF document is invalid: {}{more}", shown.join("; "))
        }
        other => format!("the glTF document is invalid: {other}"),
    };
    LoadError::file(path, message)
}

/// Prepares `root` for the glTF crate's validation: refuses a POSITION attribute naming an
/// accessor that does not exist (the validation would index out of bounds and panic), and
/// gives POSITION accessors without a valid `min` or `max` a placeholder (the specification
/// requires them, and the validation refuses files without them, but nothing here uses them).
fn forgive_positions(root: &mut gltf::json::Root) -> Result<(), String> {
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    let accessors = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let Some(index) = prim.attributes.get(&Checked::Valid(Semantic::Positions)) else {
                continue;
            };
            let Some(a) = root.accessors.get_mut(index.value()) else {
                return Err(format!(
                    "mesh {m} primitive {p}: POSITION names accessor {}, but the file has {accessors}",
                    index.value()
                ));
            };
            for bound in [&mut a.min, &mut a.max] {
                let valid = bound.as_ref().is_some_and(|v| {
                    gltf::json::deserialize::from_value::<[f32; 3]>(v.clone()).is_ok()
                });
                if !valid {
                    *bound = Some(gltf::json::Value::from(vec![0.0; 3]));
                }
            }
        }
    }
    Ok(())
}
