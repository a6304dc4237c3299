//! Each shape's own arguments, between its `{` and its modifiers.

use super::lexer::{Loc, Tok};
use super::parser::Parser;
use super::scene::{CsgKind, Mesh, Shape};
use super::texture::Texture;
use super::value::Value;
use crate::error::LoadError;
use glam::DVec3;
use std::rc::Rc;

/// Most triangles one mesh may hold.
const MAX_TRIANGLES: usize = 20_000_000;

impl Parser {
    /// The shape `w`'s arguments (its `{` read).
    pub fn shape(&mut self, w: &str, loc: &Loc) -> Result<Shape, LoadError> {
        Ok(match w {
            "sphere" => {
                let c = self.vec3()?;
                self.eat_symbol(",")?;
                let r = self.float()?;
                Shape::Sphere(c, r)
            }
            "plane" => {
                let n = self.vec3()?;
                self.eat_symbol(",")?;
                let d = self.float()?;
                if n == DVec3::ZERO {
                    return Err(loc.error("a plane's normal is the zero vector"));
                }
                Shape::Plane(n, d)
            }
            "box" => {
                let a = self.vec3()?;
                self.eat_symbol(",")?;
                let b = self.vec3()?;
                Shape::Box(a, b)
            }
            "cylinder" => {
                let a = self.vec3()?;
                self.eat_symbol(",")?;
                let b = self.vec3()?;
                self.eat_symbol(",")?;
                let r = self.float()?;
                let open = self.eat_word("open")?;
                Shape::Cylinder(a, b, r, open)
            }
            "cone" => {
                let a = self.vec3()?;
                self.eat_symbol(",")?;
                let ra = self.float()?;
                self.eat_symbol(",")?;
                let b = self.vec3()?;
                self.eat_symbol(",")?;
                let rb = self.float()?;
                let open = self.eat_word("open")?;
                Shape::Cone(a, ra, b, rb, open)
            }
            "torus" => {
                let major = self.float()?;
                self.eat_symbol(",")?;
                let minor = self.float()?;
                self.eat_word("sturm")?;
                Shape::Torus(major, minor)
            }
            "disc" => {
                let c = self.vec3()?;
                self.eat_symbol(",")?;
                let n = self.vec3()?;
                self.eat_symbol(",")?;
                let r = self.float()?;
                let hole = if self.eat_symbol(",")? {
                    self.float()?
                } else {
                    0.0
                };
                Shape::Disc(c, n, r, hole)
            }
            "superellipsoid" => {
                let e = self.vector(2)?;
                Shape::Superellipsoid(e.c[0], e.c[1])
            }
            "triangle" | "smooth_triangle" => {
                let smooth = w == "smooth_triangle";
                let mut points = Vec::new();
                let mut normals = Vec::new();
                for i in 0..3 {
                    if i > 0 {
                        self.eat_symbol(",")?;
                    }
                    points.push(self.vec3()?);
                    if smooth {
                        self.eat_symbol(",")?;
                        normals.push(self.vec3()?);
                    }
                }
                Shape::Mesh(Rc::new(Mesh {
                    points,
                    normals: smooth.then_some(normals),
                    textures: None,
                }))
            }
            "polygon" => self.polygon(loc)?,
            "quadric" | "cubic" | "quartic" | "poly" => self.algebraic(w, loc)?,
            "mesh" => self.mesh(loc)?,
            "mesh2" => self.mesh2(loc)?,
            "union" | "intersection" | "difference" | "merge" => {
                let kind = match w {
                    "union" => CsgKind::Union,
                    "intersection" => CsgKind::Intersection,
                    "difference" => CsgKind::Difference,
                    _ => CsgKind::Merge,
                };
                let mut children = Vec::new();
                while let Some(t) = self.peek()?.cloned() {
                    let is_child = matches!(&t.tok, Tok::Word(w)
                        if super::scene::is_shape_word(w));
                    if !is_child {
                        break;
                    }
                    children.push(self.object()?);
                }
                Shape::Csg(kind, children)
            }
            _ => {
                // A shape lucent does not read: its arguments skipped whole (a warning comes
                // where it is used, not where an include file declares it).
                let mut depth = 1;
                while depth > 1 || !self.peek()?.is_some_and(|t| t.is_symbol("}")) {
                    let t = self.expect_any("`}`")?;
                    if t.is_symbol("{") {
                        depth += 1;
                    } else if t.is_symbol("}") {
                        depth -= 1;
                    }
                }
                Shape::Unread(w.into())
            }
        })
    }

    /// `polygon { n, p1, … }`: its points as a fan of triangles (convex polygons exact; closed
    /// outlines with repeated first points as POV-Ray writes several loops are split).
    fn polygon(&mut self, loc: &Loc) -> Result<Shape, LoadError> {
        let n = self.float()?;
        if !(3.0..=1e6).contains(&n) {
            return Err(loc.error(format!("a polygon needs 3 to 10⁶ points, not {n}")));
        }
        let mut pts = Vec::new();
        for _ in 0..n as usize {
            self.eat_symbol(",")?;
            let v = self.vector(2)?;
            pts.push(if v.n == 2 {
                DVec3::new(v.c[0], v.c[1], 0.0)
            } else {
                v.v3()
            });
        }
        let mut mesh = Mesh::default();
        // Loops: each ends where it returns to its first point.
        let mut start = 0;
        let mut i = 1;
        let mut warned = false;
        while i < pts.len() {
            if pts[i] == pts[start] {
                let ring = &pts[start..i];
                if ring.len() >= 3 {
                    if !warned && start > 0 {
                        self.warn(
                            loc,
                            "a polygon of several loops is read as their fans (holes are not cut)",
                        );
                        warned = true;
                    }
                    fan(ring, &mut mesh.points);
                }
                start = i + 1;
                i = start + 1;
            } else {
                i += 1;
            }
        }
        if start == 0 {
            fan(&pts, &mut mesh.points);
        }
        Ok(Shape::Mesh(Rc::new(mesh)))
    }

    /// `mesh { triangle {…} smooth_triangle {…} … [inside_vector v] }`.
    fn mesh(&mut self, loc: &Loc) -> Result<Shape, LoadError> {
        let mut mesh = Mesh::default();
        let mut normals = Vec::new();
        let mut textures = Vec::new();
        let mut any_smooth = false;
        let mut any_texture = false;
        while let Some(t) = self.peek()?.cloned() {
            let smooth = t.is_word("smooth_triangle");
            if !(smooth || t.is_word("triangle")) {
                if t.is_word("inside_vector") {
                    self.next_token()?;
                    self.vec3()?;
                    continue;
                }
                break;
            }
            self.next_token()?;
            self.expect_symbol("{")?;
            for i in 0..3 {
                if i > 0 {
                    self.eat_symbol(",")?;
                }
                mesh.points.push(self.vec3()?);
                if smooth {
                    self.eat_symbol(",")?;
                    normals.push(self.vec3()?);
                } else {
                    normals.push(DVec3::ZERO);
                }
            }
            any_smooth |= smooth;
            let mut tex = None;
            while !self.eat_symbol("}")? {
                let t = self.expect_any("`}`")?;
                if t.is_word("texture") {
                    let name = self.expect_any("a texture")?;
                    tex = match &name.tok {
                        Tok::Word(n) => match self.lookup(n) {
                            Some(Value::Texture(t)) => Some(t.clone()),
                            _ => return Err(name.loc.error(format!("`{n}` is not a texture"))),
                        },
                        _ if name.is_symbol("{") => {
                            self.push_back(name.clone());
                            Some(Rc::new(self.texture_block()?))
                        }
                        _ => return Err(name.loc.error("expected a texture")),
                    };
                    any_texture = true;
                } else if t.is_word("uv_vectors") {
                    for _ in 0..3 {
                        self.eat_symbol(",")?;
                        self.vector(2)?;
                    }
                } else {
                    return Err(t
                        .loc
                        .error(format!("{} is not part of a mesh's triangle", t.tok)));
                }
            }
            textures.push(tex);
            if mesh.points.len() / 3 > MAX_TRIANGLES {
                return Err(loc.error(format!("a mesh of more than {MAX_TRIANGLES} triangles")));
            }
        }
        if any_smooth {
            mesh.normals = Some(normals);
        }
        if any_texture {
            mesh.textures = Some(textures);
        }
        Ok(Shape::Mesh(Rc::new(mesh)))
    }

    /// `mesh2 { vertex_vectors {n, …} normal_vectors {…} uv_vectors {…} texture_list {…}
    /// face_indices {…} normal_indices {…} uv_indices {…} }`.
    fn mesh2(&mut self, loc: &Loc) -> Result<Shape, LoadError> {
        let mut vertices = Vec::new();
        let mut normal_vectors = Vec::new();
        let mut texture_list: Vec<Rc<Texture>> = Vec::new();
        let mut faces: Vec<([usize; 3], Vec<usize>)> = Vec::new();
        let mut normal_indices: Vec<[usize; 3]> = Vec::new();
        while let Some(t) = self.peek()?.cloned() {
            let Tok::Word(w) = &t.tok else { break };
            let w = w.clone();
            match &*w {
                "vertex_vectors" | "normal_vectors" | "uv_vectors" => {
                    self.next_token()?;
                    self.expect_symbol("{")?;
                    let n = self.count(&t.loc)?;
                    let mut list = Vec::with_capacity(n);
                    for _ in 0..n {
                        self.eat_symbol(",")?;
                        list.push(self.vector(2)?);
                    }
                    self.eat_symbol(",")?;
                    self.expect_symbol("}")?;
                    match &*w {
                        "vertex_vectors" => vertices = list.iter().map(|v| v.v3()).collect(),
                        "normal_vectors" => normal_vectors = list.iter().map(|v| v.v3()).collect(),
                        _ => {}
                    }
                }
                "texture_list" => {
                    self.next_token()?;
                    self.expect_symbol("{")?;
                    let n = self.count(&t.loc)?;
                    for _ in 0..n {
                        self.eat_symbol(",")?;
                        if !self.eat_word("texture")? {
                            return Err(self.loc().error("expected `texture` in a texture_list"));
                        }
                        texture_list.push(Rc::new(self.texture_block()?));
                    }
                    self.expect_symbol("}")?;
                }
                "face_indices" | "normal_indices" | "uv_indices" => {
                    self.next_token()?;
                    self.expect_symbol("{")?;
                    let n = self.count(&t.loc)?;
                    for _ in 0..n {
                        self.eat_symbol(",")?;
                        let v = self.vec3()?;
                        let idx = [v.x as usize, v.y as usize, v.z as usize];
                        if v.min_element() < 0.0 {
                            return Err(self.loc().error("a negative index in a mesh2"));
                        }
                        let mut texs = Vec::new();
                        // A face's texture index (or three, one per corner).
                        if w.as_ref() == "face_indices" && !texture_list.is_empty() {
                            while self.peek_plain().is_some_and(|t| t.is_symbol(",")) {
                                // `, i` after the face: peek past the comma for a number.
                                self.next_token()?;
                                if self.peek()?.is_some_and(|t| {
                                    matches!(t.tok, Tok::Number(_))
                                        || matches!(&t.tok, Tok::Word(_))
                                }) {
                                    texs.push(self.float()? as usize);
                                } else {
                                    break;
                                }
                                if texs.len() == 3 {
                                    break;
                                }
                            }
                        }
                        match &*w {
                            "face_indices" => faces.push((idx, texs)),
                            "normal_indices" => normal_indices.push(idx),
                            _ => {}
                        }
                    }
                    self.eat_symbol(",")?;
                    self.expect_symbol("}")?;
                }
                "inside_vector" => {
                    self.next_token()?;
                    self.vec3()?;
                }
                _ => break,
            }
        }
        let mut mesh = Mesh::default();
        let corner = |i: usize, list: &[DVec3], what: &str| {
            list.get(i).copied().ok_or_else(|| {
                loc.error(format!(
                    "a mesh2 {what} index {i} is outside its {} vectors",
                    list.len()
                ))
            })
        };
        let smooth = !normal_vectors.is_empty();
        let mut normals = Vec::new();
        let mut textures = Vec::new();
        for (k, (f, texs)) in faces.iter().enumerate() {
            for &i in f {
                mesh.points.push(corner(i, &vertices, "vertex")?);
            }
            if smooth {
                let ni = normal_indices.get(k).copied().unwrap_or(*f);
                for i in ni {
                    normals.push(corner(i, &normal_vectors, "normal")?);
                }
            }
            if !texture_list.is_empty() {
                let tex = match texs.first() {
                    Some(&i) => Some(texture_list.get(i).cloned().ok_or_else(|| {
                        loc.error(format!(
                            "a mesh2 texture index {i} is outside its {} textures",
                            texture_list.len()
                        ))
                    })?),
                    None => None,
                };
                textures.push(tex);
            }
        }
        if faces.len() > MAX_TRIANGLES {
            return Err(loc.error(format!("a mesh of more than {MAX_TRIANGLES} triangles")));
        }
        if smooth {
            mesh.normals = Some(normals);
        }
        if !texture_list.is_empty() {
            mesh.textures = Some(textures);
        }
        Ok(Shape::Mesh(Rc::new(mesh)))
    }

    /// A list's count.
    fn count(&mut self, loc: &Loc) -> Result<usize, LoadError> {
        let n = self.float()?;
        if !(0.0..=6e7).contains(&n) {
            return Err(loc.error(format!("a list of {n} items")));
        }
        Ok(n as usize)
    }
}

/// The fan of triangles of a polygon's points.
fn fan(ring: &[DVec3], out: &mut Vec<DVec3>) {
    for i in 1..ring.len().saturating_sub(1) {
        out.extend([ring[0], ring[i], ring[i + 1]]);
    }
}
