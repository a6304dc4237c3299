//! A fingerprint of a scene's inputs: the scene file's text and the bytes of every mesh file it
//! reads, so that shards and checkpoints can tell whether they come from the same scene.
//!
//! FNV-1a over 64 bits: not a defence against a forger, but any accidental change (an edited
//! scene, a different mesh file) gives another fingerprint.

/// A running FNV-1a 64-bit hash.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fingerprint(u64);

impl Default for Fingerprint {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fingerprint {
    /// Adds `bytes`, preceded by their length (so that "ab"+"c" and "a"+"bc" differ).
    pub fn add(&mut self, bytes: &[u8]) {
        self.add_raw(&(bytes.len() as u64).to_le_bytes());
        self.add_raw(bytes);
    }

    /// Adds `bytes` with no length before them: for a stream whose layout is fixed by what
    /// came before (such as the pixels of an image of known size).
    pub fn add_raw(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }

    /// The value so far.
    pub fn value(&self) -> u64 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_value_and_boundaries_matter() {
        let mut empty = Fingerprint::default();
        empty.add_raw(b"");
        assert_eq!(empty.value(), 0xcbf2_9ce4_8422_2325);
        let mut a = Fingerprint::default();
        a.add_raw(b"a");
        assert_eq!(a.value(), 0xaf63_dc4c_8601_ec8c); // FNV-1a("a")
        let (mut x, mut y) = (Fingerprint::default(), Fingerprint::default());
        x.add(b"ab");
        x.add(b"c");
        y.add(b"a");
        y.add(b"bc");
        assert_ne!(x, y);
    }
}
