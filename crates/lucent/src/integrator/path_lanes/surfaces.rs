//! The materials lanes shade, and what they are at a hit.

use crate::Rgb;
use crate::bsdf::Distribution;
use crate::bsdf::fresnel::sane_eta;
use crate::bsdf::plastic::Plastic;
use crate::bsdf::rough_dielectric::INDEX_MATCHED;
use crate::material::{Roughness, Surface};
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::texture::Texture;

/// Which of a scene's materials the lanes shade, and how.
#[derive(Clone, Debug, Default)]
pub struct LaneMaterials<'a> {
    /// Per material: how lanes shade it, if they do.
    lanes: Vec<Option<LaneMaterial<'a>>>,
}

/// A material as lanes shade it.
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneMaterial<'a> {
    surface: LaneSurface<'a>,
    /// Whether the hit's vertex colour multiplies a Lambertian albedo.
    vertex_colors: bool,
    pub(super) two_sided: bool,
}

/// The surfaces lanes know, with their textures.
#[derive(Clone, Copy, Debug)]
enum LaneSurface<'a> {
    /// Lambertian (Mitsuba's `diffuse`).
    Lambert { reflectance: &'a Texture },
    /// A smooth conductor (Mitsuba's `conductor`).
    Mirror {
        eta: &'a Texture,
        k: &'a Texture,
        specular: &'a Texture,
    },
    /// A rough conductor with GGX facets (Mitsuba's `roughconductor`).
    RoughMirror {
        eta: &'a Texture,
        k: &'a Texture,
        specular: &'a Texture,
        roughness: &'a Roughness,
    },
    /// Smooth glass (Mitsuba's `dielectric`).
    Glass {
        eta: f32,
        specular: &'a Texture,
        transmittance: &'a Texture,
    },
    /// A diffuse base under a smooth coat (Mitsuba's `plastic`).
    Plastic {
        diffuse: &'a Texture,
        eta: f32,
        specular: &'a Texture,
        nonlinear: bool,
    },
    /// Rough glass with GGX facets (Mitsuba's `roughdielectric`), its index made sane and not
    /// index-matched.
    RoughGlass {
        eta: f32,
        specular: &'a Texture,
        transmittance: &'a Texture,
        roughness: &'a Roughness,
    },
}

/// What a lane's surface is at its hit, textures evaluated.
#[derive(Clone, Copy, Debug)]
pub(super) enum LaneBsdf {
    /// Lambert's albedo.
    Lambert(Rgb),
    /// A smooth conductor's index and tint.
    Mirror { eta: Rgb, k: Rgb, specular: Rgb },
    /// A rough conductor's index, tint and GGX roughness (tangent, bitangent; clamped).
    RoughMirror {
        eta: Rgb,
        k: Rgb,
        specular: Rgb,
        alpha: (f32, f32),
    },
    /// Smooth glass's index and tints.
    Glass {
        eta: f32,
        specular: Rgb,
        transmittance: Rgb,
    },
    /// A plastic's base (its value before the coat's transmittances and `cos/π`), its coat's
    /// tint, index (sane) and specular sampling weight; `delta` when only the coat is left (a
    /// black base: no light sample).
    Plastic {
        base: Rgb,
        specular: Rgb,
        eta: f32,
        w: f32,
        delta: bool,
    },
    /// Rough glass's index, tints and GGX roughness (tangent, bitangent; clamped).
    RoughGlass {
        eta: f32,
        specular: Rgb,
        transmittance: Rgb,
        alpha: (f32, f32),
    },
}

impl LaneBsdf {
    /// A rough surface's GGX roughness (tangent, bitangent).
    pub(super) fn alpha(&self) -> Option<(f32, f32)> {
        match *self {
            LaneBsdf::RoughMirror { alpha, .. } | LaneBsdf::RoughGlass { alpha, .. } => Some(alpha),
            _ => None,
        }
    }

    /// Rough glass's or a plastic coat's index (made sane).
    pub(super) fn eta(&self) -> Option<f32> {
        match *self {
            LaneBsdf::RoughGlass { eta, .. } | LaneBsdf::Plastic { eta, .. } => Some(eta),
            _ => None,
        }
    }

    /// A plastic's specular sampling weight.
    pub(super) fn sampling_weight(&self) -> Option<f32> {
        match *self {
            LaneBsdf::Plastic { w, .. } => Some(w),
            _ => None,
        }
    }

    /// Whether it transmits (glass): a two-sided reflector's normals turn round when it is
    /// seen from the back, glass's do not; and glass picks its lobe with a number.
    pub(super) fn transmits(&self) -> bool {
        matches!(self, LaneBsdf::Glass { .. } | LaneBsdf::RoughGlass { .. })
    }
}

impl<'a> LaneMaterials<'a> {
    /// The materials of `scene` that lanes shade: Lambertian surfaces (Mitsuba's `diffuse`),
    /// smooth conductors (`conductor`), rough conductors with GGX facets (`roughconductor`),
    /// smooth glass (`dielectric`), rough glass with GGX facets (`roughdielectric`, not
    /// index-matched) and smooth plastic (`plastic`), their parameters colours or textures. Any
    /// other material is shaded per path.
    pub fn of(scene: &'a Scene) -> Self {
        let lanes = scene
            .materials
            .iter()
            .map(|m| {
                let surface = match &m.surface {
                    Surface::Diffuse { reflectance } => LaneSurface::Lambert { reflectance },
                    Surface::Conductor {
                        eta,
                        k,
                        specular,
                        roughness: None,
                    } => LaneSurface::Mirror { eta, k, specular },
                    Surface::Conductor {
                        eta,
                        k,
                        specular,
                        roughness: Some(roughness),
                    } if roughness.distribution == Distribution::Ggx => LaneSurface::RoughMirror {
                        eta,
                        k,
                        specular,
                        roughness,
                    },
                    Surface::Dielectric {
                        eta,
                        specular,
                        transmittance,
                        roughness: None,
                    } => LaneSurface::Glass {
                        eta: *eta,
                        specular,
                        transmittance,
                    },
                    Surface::Dielectric {
                        eta,
                        specular,
                        transmittance,
                        roughness: Some(roughness),
                    } if roughness.distribution == Distribution::Ggx
                        && (sane_eta(*eta) - 1.0).abs() >= INDEX_MATCHED =>
                    {
                        LaneSurface::RoughGlass {
                            eta: sane_eta(*eta),
                            specular,
                            transmittance,
                            roughness,
                        }
                    }
                    Surface::Plastic {
                        diffuse,
                        eta,
                        specular,
                        nonlinear,
                        coat: None,
                    } => LaneSurface::Plastic {
                        diffuse,
                        eta: *eta,
                        specular,
                        nonlinear: *nonlinear,
                    },
                    _ => return None,
                };
                Some(LaneMaterial {
                    surface,
                    vertex_colors: m.vertex_colors,
                    two_sided: m.two_sided,
                })
            })
            .collect();
        Self { lanes }
    }

    /// How lanes shade material `index`, if they do.
    #[inline]
    pub(super) fn get(&self, index: u32) -> Option<LaneMaterial<'a>> {
        self.lanes.get(index as usize).copied().flatten()
    }

    /// Whether lanes shade any material of the scene.
    pub fn any(&self) -> bool {
        self.lanes.iter().any(Option::is_some)
    }
}

/// What material `m` is at `hit`, its textures evaluated as `Resolve` evaluates them (at the
/// hit's coordinates, over `footprint`); a Lambertian albedo times the vertex colour (the
/// hit's, white on shapes without) where the material says.
#[inline(always)]
pub(super) fn bsdf_at(
    scene: &Scene,
    m: LaneMaterial,
    hit: &SurfaceHit,
    footprint: f32,
) -> LaneBsdf {
    let material = &scene.materials[hit.material as usize];
    // The hit's vertex colour where the material multiplies its base by it.
    let vertex_color = || {
        if m.vertex_colors {
            hit.color
        } else {
            Rgb::WHITE
        }
    };
    let eval = |t: &Texture| match t {
        Texture::Solid(c) => *c,
        t => t.eval(&scene.tex_coords(material, hit, footprint), &scene.images),
    };
    match m.surface {
        LaneSurface::Lambert { reflectance } => {
            LaneBsdf::Lambert(eval(reflectance) * vertex_color())
        }
        LaneSurface::Mirror { eta, k, specular } => LaneBsdf::Mirror {
            eta: eval(eta),
            k: eval(k),
            specular: eval(specular),
        },
        LaneSurface::RoughMirror {
            eta,
            k,
            specular,
            roughness,
        } => {
            let at = scene.tex_coords(material, hit, footprint);
            LaneBsdf::RoughMirror {
                eta: eval(eta),
                k: eval(k),
                specular: eval(specular),
                alpha: roughness.at(&at, &scene.images).alphas(),
            }
        }
        LaneSurface::Plastic {
            diffuse,
            eta,
            specular,
            nonlinear,
        } => {
            let specular = eval(specular);
            let plastic = Plastic::new(eval(diffuse) * vertex_color(), eta, specular, nonlinear);
            let (eta, w) = plastic.eta_and_weight();
            LaneBsdf::Plastic {
                base: plastic.base(),
                specular,
                eta,
                w,
                delta: plastic.is_delta(),
            }
        }
        LaneSurface::RoughGlass {
            eta,
            specular,
            transmittance,
            roughness,
        } => {
            let at = scene.tex_coords(material, hit, footprint);
            LaneBsdf::RoughGlass {
                eta,
                specular: eval(specular),
                transmittance: eval(transmittance),
                alpha: roughness.at(&at, &scene.images).alphas(),
            }
        }
        LaneSurface::Glass {
            eta,
            specular,
            transmittance,
        } => LaneBsdf::Glass {
            eta,
            specular: eval(specular),
            transmittance: eval(transmittance),
        },
    }
}
