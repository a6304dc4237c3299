//! The POV-Ray scene as a lucent description: POV-Ray's left-handed space mirrored into
//! lucent's right-handed one (z negated), its camera vectors turned into an eye, a look-at
//! point and a field of view, its lights and objects into lucent's, and each distinct texture
//! into a `whitted` material whose coefficients are POV-Ray's lighting terms
//! (`docs/povray.md` lists each term and how it is mapped).

use super::lexer::Loc;
use super::normal::Normal;
use super::scene::{Camera, CsgKind, Light, LightKind as PovLight, Object, PovScene, Shape};
use super::texture::{Finish, Pattern, Pigment, Texture};
use super::value::Vect;
use crate::desc::{
    BumpDesc, CameraDesc, Color, FalloffName, Finite, ImageDesc, LightDesc, LightKind,
    MaterialDesc, Matrix, ObjectDesc, ObjectKind, Point, RenderDesc, SceneDesc, TextureDesc,
    Vector, WorldDesc,
};
use crate::error::LoadError;
use glam::{DAffine3, DMat4, DVec3, Vec3};
use lucent::Rgb;
use lucent::shape::solid::algebraic;
use lucent::texture::bump::Bump;
use lucent::texture::{Checker, PatternKind, Turbulence, Wave};
use std::collections::HashMap;
use std::rc::Rc;
use toml::Spanned;

/// Most point lights one `area_light` becomes (POV-Ray's grid of lights, unjittered).
const MAX_AREA_LIGHTS: u32 = 64;

/// The mirror between POV-Ray's space and lucent's.
const FLIP: DVec3 = DVec3::new(1.0, 1.0, -1.0);

fn point(p: DVec3) -> DVec3 {
    p * FLIP
}

fn affine(m: &DAffine3) -> DAffine3 {
    let s = DAffine3::from_scale(FLIP);
    s * *m * s
}

fn span<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

fn rgb(v: DVec3) -> Rgb {
    Rgb::new(v.x as f32, v.y as f32, v.z as f32)
}

/// The conversion's state: the materials made so far, by their settings.
struct Convert<'a> {
    materials: Vec<Spanned<MaterialDesc>>,
    by_key: HashMap<String, String>,
    warnings: &'a mut Vec<String>,
    default_finish: Finish,
    default_pigment: Option<Rc<Pigment>>,
    ambient_light: DVec3,
}

/// The description of `scene` at `size` pixels.
pub fn convert(
    scene: &PovScene,
    version: Option<f64>,
    defaults: &super::scene::Defaults,
    size: (u32, u32),
    warnings: &mut Vec<String>,
    file: &Loc,
) -> Result<SceneDesc, LoadError> {
    let ambient_light = scene.ambient_light.unwrap_or(DVec3::ONE);
    let mut cx = Convert {
        materials: Vec::new(),
        by_key: HashMap::new(),
        warnings,
        default_finish: defaults.finish.clone(),
        default_pigment: defaults.pigment.clone(),
        ambient_light,
    };
    let camera = match &scene.camera {
        Some(c) => camera(c, size, cx.warnings)?,
        None => camera(&Camera::default_at(file), size, cx.warnings)?,
    };
    let mut objects = Vec::new();
    let mut lights: Vec<Spanned<LightDesc>> = Vec::new();
    for l in &scene.lights {
        lights.extend(light(l, &mut cx).into_iter().map(span));
    }
    for o in &scene.objects {
        cx.collect_lights(o, &DAffine3::IDENTITY, &mut lights);
        if let Some(d) = cx.object(o, None, &DAffine3::IDENTITY, true)? {
            objects.extend(d.into_iter().map(span));
        }
    }
    let background = scene
        .background
        .map(|c| rgb(c.v3()))
        .or_else(|| {
            scene.sky.as_ref().map(|p| {
                cx.warn(
                    &p.loc,
                    "a sky_sphere is shown as the background's one colour (its pigment's average)",
                );
                rgb(p.average().v3())
            })
        })
        .unwrap_or(Rgb::BLACK);
    let render = RenderDesc {
        max_depth: span(scene.max_trace_level.unwrap_or(5)),
        min_weight: span(Finite(scene.adc_bailout.unwrap_or(1.0 / 255.0) as f32)),
        ..RenderDesc::default()
    };
    Ok(SceneDesc {
        image: ImageDesc {
            width: span(size.0),
            height: span(size.1),
            samples: span(1),
            gamma: display_gamma(scene, version).map(|g| span(Finite(g as f32))),
            raw: display_gamma(scene, version).is_none().then_some(true),
        },
        camera: span(camera),
        world: WorldDesc {
            background: Color(background),
            ambient: Color(rgb(ambient_light)),
        },
        render,
        materials: cx.materials,
        lights,
        objects,
        media: Vec::new(),
    })
}

/// The gamma of the scene's colour space, as POV-Ray 3.7 decides it: `assumed_gamma` where
/// given; 1 for a scene of `#version 3.7` or later; `None` (no gamma correction: values
/// written as they are) for older scenes and scenes without `#version`.
fn display_gamma(scene: &PovScene, version: Option<f64>) -> Option<f64> {
    match (scene.assumed_gamma, version) {
        (Some(g), _) => Some(g),
        (None, Some(v)) if v >= 3.7 - 1e-9 => Some(1.0),
        _ => None,
    }
}

/// lucent's camera for POV-Ray's: `angle` sets the direction's length from the right
/// vector's; `look_at` turns direction, right and up about `location` with `sky` up, keeping
/// their lengths; the vertical field of view is `2·atan(|up| / 2|direction|)`.
fn camera(
    c: &Camera,
    size: (u32, u32),
    warnings: &mut Vec<String>,
) -> Result<CameraDesc, LoadError> {
    let (mut d, mut r, mut u) = (c.direction, c.right, c.up);
    if d.length() == 0.0 || r.length() == 0.0 || u.length() == 0.0 {
        return Err(c
            .loc
            .error("the camera's direction, right and up must not be zero"));
    }
    if let Some(a) = c.angle {
        if !(0.0..180.0).contains(&a) || a == 0.0 {
            return Err(c.loc.error(format!(
                "the camera's angle must be in (0, 180) degrees, not {a}"
            )));
        }
        d = d.normalize() * (0.5 * r.length() / (a.to_radians() / 2.0).tan());
    }
    if let Some(at) = c.look_at {
        let dir = at - c.location;
        if dir.length() == 0.0 {
            return Err(c.loc.error("the camera looks at its own location"));
        }
        let dn = dir.normalize();
        // Left-handed: right = sky × direction.
        let mut right = c.sky.cross(dn);
        if right.length() < 1e-12 {
            // POV-Ray keeps the right vector it has, and warns.
            warnings.push(c.loc.warning(
                "the camera looks along its sky vector: its right vector is kept, as POV-Ray does",
            ));
            right = c.right;
        }
        let handed = if c.up.cross(c.direction).dot(c.right) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let rn = right.normalize() * handed;
        let un = dn.cross(rn).normalize() * handed;
        d = dn * d.length();
        r = rn * r.length();
        u = un * u.length();
    }
    // An orthographic view given an angle, or no size, spans at the look-at point what the
    // perspective view would.
    if c.orthographic && (c.angle.is_some() || !c.sized) {
        let at = c.look_at.unwrap_or(c.location + c.direction);
        let k = (at - c.location).length() / d.length();
        if k > 0.0 {
            r *= k;
            u *= k;
        }
    }
    let m = c.transform;
    let eye = m.transform_point3(c.location);
    let (d, r, u) = (
        m.transform_vector3(d),
        m.transform_vector3(r),
        m.transform_vector3(u),
    );
    let aspect = r.length() / u.length();
    let image_aspect = f64::from(size.0) / f64::from(size.1);
    if (aspect / image_aspect - 1.0).abs() > 0.01 {
        warnings.push(c.loc.warning(format!(
            "the camera's right/up ratio {aspect:.3} differs from the image's {image_aspect:.3}: POV-Ray stretches the image, lucent keeps square pixels (set `right x*image_width/image_height`)"
        )));
    }
    if r.cross(u).dot(d) > 0.0 {
        // POV-Ray's usual handedness is right = up × direction reversed; the other one mirrors
        // the image.
    }
    let fov = 2.0 * (u.length() / 2.0 / d.length()).atan();
    Ok(CameraDesc {
        eye: Point(point(eye)),
        look_at: Point(point(eye + d)),
        up: Vector(point(u).normalize().as_vec3()),
        fov: Finite(fov.to_degrees() as f32),
        aperture: None,
        focus_distance: None,
        orthographic: c.orthographic.then(|| Finite(u.length() as f32)),
        motion: None,
        shutter: None,
        medium: None,
    })
}

/// lucent's lights for one POV-Ray light (an area light is its grid of point lights).
fn light(l: &Light, cx: &mut Convert) -> Vec<LightDesc> {
    if l.shadowless {
        cx.warn(&l.loc, "a shadowless light casts shadows in lucent");
    }
    if l.fade.is_some_and(|(d, p)| d > 0.0 && p > 0.0) {
        cx.warn(
            &l.loc,
            "a light's fade_distance and fade_power are not read by lucent (no falloff)",
        );
    }
    let color = Color(rgb(l.color));
    let mut out = Vec::new();
    match l.kind {
        PovLight::Parallel => {
            let mut d = LightDesc::new(LightKind::Directional);
            let dir = point(l.point_at - l.position);
            d.direction = Some(span(Vector(dir.normalize_or(DVec3::NEG_Y).as_vec3())));
            d.intensity = Some(color);
            out.push(d);
            return out;
        }
        PovLight::Spot => {
            if l.spot.2 != 0.0 {
                cx.warn(&l.loc, "a spotlight's tightness is not read by lucent");
            }
        }
        PovLight::Point => {}
    }
    let (n, m) = l.area.map_or((1, 1), |a| (a.2, a.3));
    let (n, m) = if n * m > MAX_AREA_LIGHTS {
        cx.warn(
            &l.loc,
            format!(
                "an area light of {n}×{m} is sampled by {MAX_AREA_LIGHTS} point lights at most"
            ),
        );
        let k = (f64::from(MAX_AREA_LIGHTS) / f64::from(n * m)).sqrt();
        (
            ((f64::from(n) * k) as u32).max(1),
            ((f64::from(m) * k) as u32).max(1),
        )
    } else {
        (n, m)
    };
    let share = 1.0 / f64::from(n * m);
    for i in 0..n {
        for j in 0..m {
            let mut p = l.position;
            if let Some((a, b, _, _)) = l.area {
                let s = if n > 1 {
                    f64::from(i) / f64::from(n - 1) - 0.5
                } else {
                    0.0
                };
                let t = if m > 1 {
                    f64::from(j) / f64::from(m - 1) - 0.5
                } else {
                    0.0
                };
                p += a * s + b * t;
            }
            let mut d = if l.kind == PovLight::Spot {
                let mut d = LightDesc::new(LightKind::Spot);
                let dir = point(l.point_at - l.position);
                d.direction = Some(span(Vector(dir.normalize_or(DVec3::NEG_Y).as_vec3())));
                let cutoff = l.spot.1.clamp(0.01, 90.0);
                d.cutoff = Some(span(Finite(cutoff as f32)));
                d.cutoff_start = Some(span(Finite(l.spot.0.clamp(0.0, cutoff) as f32)));
                d
            } else {
                LightDesc::new(LightKind::Point)
            };
            d.position = Some(span(Point(point(p))));
            d.intensity = Some(Color(rgb(l.color * share)));
            d.falloff = Some(span(FalloffName::None));
            out.push(d);
        }
    }
    let _ = color;
    out
}

impl Convert<'_> {
    fn warn(&mut self, loc: &Loc, message: impl std::fmt::Display) {
        let line = loc.warning(message);
        if !self.warnings.contains(&line) {
            self.warnings.push(line);
        }
    }

    /// Lights inside combinations, placed.
    fn collect_lights(&mut self, o: &Object, outer: &DAffine3, out: &mut Vec<Spanned<LightDesc>>) {
        let m = *outer * o.transform;
        match &o.shape {
            Shape::Light(l) => {
                let mut l = (**l).clone();
                l.position = m.transform_point3(l.position);
                l.point_at = m.transform_point3(l.point_at);
                out.extend(light(&l, self).into_iter().map(span));
            }
            Shape::Csg(_, children) => {
                for c in children {
                    self.collect_lights(c, &m, out);
                }
            }
            _ => {}
        }
    }

    /// The material's name for a texture and interior, made once per distinct set.
    fn material(&mut self, o: &Object, inherited: Option<&Rc<Texture>>) -> String {
        let tex = o.texture.as_ref().or(inherited);
        let pigment = tex
            .and_then(|t| t.pigment.clone())
            .or_else(|| self.default_pigment.clone());
        let finish = match tex {
            Some(t) => self.default_finish.overlaid(&t.finish),
            None => self.default_finish.clone(),
        };
        for (what, loc) in &finish.unread {
            self.warn(loc, format!("{what} is not read by lucent"));
        }
        if let Some(loc) = tex.and_then(|t| t.layered.as_ref()) {
            let loc = loc.clone();
            self.warn(&loc, "layered textures: lucent draws the first layer only");
        }
        let bump = tex
            .and_then(|t| t.normal.clone())
            .and_then(|n| self.bump(&n));
        let interior = o.interior.as_ref();
        let ior = interior.and_then(|i| i.ior).unwrap_or(1.0);
        if let Some(i) = interior {
            for (what, loc) in &i.unread {
                let (what, loc) = (what.clone(), loc.clone());
                self.warn(&loc, format!("{what} is not read by lucent"));
            }
        }
        let mut m = self.whitted(pigment.as_deref(), &finish, ior, &o.loc);
        m.bump = bump;
        let key = format!(
            "{:?}",
            (
                &m.ka,
                &m.ka_map,
                &m.kd,
                &m.ks,
                &m.shininess,
                &m.highlight,
                &m.brilliance,
                &m.kr,
                &m.kt,
                &m.ior,
                &m.bump
            )
        );
        if let Some(name) = self.by_key.get(&key) {
            return name.clone();
        }
        let name = format!("pov{}", self.materials.len() + 1);
        m.name = span(name.clone());
        self.materials.push(span(m));
        self.by_key.insert(key, name.clone());
        name
    }

    /// POV-Ray's lighting terms as Whitted's coefficients.
    fn whitted(
        &mut self,
        pigment: Option<&Pigment>,
        f: &Finish,
        ior: f64,
        at: &Loc,
    ) -> MaterialDesc {
        let black = Pigment::solid(Vect::splat(0.0, 5), at.clone());
        let pigment = pigment.unwrap_or(&black);
        let avg = pigment.average();
        // Not clamped: POV-Ray lets `transmit 100` make a surface's own light negative (a
        // contrast trick of its sample scenes).
        let opacity = |c: &Vect| 1.0 - c.c[3] - c.c[4];
        let diffuse = f.diffuse.unwrap_or(0.6);
        let ambient = f.ambient.unwrap_or(DVec3::splat(0.1));
        let metallic = f.metallic.unwrap_or(0.0);
        let lit = |c: &Vect| rgb(c.v3() * diffuse * opacity(c));
        let kd = match self.texture_of(pigment, &lit) {
            Some(t) => t,
            None => TextureDesc::Solid(lit(&avg)),
        };
        let mut m = MaterialDesc::named("");
        // Ambient light reflects as the pigment's colour: `ka` is the finish's ambient, and
        // `ka_map` the pattern's colours (their opacity applied).
        let seen = |c: &Vect| rgb(c.v3() * opacity(c));
        m.ka_map = self.texture_of_quiet(pigment, &seen);
        m.ka = Some(Color(match m.ka_map {
            Some(_) => rgb(ambient),
            None => rgb(ambient * avg.v3() * opacity(&avg)),
        }));
        if let Some(e) = f.emission.filter(|e| *e != DVec3::ZERO) {
            // `emission` adds like ambient light of 1: folded into `ka` over `Ia`.
            let ia = self.ambient_light.max(DVec3::splat(1e-6));
            let ka = m.ka.map_or(DVec3::ZERO, |c| {
                DVec3::new(c.0.r.into(), c.0.g.into(), c.0.b.into())
            });
            let extra = if m.ka_map.is_some() {
                e / ia
            } else {
                e * avg.v3() * opacity(&avg) / ia
            };
            m.ka = Some(Color(rgb(ka + extra)));
        }
        m.kd = Some(kd);
        if let Some(b) = f.brilliance.filter(|b| (b - 1.0).abs() > 1e-9) {
            m.brilliance = Some(span(Finite(b.clamp(1e-3, 1000.0) as f32)));
        }
        let tint = |k: f64| {
            let c = avg.v3();
            DVec3::splat(k) * (DVec3::ONE - metallic) + c * k * metallic
        };
        let phong = f.phong.unwrap_or(0.0);
        let specular = f.specular.unwrap_or(0.0);
        if phong > 0.0 {
            m.ks = Some(Color(rgb(tint(phong))));
            m.shininess = Some(span(Finite(f.phong_size.unwrap_or(40.0) as f32)));
            if specular > 0.0 {
                self.warn(
                    at,
                    "`specular` beside `phong`: lucent draws the phong highlight only",
                );
            }
        } else if specular > 0.0 {
            // Blinn's highlight (N·H)^(1/roughness).
            let roughness = f.roughness.unwrap_or(0.05).max(1e-4);
            m.ks = Some(Color(rgb(tint(specular))));
            m.shininess = Some(span(Finite((1.0 / roughness) as f32)));
            m.highlight = Some(span("blinn".to_string()));
        }
        if let Some(r) = f.reflection {
            let c = avg.v3();
            let kr = r * (DVec3::ONE - metallic) + r * c * metallic;
            if kr != DVec3::ZERO {
                m.kr = Some(Color(rgb(kr)));
            }
        }
        let kt = avg.v3() * avg.c[3] + DVec3::splat(avg.c[4]);
        if kt != DVec3::ZERO {
            m.kt = Some(Color(rgb(kt)));
        }
        if f.conserve_energy == Some(true) {
            self.warn(at, "`conserve_energy` is not read by lucent");
        }
        m.ior = Some(span(Finite(ior as f32)));
        m
    }

    /// A lucent texture for a pigment's pattern, each colour passed through `lit`; `None` for
    /// one colour, or where the pattern is not read (its average stands in, with a warning).
    fn texture_of(&mut self, p: &Pigment, lit: &dyn Fn(&Vect) -> Rgb) -> Option<TextureDesc> {
        // lucent's world back to POV-Ray's (the mirror), then into the pattern's space.
        let to_pattern = p.transform.inverse() * DAffine3::from_scale(FLIP);
        let to_pattern = glam::Affine3A::from_mat4(DMat4::from(to_pattern).as_mat4());
        let solid = |q: &Pigment| match q.pattern {
            Pattern::Solid(c) => Some(c),
            _ => None,
        };
        let (kind, map, default_wave) = match &p.pattern {
            Pattern::Solid(_) => return None,
            Pattern::Checker(pair) => {
                let (Some(a), Some(b)) = (solid(&pair[0]), solid(&pair[1])) else {
                    self.warn(
                        &p.loc,
                        "a checker of patterns is shown by its average colour",
                    );
                    return None;
                };
                return Some(TextureDesc::Checker(Checker {
                    even: lit(&a),
                    odd: lit(&b),
                    size: 1.0,
                    world: Some(to_pattern),
                }));
            }
            Pattern::Hexagon(three) => {
                let cs: Vec<Option<Vect>> = three.iter().map(solid).collect();
                if cs.iter().any(Option::is_none) {
                    self.warn(
                        &p.loc,
                        "a hexagon of patterns is shown by its average colour",
                    );
                    return None;
                }
                let map = cs
                    .iter()
                    .flatten()
                    .enumerate()
                    .map(|(i, c)| (i as f32, lit(c)))
                    .collect();
                (PatternKind::Hexagon, map, Wave::Ramp)
            }
            Pattern::Mapped(name, axis, map) => {
                let (kind, wave) = match &**name {
                    "gradient" => (PatternKind::Gradient(axis.as_vec3()), Wave::Ramp),
                    "marble" => (PatternKind::Marble, Wave::Triangle),
                    "wood" => (PatternKind::Wood, Wave::Triangle),
                    "onion" => (PatternKind::Onion, Wave::Ramp),
                    "leopard" => (PatternKind::Leopard, Wave::Ramp),
                    "radial" => (PatternKind::Radial, Wave::Ramp),
                    "spherical" => (PatternKind::Spherical, Wave::Ramp),
                    "cylindrical" => (PatternKind::Cylindrical, Wave::Ramp),
                    "planar" => (PatternKind::Planar, Wave::Ramp),
                    "boxed" => (PatternKind::Boxed, Wave::Ramp),
                    "bozo" | "spotted" | "bumps" | "dents" => (PatternKind::Noise, Wave::Ramp),
                    "granite" => (PatternKind::Granite, Wave::Ramp),
                    "agate" => (PatternKind::Agate, Wave::Ramp),
                    "ripples" | "waves" => (PatternKind::Ripples, Wave::Ramp),
                    "wrinkles" => (PatternKind::Wrinkles, Wave::Ramp),
                    other => {
                        self.warn(
                            &p.loc,
                            format!(
                                "the `{other}` pattern is shown by its colour map's average colour"
                            ),
                        );
                        return None;
                    }
                };
                if matches!(
                    kind,
                    PatternKind::Noise
                        | PatternKind::Granite
                        | PatternKind::Agate
                        | PatternKind::Wrinkles
                ) || p.shaping.turbulence.is_some()
                {
                    self.warn(&p.loc, format!("the `{name}` pattern's noise is lucent's own: its grain differs from POV-Ray's"));
                }
                let map: Vec<(f32, Rgb)> = map.iter().map(|(v, c)| (*v as f32, lit(c))).collect();
                (kind, map, wave)
            }
        };
        let sh = &p.shaping;
        let wave = match sh.wave.as_ref().map(|(w, e)| (&**w, *e)) {
            None => default_wave,
            Some(("ramp_wave", _)) => Wave::Ramp,
            Some(("triangle_wave", _)) => Wave::Triangle,
            Some(("sine_wave", _)) => Wave::Sine,
            Some(("scallop_wave", _)) => Wave::Scallop,
            Some(("cubic_wave", _)) => Wave::Cubic,
            Some((_, e)) => Wave::Poly(e as f32),
        };
        let turbulence = sh.turbulence.map(|amount| Turbulence {
            amount: amount.as_vec3(),
            octaves: sh.octaves.unwrap_or(6.0).clamp(1.0, 10.0) as u32,
            omega: sh.omega.unwrap_or(0.5) as f32,
            lambda: sh.lambda.unwrap_or(2.0) as f32,
        });
        Some(TextureDesc::Pattern(Box::new(lucent::texture::Pattern {
            kind,
            to_pattern,
            wave,
            frequency: sh.frequency.unwrap_or(1.0) as f32,
            phase: sh.phase.unwrap_or(0.0) as f32,
            turbulence,
            map,
        })))
    }

    /// An `algebraic` object of `c` cut to `o`'s bounds; at the top level, where it has none
    /// (or is open along an axis), to ±[`UNBOUNDED`] about its origin, with a warning.
    fn cut_algebraic(&mut self, c: &algebraic::Coefficients, o: &Object, top: bool) -> ObjectDesc {
        let far = [DVec3::splat(-UNBOUNDED), DVec3::splat(UNBOUNDED)];
        let bounds = match o.bounds {
            Some([lo, hi]) if top => {
                if !(lo.is_finite() && hi.is_finite()) {
                    self.warn(&o.loc, format!("an algebraic shape unbounded along an axis is cut there to ±{UNBOUNDED} about its origin"));
                }
                Some([lo.max(far[0]), hi.min(far[1])])
            }
            None if top => {
                self.warn(
                    &o.loc,
                    format!("an unbounded algebraic shape is cut to the box ±{UNBOUNDED} about its origin (give it a `bounded_by` or `clipped_by`)"),
                );
                Some(far)
            }
            b => b,
        };
        algebraic_desc(c, bounds)
    }

    /// A normal's bump pattern; `None` (with a warning) where lucent cannot follow it.
    fn bump(&mut self, n: &Normal) -> Option<BumpDesc> {
        for (what, loc) in &n.unread {
            self.warn(
                loc,
                format!("{what} is not read by lucent: the surface is smooth there"),
            );
        }
        let Pattern::Mapped(name, _, _) = &n.pattern.pattern else {
            return None;
        };
        if matches!(
            &**name,
            "crackle" | "quilted" | "cells" | "spiral1" | "spiral2" | "mandel"
        ) {
            self.warn(
                &n.pattern.loc,
                format!("the normal pattern `{name}` is not read by lucent: the surface is smooth"),
            );
            return None;
        }
        let Some(TextureDesc::Pattern(mut p)) = self.texture_of(&n.pattern, &|_| Rgb::BLACK) else {
            return None;
        };
        let mut amount = n.amount as f32;
        match &**name {
            // POV-Ray's own normal patterns bend by their vector noise or waves times the
            // amount. Dents are deep where the noise is high: its cube.
            // POV-Ray's vector noise is about half as steep as lucent's noise's slope.
            "bumps" => amount *= 0.5,
            "dents" => {
                if n.pattern.shaping.wave.is_none() {
                    p.wave = Wave::Poly(3.0);
                }
                amount *= 0.5;
            }
            // POV-Ray's wrinkles sum its octaves' vector noise, a smooth bending: lucent's
            // sum of folded octaves is sharp-edged, so the noise's own slope stands in.
            "wrinkles" => {
                p.kind = PatternKind::Noise;
                amount *= 0.5;
            }
            // Ripples and waves bend by at most their amount; a sine of frequency f rises by
            // up to π·f per unit.
            "ripples" | "waves" => amount /= std::f32::consts::PI * p.frequency.abs().max(1e-3),
            // Any other pattern: POV-Ray sums its values at four points `accuracy` away
            // (0.02) along a tetrahedron's corners, `Σ v(p + δ·dᵢ)·dᵢ ≈ (4/3)·δ·∇v`.
            _ => amount *= 4.0 / 3.0 * lucent::texture::bump::ACCURACY,
        }
        Some(BumpDesc(Box::new(Bump {
            pattern: *p,
            amount,
        })))
    }

    /// [`Convert::texture_of`] without its warnings (given once, for the diffuse colour).
    fn texture_of_quiet(&mut self, p: &Pigment, lit: &dyn Fn(&Vect) -> Rgb) -> Option<TextureDesc> {
        let n = self.warnings.len();
        let t = self.texture_of(p, lit);
        self.warnings.truncate(n);
        t
    }

    /// A mesh's triangles (degenerate ones left out, as POV-Ray does), placed by `m`: one
    /// `triangles` object per texture they wear.
    fn mesh(
        &mut self,
        o: &Object,
        mesh: &super::scene::Mesh,
        inherited: Option<&Rc<Texture>>,
        m: &DAffine3,
    ) -> Vec<ObjectDesc> {
        let normal_map = m.matrix3.inverse().transpose();
        let own = self.material(o, inherited);
        let mut groups: Vec<(String, ObjectDesc)> = Vec::new();
        for (k, tri) in mesh.points.chunks_exact(3).enumerate() {
            let v = [tri[0], tri[1], tri[2]].map(|p| point(m.transform_point3(p)));
            let area = (v[1] - v[0]).cross(v[2] - v[0]).length();
            if area <= 1e-12 * (v[1] - v[0]).length_squared().max(f64::MIN_POSITIVE) {
                continue;
            }
            let name = match mesh.textures.as_ref().and_then(|ts| ts.get(k)) {
                Some(Some(t)) => {
                    let mut worn = o.clone();
                    worn.texture = Some(t.clone());
                    self.material(&worn, None)
                }
                _ => own.clone(),
            };
            let at = match groups.iter().position(|(n, _)| *n == name) {
                Some(i) => i,
                None => {
                    let mut d = ObjectDesc::new(ObjectKind::Triangles, &name);
                    d.positions = Some(span(Vec::new()));
                    d.indices = Some(span(Vec::new()));
                    if mesh.normals.is_some() {
                        d.normals = Some(span(Vec::new()));
                    }
                    groups.push((name, d));
                    groups.len() - 1
                }
            };
            let d = &mut groups[at].1;
            let positions = d.positions.as_mut().expect("made above").get_mut();
            let first = positions.len() as u32;
            positions.extend(v.map(Point));
            let indices = d.indices.as_mut().expect("made above").get_mut();
            indices.push([first, first + 1, first + 2]);
            if let (Some(ns), Some(out)) = (&mesh.normals, d.normals.as_mut()) {
                let out = out.get_mut();
                for n in &ns[3 * k..3 * k + 3] {
                    out.push(Vector(point(normal_map * *n).as_vec3()));
                }
            }
        }
        groups.into_iter().map(|(_, d)| d).collect()
    }

    /// The description of an object (several for a mesh: one per triangle), `None` when
    /// nothing of it is drawn.
    fn object(
        &mut self,
        o: &Object,
        inherited: Option<&Rc<Texture>>,
        outer: &DAffine3,
        top: bool,
    ) -> Result<Option<Vec<ObjectDesc>>, LoadError> {
        let m = *outer * o.transform;
        let tex = o.texture.as_ref().or(inherited);
        let material = || String::new();
        let mut d = match &o.shape {
            Shape::Light(_) => return Ok(None),
            Shape::Unread(name) => {
                if &**name != "material" {
                    self.warn(
                        &o.loc,
                        format!("the shape `{name}` is not read by lucent and is left out"),
                    );
                }
                return Ok(None);
            }
            Shape::Sphere(c, r) => {
                let mut d = ObjectDesc::new(ObjectKind::Ellipsoid, &material());
                d.center = Some(span(Point(*c)));
                d.radii = Some(span(Vector(Vec3::splat(*r as f32))));
                d
            }
            Shape::Plane(n, dist) if top && o.bounds.is_none() => {
                let mut d = ObjectDesc::new(ObjectKind::Plane, &material());
                let nn = n.normalize();
                let p = m.transform_point3(nn * *dist);
                let normal = m.matrix3.inverse().transpose() * nn;
                d.point = Some(span(Point(point(p))));
                d.normal = Some(span(Vector(point(normal).normalize().as_vec3())));
                d.material = span(self.material(o, inherited));
                return Ok(Some(vec![d]));
            }
            Shape::Plane(n, dist) => {
                // In a combination, or clipped: the half-space behind it, `n̂·x − dist < 0`.
                self.cut_algebraic(&algebraic::half_space(n.normalize(), *dist), o, top)
            }
            Shape::Algebraic(c) => self.cut_algebraic(c, o, top),
            Shape::Box(a, b) => {
                let mut d = ObjectDesc::new(ObjectKind::Box, &material());
                // A flat box (POV-Ray draws it as its face) gets a sliver of thickness.
                let (lo, mut hi) = (a.min(*b), a.max(*b));
                let sliver = 1e-6 * (hi - lo).max_element().max(1e-3);
                hi = DVec3::select(hi.cmpgt(lo), hi, lo + sliver);
                d.min = Some(span(Point(lo)));
                d.max = Some(span(Point(hi)));
                d
            }
            Shape::Cylinder(a, b, r, open) => {
                let mut d = ObjectDesc::new(ObjectKind::Cylinder, &material());
                d.base = Some(span(Point(*a)));
                d.cap = Some(span(Point(*b)));
                d.radius = Some(span(Finite(*r as f32)));
                d.open = Some(*open);
                d
            }
            Shape::Cone(a, ra, b, rb, open) => {
                let mut d = ObjectDesc::new(ObjectKind::Cone, &material());
                d.base = Some(span(Point(*a)));
                d.cap = Some(span(Point(*b)));
                d.base_radius = Some(span(Finite(*ra as f32)));
                d.cap_radius = Some(span(Finite(*rb as f32)));
                d.open = Some(*open);
                d
            }
            Shape::Torus(major, minor) => {
                let mut d = ObjectDesc::new(ObjectKind::Torus, &material());
                d.major = Some(span(Finite(*major as f32)));
                d.minor = Some(span(Finite(*minor as f32)));
                d
            }
            Shape::Disc(c, n, r, hole) => {
                let mut d = ObjectDesc::new(ObjectKind::Disc, &material());
                d.center = Some(span(Point(*c)));
                d.normal = Some(span(Vector(n.as_vec3())));
                d.radius = Some(span(Finite(*r as f32)));
                d.hole = Some(span(Finite(*hole as f32)));
                d
            }
            Shape::Superellipsoid(e, n) => {
                let mut d = ObjectDesc::new(ObjectKind::Superellipsoid, &material());
                d.exponents = Some(span([Finite(*e as f32), Finite(*n as f32)]));
                d
            }
            Shape::Mesh(mesh) => {
                if !top {
                    self.warn(
                        &o.loc,
                        "triangles inside a combination are not read by lucent and are left out",
                    );
                    return Ok(None);
                }
                return Ok(Some(self.mesh(o, mesh, inherited, &m)));
            }
            Shape::Csg(kind, children) => {
                let mut d = ObjectDesc::new(
                    match kind {
                        CsgKind::Union => ObjectKind::Union,
                        CsgKind::Intersection => ObjectKind::Intersection,
                        CsgKind::Difference => ObjectKind::Difference,
                        CsgKind::Merge => ObjectKind::Merge,
                    },
                    &material(),
                );
                if *kind == CsgKind::Union && top {
                    // A union's parts are drawn as separate objects: every kind of shape may
                    // be one, and a union keeps all surfaces anyway.
                    let mut out = Vec::new();
                    for c in children {
                        let c = &with_interior(c, o);
                        if let Some(mut parts) = self.object(c, tex, &m, true)? {
                            if o.inverse {
                                self.warn(&o.loc, "an inverted union is drawn as its parts");
                            }
                            out.append(&mut parts);
                        }
                    }
                    return Ok(Some(out));
                }
                let mut kids = Vec::new();
                for c in children {
                    let c = &with_interior(c, o);
                    if let Some(parts) = self.object(c, tex, &DAffine3::IDENTITY, false)? {
                        kids.extend(parts.into_iter().map(span));
                    }
                }
                if kids.is_empty() {
                    return Ok(None);
                }
                // One part left (the others not read, with warnings): that part.
                if kids.len() == 1 {
                    let mut only = kids.pop().map(Spanned::into_inner).expect("one child");
                    // One part: itself, placed by the combination.
                    let inner = only
                        .transform
                        .map(|t| t.into_inner().0)
                        .unwrap_or(DMat4::IDENTITY);
                    let outer = if top {
                        affine(&m)
                    } else {
                        affine(&o.transform)
                    };
                    only.transform = Some(span(Matrix(DMat4::from(outer) * inner)));
                    if top {
                        fill_material(&mut only, &self.material(o, inherited));
                    }
                    return Ok(Some(vec![only]));
                }
                d.children = Some(span(kids));
                d
            }
        };
        let placement = if top { m } else { o.transform };
        d.transform = Some(span(Matrix(DMat4::from(affine(&placement)))));
        if o.inverse {
            d.inverse = Some(true);
        }
        // Points given in POV-Ray's space: mirrored by the transform's flip (the placement
        // conjugated by the mirror takes them from POV-Ray's object space to lucent's world,
        // so shape data is given in mirrored object space).
        mirror_shape(&mut d);
        if top || o.texture.is_some() {
            d.material = span(self.material(o, inherited));
        }
        if o.no_shadow {
            self.warn(
                &o.loc,
                "`no_shadow` is not read by lucent: the object casts shadows",
            );
        }
        if top && d.children.is_some() && !bounded(&d) {
            // A union or merge with a plane in it, say: infinite, as POV-Ray draws it; lucent's
            // combinations must be bounded, so it is cut far away.
            self.warn(
                &o.loc,
                format!("an unbounded combination is cut to the box ±{UNBOUNDED} about the origin"),
            );
            let mut far = ObjectDesc::new(ObjectKind::Box, "");
            far.min = Some(span(Point(DVec3::splat(-UNBOUNDED))));
            far.max = Some(span(Point(DVec3::splat(UNBOUNDED))));
            let mut cut = ObjectDesc::new(ObjectKind::Intersection, d.material.get_ref());
            cut.children = Some(span(vec![span(d), span(far)]));
            d = cut;
        }
        Ok(Some(vec![d]))
    }
}

/// Whether a description's shape lies in a finite box, by the rules lucent's combinations
/// follow: a union or merge when all its parts do, an intersection when any does, a
/// difference when its first does; an inverted part, a plane or an uncut algebraic surface
/// never.
fn bounded(d: &ObjectDesc) -> bool {
    if d.inverse == Some(true) {
        return false;
    }
    let kids = || {
        d.children
            .iter()
            .flat_map(|c| c.get_ref().iter().map(Spanned::get_ref))
    };
    match d.kind {
        ObjectKind::Plane => false,
        ObjectKind::Algebraic => d.bounds.as_ref().is_some_and(|b| {
            let [lo, hi] = b.get_ref();
            lo.0.is_finite() && hi.0.is_finite()
        }),
        ObjectKind::Union | ObjectKind::Merge => kids().all(bounded),
        ObjectKind::Intersection => kids().any(bounded),
        ObjectKind::Difference => kids().next().is_some_and(bounded),
        _ => true,
    }
}

/// `child` wearing its combination's interior when it has none of its own.
fn with_interior(child: &Object, parent: &Object) -> Object {
    let mut c = child.clone();
    if c.interior.is_none() {
        c.interior = parent.interior.clone();
    }
    c
}

/// Gives `d` and its children without a material the name `m`.
fn fill_material(d: &mut ObjectDesc, m: &str) {
    if d.material.get_ref().is_empty() {
        d.material = span(m.to_string());
    }
}

/// The shape's own points and directions moved into the mirrored object space.
fn mirror_shape(d: &mut ObjectDesc) {
    for p in [&mut d.center, &mut d.base, &mut d.cap]
        .into_iter()
        .flatten()
    {
        *p = span(Point(point(p.get_ref().0)));
    }
    if let (Some(a), Some(b)) = (&d.min, &d.max) {
        let (a, b) = (point(a.get_ref().0), point(b.get_ref().0));
        d.min = Some(span(Point(a.min(b))));
        d.max = Some(span(Point(a.max(b))));
    }
    if let Some(terms) = &mut d.terms {
        let mirrored = terms
            .get_ref()
            .iter()
            .map(|&[k, i, j, l]| [if l % 2.0 == 1.0 { -k } else { k }, i, j, l])
            .collect();
        *terms = span(mirrored);
    }
    if let Some(b) = &d.bounds {
        let [lo, hi] = b.get_ref().map(|p| point(p.0));
        d.bounds = Some(span([Point(lo.min(hi)), Point(lo.max(hi))]));
    }
    if d.kind == ObjectKind::Disc
        && let Some(n) = &d.normal
    {
        d.normal = Some(span(Vector(point(n.get_ref().0.as_dvec3()).as_vec3())));
    }
}

/// How far from its origin an algebraic shape without bounds is drawn alone.
const UNBOUNDED: f64 = 1e4;

/// An `algebraic` object of `c` (in POV-Ray's object space), cut to `bounds`.
fn algebraic_desc(c: &algebraic::Coefficients, bounds: Option<[DVec3; 2]>) -> ObjectDesc {
    let mut d = ObjectDesc::new(ObjectKind::Algebraic, "");
    let terms = c
        .iter()
        .zip(algebraic::POWERS)
        .filter(|(k, _)| **k != 0.0)
        .map(|(k, [i, j, l])| [*k, f64::from(i), f64::from(j), f64::from(l)])
        .collect();
    d.terms = Some(span(terms));
    d.bounds = bounds.map(|b| span(b.map(Point)));
    d
}
