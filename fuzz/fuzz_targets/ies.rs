//! IES photometric files (LM-63): parsed, then the profile asked for its intensity along a
//! spread of directions, its flux, photons drawn from it, and a tilt table's factors; nothing
//! may panic, and every answer must be finite and not negative.
#![no_main]

use glam::{Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use lucent_scene::ies::parse_ies;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let Ok(ies) = parse_ies(Path::new("fuzz.ies"), &text) else {
        return;
    };
    let p = &ies.profile;
    let total = p.total();
    assert!(total.is_finite() && total >= 0.0, "total {total}");
    for i in 0..64 {
        let (a, b) = (i as f32 * 0.618_034, i as f32 * 0.414_214);
        let d = Vec3::new(a.sin() * b.cos(), a.cos(), a.sin() * b.sin()).normalize_or(Vec3::Z);
        let v = p.intensity(d);
        assert!(v.is_finite() && v >= 0.0, "intensity {v} along {d}");
        let u = Vec2::new(a.fract(), b.fract());
        if let Some((dir, pdf)) = p.sample(u) {
            assert!(dir.is_finite() && pdf.is_finite() && pdf > 0.0, "{dir} {pdf}");
        }
    }
    if let Some(t) = &ies.tilt {
        for angle in [0.0, 15.0, 45.0, 90.0, 180.0] {
            let f = t.factor(angle);
            assert!(f.is_finite(), "tilt factor {f} at {angle}");
        }
    }
});
