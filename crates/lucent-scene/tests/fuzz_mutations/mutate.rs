//! The mutations: what a fuzzer does to a file, as values proptest can generate and shrink.

use proptest::prelude::*;
use proptest::sample::Index;

/// Values a number is replaced with: the edges of the integer types, non-finite and
/// out-of-range floats, a negative count.
const NUMBERS: [&str; 15] = [
    "4294967295",
    "4294967296",
    "-1",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e39",
    "1e308",
    "-0",
    "0",
    "18446744073709551615",
    "99999999999999999999999",
    "2147483648",
    "1e-45",
];

/// 32-bit words written over binary data: the same edges, and NaN and infinity as `f32`.
const WORDS: [u32; 7] = [
    u32::MAX,
    0x7fff_ffff,
    0x8000_0000,
    0x7fc0_0000,
    0x7f80_0000,
    0,
    0x0001_0000,
];

#[derive(Clone, Debug)]
pub enum Mutation {
    /// Flip one bit of a byte.
    Flip(Index, u8),
    /// Set a byte.
    Set(Index, u8),
    /// Insert a run of random bytes.
    Insert(Index, Vec<u8>),
    /// Delete a run of up to this many bytes.
    Delete(Index, usize),
    /// Cut the file short.
    Truncate(Index),
    /// Insert a run of another sample of the format: (where, which sample, from, length).
    Splice(Index, Index, Index, usize),
    /// Replace the k-th number with one of [`NUMBERS`].
    Number(Index, Index),
    /// Overwrite four bytes with one of [`WORDS`], little-endian.
    Word(Index, Index),
    /// Repeat a line this many more times.
    DuplicateLine(Index, u8),
}

pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        2 => (any::<Index>(), 0..8u8).prop_map(|(i, b)| Mutation::Flip(i, b)),
        1 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::Set(i, b)),
        1 => (any::<Index>(), proptest::collection::vec(any::<u8>(), 1..32))
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
        1 => (any::<Index>(), 1..256usize).prop_map(|(i, n)| Mutation::Delete(i, n)),
        1 => any::<Index>().prop_map(Mutation::Truncate),
        1 => (any::<Index>(), any::<Index>(), any::<Index>(), 1..512usize)
            .prop_map(|(a, b, c, n)| Mutation::Splice(a, b, c, n)),
        3 => (any::<Index>(), any::<Index>()).prop_map(|(k, v)| Mutation::Number(k, v)),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(i, v)| Mutation::Word(i, v)),
        1 => (any::<Index>(), 1..4u8).prop_map(|(i, n)| Mutation::DuplicateLine(i, n)),
    ]
}

/// The spans of the numbers in `b`: runs of digits, signs, points and exponents holding a digit.
pub fn numbers(b: &[u8]) -> Vec<(usize, usize)> {
    let part = |c: u8| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+' | b'e' | b'E');
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if part(b[i]) {
            let start = i;
            while i < b.len() && part(b[i]) {
                i += 1;
            }
            if b[start..i].iter().any(u8::is_ascii_digit) {
                out.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The spans of the lines of `b`, each with its line break.
fn lines(b: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &c) in b.iter().enumerate() {
        if c == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < b.len() {
        out.push((start, b.len()));
    }
    out
}

pub fn apply(m: &Mutation, b: &mut Vec<u8>, samples: &[Vec<u8>]) {
    let len = b.len();
    // Positions in 0..len (`at`) or 0..=len (`gap`, for insertions).
    let at = |i: &Index| (len > 0).then(|| i.index(len));
    let gap = |i: &Index| i.index(len + 1);
    match m {
        Mutation::Flip(i, bit) => {
            if let Some(k) = at(i) {
                b[k] ^= 1 << bit;
            }
        }
        Mutation::Set(i, v) => {
            if let Some(k) = at(i) {
                b[k] = *v;
            }
        }
        Mutation::Insert(i, run) => {
            let k = gap(i);
            b.splice(k..k, run.iter().copied());
        }
        Mutation::Delete(i, n) => {
            if let Some(k) = at(i) {
                b.drain(k..(k + n).min(len));
            }
        }
        Mutation::Truncate(i) => b.truncate(gap(i)),
        Mutation::Splice(i, which, from, n) => {
            let other = &samples[which.index(samples.len())];
            if !other.is_empty() {
                let s = from.index(other.len());
                let run = &other[s..(s + n).min(other.len())];
                let k = gap(i);
                b.splice(k..k, run.iter().copied());
            }
        }
        Mutation::Number(k, v) => {
            let spans = numbers(b);
            if !spans.is_empty() {
                let (s, e) = spans[k.index(spans.len())];
                b.splice(s..e, v.get(&NUMBERS[..]).bytes());
            }
        }
        Mutation::Word(i, v) => {
            if len >= 4 {
                let k = i.index(len - 3);
                b[k..k + 4].copy_from_slice(&v.get(&WORDS[..]).to_le_bytes());
            }
        }
        Mutation::DuplicateLine(i, n) => {
            let spans = lines(b);
            if !spans.is_empty() {
                let (s, e) = spans[i.index(spans.len())];
                let line = b[s..e].to_vec();
                for _ in 0..*n {
                    b.splice(e..e, line.iter().copied());
                }
            }
        }
    }
}
