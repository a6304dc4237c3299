//! Hostile input: mangled and deeply nested files are refused, never a panic or a stack overflow.

use super::support::*;
use lucent_scene::hash::Fingerprint;
use lucent_scene::mitsuba::import_mitsuba;
use lucent_scene::{LoadOptions, SceneFile};

#[test]
fn mangled_cornell_boxes_never_panic() {
    let dir = Dir::new("mangled");
    let path = dir.path("mangled.xml");
    let bytes = CBOX.as_bytes();
    let mut variants: Vec<Vec<u8>> = Vec::new();
    // Truncations, every few bytes.
    for end in (0..bytes.len()).step_by(bytes.len() / 150) {
        variants.push(bytes[..end].to_vec());
    }
    // One to three bytes changed: a bit flipped, or a character that XML or Mitsuba reads as
    // special, from a fixed sequence of pseudo-random numbers.
    const SPECIAL: &[u8] = b"<>\"'/=$&;-.e0 \n\0\xff";
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..300 {
        let mut v = bytes.to_vec();
        for _ in 0..1 + next() % 3 {
            let at = (next() % v.len() as u64) as usize;
            v[at] = match next() % 2 {
                0 => v[at] ^ (1 << (next() % 8)),
                _ => SPECIAL[(next() % SPECIAL.len() as u64) as usize],
            };
        }
        variants.push(v);
    }
    assert!(variants.len() > 400);

    let (mut ok, mut refused) = (0, 0);
    for (i, v) in variants.iter().enumerate() {
        std::fs::write(&path, v).unwrap();
        let outcome = std::panic::catch_unwind(|| {
            let imported =
                import_mitsuba(&path, &LoadOptions::default(), &mut Fingerprint::default());
            // What imports must also build, or be refused with a message.
            if imported.is_ok() {
                let built = SceneFile::read_with(&path, &open()).and_then(|f| f.build());
                if let Err(e) = &built {
                    assert!(!e.message.is_empty());
                }
            }
            imported.map(|_| ())
        });
        match outcome {
            Ok(Ok(())) => ok += 1,
            Ok(Err(e)) => {
                assert!(
                    !e.message.is_empty() && !e.to_string().contains('\n'),
                    "variant {i}: {e}"
                );
                refused += 1;
            }
            Err(_) => panic!("variant {i} panicked:\n{}", String::from_utf8_lossy(v)),
        }
    }
    // Both outcomes happen: the test is not only feeding garbage.
    assert!(ok >= 5 && refused > 100, "{ok} read, {refused} refused");
}

#[test]
fn deeply_nested_elements_are_refused_without_exhausting_the_stack() {
    let dir = Dir::new("nested");
    let depth = 100_000;
    let body = "<bsdf type=\"twosided\">".repeat(depth) + &"</bsdf>".repeat(depth);
    let path = dir.write("nested.xml", scene(&body));
    // Tests run on threads with small stacks; the reader must not recurse this deep.
    let e = import_error(&path, &open());
    assert!(e.message.contains("nested more than"), "{e}");
    assert_eq!(e.position.map(|p| p.0), Some(2));
}
