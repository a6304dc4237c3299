//! The budgets a scene is held to, checked before the work they bound: a small file must not
//! make lucent read, parse or build gigabytes before it says no. Each is named, documented
//! (`docs/import.md`, "Limits and hostile input") and raised by `--limit NAME=VALUE` for the
//! rare real scene that needs more.

use std::fmt;

/// The budgets (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Bytes of XML a Mitsuba scene may read, each include counted each time it is included
    /// (`xml`, in MiB).
    pub xml_bytes: u64,
    /// Objects a scene may hold after its files are read: a mesh file's parts, a Mitsuba
    /// file's shapes, a TOML file's objects (`objects`).
    pub objects: u64,
    /// Vertices plus triangles of the meshes a scene stores, instances of a stored mesh not
    /// counted again (`geometry`).
    pub geometry: u64,
    /// Bytes of pixel data a partial film or checkpoint may hold, for `lucent merge` and
    /// `--resume` (`film`, in MiB).
    pub film_bytes: u64,
}

impl Limits {
    /// The defaults (see [`Limits::default`]), as a constant.
    pub const DEFAULT: Limits = Limits {
        xml_bytes: 16 << 20,
        objects: 100_000,
        geometry: 1 << 27,
        film_bytes: 1 << 30,
    };
}

impl Default for Limits {
    /// 16 MiB of XML (published Mitsuba scenes hold a few MiB at most; 16 MiB of includes are
    /// refused in 0.5 s and 125 MB), 100,000 objects (an OBJ of that many parts takes 2.1 s
    /// and 0.7 GB for `lucent info`), 2²⁷ vertices and triangles (about 5 GB of geometry and
    /// accelerators), and 1 GiB of film (a 7680 × 4320 render's partial films are 0.62 GiB).
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One budget by name, for messages and the flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// [`Limits::xml_bytes`].
    Xml,
    /// [`Limits::objects`].
    Objects,
    /// [`Limits::geometry`].
    Geometry,
    /// [`Limits::film_bytes`].
    Film,
}

impl Limit {
    /// Every budget, in the order the docs list them.
    pub const ALL: [Limit; 4] = [Limit::Xml, Limit::Objects, Limit::Geometry, Limit::Film];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Limit::Xml => "xml",
            Limit::Objects => "objects",
            Limit::Geometry => "geometry",
            Limit::Film => "film",
        }
    }

    /// The unit its flag's value is given in: bytes per unit.
    fn unit(self) -> u64 {
        match self {
            Limit::Xml | Limit::Film => 1 << 20,
            Limit::Objects | Limit::Geometry => 1,
        }
    }
}

impl Limits {
    /// The value of `limit`, in its own unit (bytes or a count).
    pub fn get(&self, limit: Limit) -> u64 {
        match limit {
            Limit::Xml => self.xml_bytes,
            Limit::Objects => self.objects,
            Limit::Geometry => self.geometry,
            Limit::Film => self.film_bytes,
        }
    }

    /// Sets a budget from `NAME=VALUE` (MiB for `xml` and `film`, a count otherwise).
    pub fn set(&mut self, spec: &str) -> Result<(), String> {
        let names = || {
            Limit::ALL
                .map(Limit::name)
                .map(|n| format!("`{n}`"))
                .join(", ")
        };
        let (name, value) = spec
            .split_once('=')
            .ok_or_else(|| format!("`{spec}`: expected NAME=VALUE, NAME one of {}", names()))?;
        let limit = Limit::ALL
            .into_iter()
            .find(|l| l.name() == name.trim())
            .ok_or_else(|| format!("`{name}` is not a budget; the budgets are {}", names()))?;
        let value: u64 = value
            .trim()
            .parse()
            .ok()
            .filter(|&v| v > 0)
            .ok_or_else(|| format!("`{spec}`: the value must be a positive whole number"))?;
        let value = value.saturating_mul(limit.unit());
        match limit {
            Limit::Xml => self.xml_bytes = value,
            Limit::Objects => self.objects = value,
            Limit::Geometry => self.geometry = value,
            Limit::Film => self.film_bytes = value,
        }
        Ok(())
    }

    /// The message for going over `limit`: what it is, and how to raise it.
    pub fn exceeded(&self, limit: Limit, what: impl fmt::Display) -> String {
        let v = self.get(limit);
        let shown = match limit.unit() {
            1 => v.to_string(),
            u => format!("{} MiB", v.div_ceil(u)),
        };
        format!(
            "{what}, over the budget of {shown} (`--limit {}=N` raises it)",
            limit.name()
        )
    }

    /// `amount` of `limit` held to its budget: the [`Limits::exceeded`] message of
    /// `what(amount)` when over it.
    pub fn check(
        &self,
        limit: Limit,
        amount: u64,
        what: impl FnOnce(u64) -> String,
    ) -> Result<(), String> {
        if amount > self.get(limit) {
            return Err(self.exceeded(limit, what(amount)));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_are_set_by_name_in_their_units() {
        let mut l = Limits::default();
        l.set("xml=64").unwrap();
        l.set(" objects = 500000").unwrap();
        assert_eq!((l.xml_bytes, l.objects), (64 << 20, 500_000));
        for bad in ["xml", "xml=0", "xml=-1", "texels=5", "film=lots"] {
            assert!(l.set(bad).is_err(), "{bad}");
        }
        assert!(
            l.exceeded(Limit::Xml, "the includes come to 70 MiB")
                .ends_with("over the budget of 64 MiB (`--limit xml=N` raises it)")
        );
    }
}
