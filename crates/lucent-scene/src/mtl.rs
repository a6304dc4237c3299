//! Wavefront MTL material libraries, mapped onto lucent's `whitted` coefficients as the MTL
//! specification's illumination models define them.
//!
//! | `illum` | MTL meaning | lucent |
//! |---|---|---|
//! | 0 | colour, no ambient | `kd = Kd` |
//! | 1 | colour and ambient | `ka = Ka`, `kd = Kd` |
//! | 2 | highlight | + `ks = Ks`, `shininess = Ns` |
//! | 3, 8 | reflection (ray traced; 8: not) | + `kr = Ks` |
//! | 5 | reflection with Fresnel | + `kr = Ks` (Fresnel left out) |
//! | 4, 6, 7, 9 | glass / refraction | + `kt = Tf` (or `1 − d`), `ior = Ni`; `kr = Ks` except 9 |
//! | 10 | shadows on invisible surfaces | as 2, with a warning |
//!
//! With no `illum`, 2 is assumed when `Ks` is given, else 1. `Ke` becomes `emission`, `map_Kd`
//! an image texture (its options are skipped; the last word is the file).

use crate::desc::{Color, Finite, ImageMapDesc, MaterialDesc, TextureDesc};
use crate::error::LoadError;
use lucent::Rgb;
use std::path::Path;
use toml::Spanned;

/// One `newmtl` block as read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MtlMaterial {
    /// Its name.
    pub name: String,
    /// The line of its `newmtl`.
    pub line: usize,
    ka: Option<Rgb>,
    kd: Option<Rgb>,
    ks: Option<Rgb>,
    ke: Option<Rgb>,
    tf: Option<Rgb>,
    ns: Option<f32>,
    ni: Option<f32>,
    dissolve: Option<f32>,
    illum: Option<u32>,
    map_kd: Option<String>,
}

/// Parses MTL text; `path` names it in errors.
pub fn parse_mtl(bytes: &[u8], path: &Path) -> Result<Vec<MtlMaterial>, LoadError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let text = String::from_utf8_lossy(bytes);
    let mut out: Vec<MtlMaterial> = Vec::new();
    for (n, raw) in text.lines().enumerate() {
        let line = n + 1;
        let err = |m: String| LoadError::line(path, line, m);
        let mut words = raw.split_ascii_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let rest: Vec<&str> = words.collect();
        let number = |w: &str| -> Result<f32, LoadError> {
            match w.parse::<f32>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(err(format!("`{keyword}`: `{w}` is not finite"))),
                Err(_) => Err(err(format!("`{keyword}`: `{w}` is not a number"))),
            }
        };
        let color = || -> Result<Rgb, LoadError> {
            if rest
                .first()
                .is_some_and(|w| *w == "spectral" || *w == "xyz")
            {
                return Err(err(format!("`{keyword}`: only RGB colours are read")));
            }
            match rest.as_slice() {
                [g] => Ok(Rgb::gray(number(g)?)),
                [r, g, b, ..] => Ok(Rgb::new(number(r)?, number(g)?, number(b)?)),
                _ => Err(err(format!(
                    "`{keyword}` needs a colour: one or three numbers"
                ))),
            }
        };
        if keyword == "newmtl" {
            let name = raw.trim_start()[keyword.len()..].trim().to_string();
            out.push(MtlMaterial {
                name,
                line,
                ..MtlMaterial::default()
            });
            continue;
        }
        let Some(m) = out.last_mut() else {
            if keyword.starts_with('#') {
                continue;
            }
            return Err(err(format!("`{keyword}` before any `newmtl`")));
        };
        let first = || {
            rest.first()
                .copied()
                .ok_or_else(|| err(format!("`{keyword}` needs a value")))
        };
        match keyword {
            "Ka" => m.ka = Some(color()?),
            "Kd" => m.kd = Some(color()?),
            "Ks" => m.ks = Some(color()?),
            "Ke" => m.ke = Some(color()?),
            "Tf" => m.tf = Some(color()?),
            "Ns" => m.ns = Some(number(first()?)?.max(0.0)),
            "Ni" => m.ni = Some(number(first()?)?),
            "d" => m.dissolve = Some(number(rest.last().copied().unwrap_or(""))?),
            "Tr" => m.dissolve = Some(1.0 - number(first()?)?),
            "illum" => {
                let w = first()?;
                m.illum = Some(
                    w.parse()
                        .map_err(|_| err(format!("`illum`: `{w}` is not 0 to 10")))?,
                );
            }
            "map_Kd" => m.map_kd = rest.last().map(|s| s.to_string()),
            _ => {}
        }
        if m.illum.is_some_and(|i| i > 10) {
            return Err(err(format!(
                "`illum` {} is not 0 to 10",
                m.illum.unwrap_or(0)
            )));
        }
    }
    Ok(out)
}

impl MtlMaterial {
    /// The `whitted` material description named `name` (see the module's table); warnings
    /// name what is approximated.
    pub fn to_desc(
        &self,
        name: &str,
        texture_path: Option<String>,
        warnings: &mut Vec<String>,
    ) -> MaterialDesc {
        let mut d = MaterialDesc::named(name);
        let c = |v: Rgb| Some(Color(v));
        let illum = self.illum.unwrap_or(if self.ks.is_some() { 2 } else { 1 });
        let kd = self.kd.unwrap_or(Rgb::gray(0.8));
        d.kd = Some(match texture_path {
            Some(file) => TextureDesc::Image(ImageMapDesc::new(file)),
            None => TextureDesc::Solid(kd),
        });
        if illum >= 1 {
            d.ka = c(self.ka.unwrap_or(kd));
        }
        let ks = self.ks.unwrap_or(Rgb::BLACK);
        if illum >= 2 {
            d.ks = c(ks);
            d.shininess = Some(Spanned::new(0..0, Finite(self.ns.unwrap_or(0.0))));
        }
        if matches!(illum, 3..=8) {
            d.kr = c(ks);
        }
        if matches!(illum, 4 | 6 | 7 | 9) {
            let kt = self.tf.unwrap_or(Rgb::gray(
                1.0 - self.dissolve.unwrap_or(0.0).clamp(0.0, 1.0),
            ));
            d.kt = c(kt);
            let ior = self.ni.filter(|&n| n > 0.0).unwrap_or(1.5);
            d.ior = Some(Spanned::new(0..0, Finite(ior)));
        }
        if illum == 10 {
            warnings.push(format!(
                "material `{}`: illum 10 (shadows on invisible surfaces) is rendered as illum 2",
                self.name
            ));
        }
        if let Some(ke) = self.ke.filter(|k| !k.is_black()) {
            d.emission = Some(TextureDesc::Solid(ke));
        }
        d
    }

    /// The `map_Kd` file name, as written.
    pub fn texture(&self) -> Option<&str> {
        self.map_kd.as_deref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<MtlMaterial>, LoadError> {
        parse_mtl(text.as_bytes(), Path::new("m.mtl"))
    }

    #[test]
    fn illumination_models_map_to_coefficients() {
        let mats = parse(
            "newmtl mirror\nKd 0.1 0.2 0.3\nKs 0.9\nNs 50\nillum 3\n\nnewmtl glass\nKs 0.1\nNi 1.45\nTf 0.9 0.9 1\nillum 7\n# c\nnewmtl lamp\nKe 4 4 4\nmap_Kd -s 1 1 1 wood.png\n",
        )
        .unwrap();
        let mut warnings = vec![];
        let mirror = mats[0].to_desc("m", None, &mut warnings);
        assert_eq!(mirror.kd, Some(TextureDesc::Solid(Rgb::new(0.1, 0.2, 0.3))));
        assert_eq!(mirror.kr, Some(Color(Rgb::gray(0.9))));
        assert_eq!(mirror.shininess.map(|s| s.into_inner().0), Some(50.0));
        assert!(mirror.kt.is_none());
        let glass = mats[1].to_desc("g", None, &mut warnings);
        assert_eq!(glass.kt, Some(Color(Rgb::new(0.9, 0.9, 1.0))));
        assert_eq!(glass.ior.map(|s| s.into_inner().0), Some(1.45));
        assert_eq!(glass.kr, Some(Color(Rgb::gray(0.1))));
        assert_eq!(mats[2].texture(), Some("wood.png"));
        let lamp = mats[2].to_desc("l", Some("wood.png".into()), &mut warnings);
        assert_eq!(lamp.emission, Some(TextureDesc::Solid(Rgb::gray(4.0))));
        assert_eq!(
            lamp.kd,
            Some(TextureDesc::Image(ImageMapDesc::new("wood.png")))
        );
        assert!(warnings.is_empty());
    }

    #[test]
    fn dissolve_gives_transmission_for_glass() {
        let mats = parse("newmtl a\nd 0.25\nillum 9\nnewmtl b\nTr 0.5\nillum 4\n").unwrap();
        let mut w = vec![];
        assert_eq!(
            mats[0].to_desc("a", None, &mut w).kt,
            Some(Color(Rgb::gray(0.75)))
        );
        assert!(
            mats[0].to_desc("a", None, &mut w).kr.is_none(),
            "illum 9: no reflection"
        );
        assert_eq!(
            mats[1].to_desc("b", None, &mut w).kt,
            Some(Color(Rgb::gray(0.5)))
        );
    }

    #[test]
    fn errors_name_the_line() {
        for (text, line, needle) in [
            ("Kd 1 1 1\n", 1, "before any `newmtl`"),
            ("newmtl a\nKd 1 x 1\n", 2, "not a number"),
            ("newmtl a\nNs nan\n", 2, "not finite"),
            ("newmtl a\nillum 12\n", 2, "0 to 10"),
            ("newmtl a\nKd\n", 2, "needs a colour"),
        ] {
            let e = parse(text).unwrap_err();
            assert_eq!(e.position, Some((line, 1)), "{text:?}");
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }
}
