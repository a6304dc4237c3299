//! Settings given beside a scene file (the command line's flags, a Python call's keywords)
//! that replace the file's own before the build.
//!
//! One place decides what an override replaces and which combinations make no sense, so the
//! `lucent` command and the Python package render the same image from the same settings. Errors
//! name the settings the way the caller spells them ([`Spelling`]).

use crate::SceneFile;
use crate::build::{MAX_AA_BLOCK, MAX_DEPTH, MAX_IMAGE_SIDE, MAX_SAMPLES};
use crate::desc::IntegratorName;
use crate::desc::settings::{FilterName, FilterSamplingName, SamplingName, TriangleTestName};
use crate::desc::values::Finite;
use lucent::accel::AccelKind;
use lucent::schedule::adaptive::MAX_DEPTH as ADAPTIVE_MAX_DEPTH;
use toml::Spanned;

/// How errors spell a setting: `--aa-threshold` on the command line, `aa_threshold` in Python.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spelling {
    /// Command-line flags.
    Flags,
    /// Keyword arguments.
    Keywords,
}

impl Spelling {
    /// `setting` (in snake case) as this spelling writes it.
    pub fn name(self, setting: &str) -> String {
        match self {
            Spelling::Flags => format!("--{}", setting.replace('_', "-")),
            Spelling::Keywords => setting.to_string(),
        }
    }

    /// `setting` turned off: `--no-shadows`, `shadows=False`.
    fn off(self, setting: &str) -> String {
        match self {
            Spelling::Flags => format!("--no-{}", setting.replace('_', "-")),
            Spelling::Keywords => format!("{setting}=False"),
        }
    }

    /// `setting` given the value `value`.
    fn given(self, setting: &str, value: &str) -> String {
        match self {
            Spelling::Flags => format!("{} {value}", self.name(setting)),
            Spelling::Keywords => format!("{setting}=\"{value}\""),
        }
    }
}

/// Settings that replace a scene file's; `None` (or `false`) keeps the file's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Image width in pixels.
    pub width: Option<u32>,
    /// Image height in pixels.
    pub height: Option<u32>,
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// The integrator.
    pub integrator: Option<IntegratorName>,
    /// Maximum path or recursion depth.
    pub max_depth: Option<u32>,
    /// Seed of the samplers.
    pub seed: Option<u64>,
    /// The acceleration structure.
    pub accel: Option<AccelKind>,
    /// The ray–triangle test.
    pub triangle_test: Option<TriangleTestName>,
    /// Whitted without shadow rays.
    pub no_shadows: bool,
    /// Uniform, adaptive or quadtree anti-aliasing.
    pub aa: Option<SamplingName>,
    /// Adaptive sampling's colour threshold.
    pub aa_threshold: Option<f32>,
    /// Adaptive sampling's subdivision depth.
    pub aa_depth: Option<u32>,
    /// The quadtree's block size (log2).
    pub aa_block: Option<u32>,
    /// The reconstruction filter.
    pub filter: Option<FilterName>,
    /// How samples reach the pixels under the filter.
    pub filter_sampling: Option<FilterSamplingName>,
    /// Seconds to render for, at most (unbounded samples unless `spp` is given too).
    pub time_limit: Option<f64>,
}

/// An overridden value has no place in the file: errors about it must not point there.
fn given<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

impl Overrides {
    /// Checks the counts against the ranges the command line's flags take, so that an error
    /// names the setting rather than the scene file it replaced a value of.
    fn within_ranges(&self, spelling: Spelling) -> Result<(), String> {
        let ranges = [
            ("width", self.width, 1, MAX_IMAGE_SIDE),
            ("height", self.height, 1, MAX_IMAGE_SIDE),
            ("spp", self.spp, 1, MAX_SAMPLES),
            ("max_depth", self.max_depth, 0, MAX_DEPTH),
            ("aa_depth", self.aa_depth, 0, ADAPTIVE_MAX_DEPTH),
            ("aa_block", self.aa_block, 1, MAX_AA_BLOCK),
        ];
        for (setting, value, least, most) in ranges {
            if let Some(v) = value
                && !(least..=most).contains(&v)
            {
                return Err(format!(
                    "{} must be between {least} and {most}, not {v}",
                    spelling.name(setting)
                ));
            }
        }
        match self.time_limit {
            Some(t) if !(t.is_finite() && t > 0.0) => Err(format!(
                "{} must be a positive number of seconds, not {t}",
                spelling.name("time_limit")
            )),
            _ => Ok(()),
        }
    }

    /// Replaces `file`'s settings with these, after checking that they go together. The file's
    /// settings that only another integrator or sampling reads are dropped with it.
    pub fn apply(&self, file: &mut SceneFile, spelling: Spelling) -> Result<(), String> {
        let name = |s: &str| spelling.name(s);
        self.within_ranges(spelling)?;
        let d = &mut file.desc;
        if let Some(aa) = self.aa {
            d.render.aa = aa;
            let r = &mut d.render;
            if aa == SamplingName::Uniform {
                (r.aa_threshold, r.aa_depth) = (None, None);
            }
            if aa != SamplingName::Quadtree {
                r.aa_block = None;
            }
        }
        let aa = d.render.aa;
        if aa == SamplingName::Uniform
            && (self.aa_threshold.is_some() || self.aa_depth.is_some() || self.aa_block.is_some())
        {
            return Err(format!(
                "{}, {} and {} need {} or quadtree",
                name("aa_threshold"),
                name("aa_depth"),
                name("aa_block"),
                spelling.given("aa", "adaptive"),
            ));
        }
        if aa == SamplingName::Adaptive && self.aa_block.is_some() {
            return Err(format!(
                "{} needs {}",
                name("aa_block"),
                spelling.given("aa", "quadtree")
            ));
        }
        if self.spp.is_some() && aa != SamplingName::Uniform {
            return Err(format!(
                "{} has no effect with adaptive or quadtree sampling (each pixel takes its corners)",
                name("spp")
            ));
        }
        if let Some(t) = self.aa_threshold {
            d.render.aa_threshold = Some(given(Finite(t)));
        }
        if let Some(v) = self.aa_depth {
            d.render.aa_depth = Some(given(v));
        }
        if let Some(v) = self.aa_block {
            d.render.aa_block = Some(given(v));
        }
        if let Some(w) = self.width {
            d.image.width = given(w);
        }
        if let Some(h) = self.height {
            d.image.height = given(h);
        }
        if let Some(n) = self.spp {
            d.image.samples = given(n);
        }
        if let Some(i) = self.integrator {
            d.render.integrator = i;
            let r = &mut d.render;
            if i != IntegratorName::Whitted {
                r.shadows = None;
            }
            if i != IntegratorName::Path {
                r.rr_depth = None;
            }
            if i != IntegratorName::Sppm {
                (r.photons, r.photon_radius) = (None, None);
            }
        }
        if let Some(m) = self.max_depth {
            d.render.max_depth = given(m);
        }
        if let Some(s) = self.seed {
            d.render.seed = s;
        }
        if let Some(f) = self.filter {
            d.render.filter = Some(given(f));
            d.render.filter_radius = None;
        }
        if let Some(f) = self.filter_sampling {
            d.render.filter_sampling = Some(given(f));
        }
        if let Some(t) = self.time_limit {
            if aa != SamplingName::Uniform {
                return Err(format!(
                    "{} needs uniform sampling ({})",
                    name("time_limit"),
                    spelling.given("aa", "uniform")
                ));
            }
            d.render.time_limit = Some(given(Finite(t as f32)));
            // The samples are unbounded unless the caller bounds them too.
            if self.spp.is_none() {
                d.image.samples = given(MAX_SAMPLES);
            }
        }
        if let Some(a) = self.accel {
            d.render.accelerator = given(a.name().to_string());
        }
        if let Some(t) = self.triangle_test {
            d.render.triangle_test = t;
        }
        // After the integrator, which it depends on.
        if self.no_shadows {
            if d.render.integrator != IntegratorName::Whitted {
                return Err(format!(
                    "{} applies to the whitted integrator only",
                    spelling.off("shadows")
                ));
            }
            d.render.shadows = Some(given(false));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_spell_settings_as_the_caller_does() {
        let refused = |spelling| {
            let mut file = SceneFile::default_scene();
            Overrides {
                aa: Some(SamplingName::Adaptive),
                spp: Some(4),
                ..Overrides::default()
            }
            .apply(&mut file, spelling)
            .unwrap_err()
        };
        assert!(refused(Spelling::Flags).starts_with("--spp has no effect"));
        assert!(refused(Spelling::Keywords).starts_with("spp has no effect"));
        let mut file = SceneFile::default_scene();
        let e = Overrides {
            integrator: Some(IntegratorName::Path),
            no_shadows: true,
            ..Overrides::default()
        }
        .apply(&mut file, Spelling::Keywords)
        .unwrap_err();
        assert_eq!(e, "shadows=False applies to the whitted integrator only");
    }

    #[test]
    fn counts_out_of_range_are_named_not_blamed_on_the_file() {
        let mut file = SceneFile::default_scene();
        let zero_spp = Overrides {
            spp: Some(0),
            ..Overrides::default()
        };
        assert_eq!(
            zero_spp.apply(&mut file, Spelling::Keywords),
            Err("spp must be between 1 and 1048576, not 0".to_string())
        );
        let wide = Overrides {
            width: Some(70_000),
            ..Overrides::default()
        };
        assert_eq!(
            wide.apply(&mut file, Spelling::Flags),
            Err("--width must be between 1 and 65536, not 70000".to_string())
        );
        let never = Overrides {
            time_limit: Some(-1.0),
            ..Overrides::default()
        };
        assert!(never.apply(&mut file, Spelling::Keywords).is_err());
        // Nothing was replaced by a refused override.
        let fresh = SceneFile::default_scene().desc;
        assert_eq!(
            file.desc.image.samples.get_ref(),
            fresh.image.samples.get_ref()
        );
        assert_eq!(file.desc.image.width.get_ref(), fresh.image.width.get_ref());
    }

    #[test]
    fn another_integrator_drops_the_settings_only_the_old_one_reads() {
        let mut file = SceneFile::default_scene();
        file.desc.render.shadows = Some(given(false));
        Overrides {
            integrator: Some(IntegratorName::Path),
            width: Some(17),
            time_limit: Some(2.0),
            ..Overrides::default()
        }
        .apply(&mut file, Spelling::Flags)
        .unwrap();
        let d = &file.desc;
        assert_eq!(d.render.shadows, None);
        assert_eq!(*d.image.width.get_ref(), 17);
        // A time limit without samples leaves the samples unbounded.
        assert_eq!(*d.image.samples.get_ref(), crate::build::MAX_SAMPLES);
        assert!(file.build().is_ok());
    }
}
