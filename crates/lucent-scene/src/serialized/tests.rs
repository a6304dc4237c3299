//! The serialized reader against files made here: every flag and precision, several shapes,
//! and hostile files (lying counts and dictionaries, truncations, zip bombs, NaN).

use super::*;
use flate2::{Compress, Compression, FlushCompress};
use std::time::Instant;

/// A shape to encode: its arrays, and counts that may lie.
#[derive(Clone)]
struct Data {
    flags: u32,
    name: &'static str,
    positions: Vec<[f64; 3]>,
    normals: Vec<[f64; 3]>,
    uvs: Vec<[f64; 2]>,
    colors: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
    /// Counts written instead of the arrays' lengths.
    counts: Option<(u64, u64)>,
}

/// A tetrahedron with every array; `flags` say which are written, and the precision.
fn tetra(flags: u32) -> Data {
    Data {
        flags,
        name: "tetra",
        positions: vec![
            [0.5, -1.25, 3.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        normals: vec![
            [0.0, 0.0, -2.0],
            [1.0, 0.0, 0.0],
            [0.6, 0.8, 0.0],
            [0.0, 0.0, 1.0],
        ],
        uvs: vec![[0.0, 0.0], [1.0, 0.25], [0.5, 1.0], [0.125, 0.75]],
        colors: vec![
            [0.1, 0.2, 0.3],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.5, 0.0, 1.0],
        ],
        triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        counts: None,
    }
}

/// The shape's stream before compression, as Mitsuba writes it.
fn raw(d: &Data, version: u16) -> Vec<u8> {
    let mut b = d.flags.to_le_bytes().to_vec();
    if version == 4 {
        b.extend_from_slice(d.name.as_bytes());
        b.push(0);
    }
    let (v, t) = d
        .counts
        .unwrap_or((d.positions.len() as u64, d.triangles.len() as u64));
    b.extend_from_slice(&v.to_le_bytes());
    b.extend_from_slice(&t.to_le_bytes());
    let mut put = |xs: &[f64]| {
        for &x in xs {
            if d.flags & DOUBLE != 0 {
                b.extend_from_slice(&x.to_le_bytes());
            } else {
                b.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
    };
    d.positions.iter().for_each(|p| put(p));
    let has = |f: u32| d.flags & f != 0;
    if has(HAS_NORMALS) {
        d.normals.iter().for_each(|n| put(n));
    }
    if has(HAS_UVS) {
        d.uvs.iter().for_each(|uv| put(uv));
    }
    if has(HAS_COLORS) {
        d.colors.iter().for_each(|c| put(c));
    }
    for t in &d.triangles {
        for i in t {
            b.extend_from_slice(&i.to_le_bytes());
        }
    }
    b
}

/// `bytes` through zlib, with `flush` at their end (`Finish` ends the stream).
fn deflate(z: &mut Compress, bytes: &[u8], flush: FlushCompress) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() + 1024);
    let start = z.total_in();
    loop {
        let used = (z.total_in() - start) as usize;
        z.compress_vec(&bytes[used..], &mut out, flush).unwrap();
        if (z.total_in() - start) as usize == bytes.len() && out.len() < out.capacity() {
            return out;
        }
        out.reserve(out.capacity());
    }
}

fn compress(bytes: &[u8]) -> Vec<u8> {
    deflate(
        &mut Compress::new(Compression::default(), true),
        bytes,
        FlushCompress::Finish,
    )
}

/// A file of compressed shape streams: each with its header, then the dictionary.
fn file_of(version: u16, streams: &[Vec<u8>]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut offsets = Vec::new();
    for s in streams {
        offsets.push(out.len() as u64);
        out.extend_from_slice(&FORMAT_ID.to_le_bytes());
        out.extend_from_slice(&version.to_le_bytes());
        out.extend_from_slice(s);
    }
    for o in &offsets {
        if version == 3 {
            out.extend_from_slice(&(*o as u32).to_le_bytes());
        } else {
            out.extend_from_slice(&o.to_le_bytes());
        }
    }
    out.extend_from_slice(&(offsets.len() as u32).to_le_bytes());
    out
}

fn file(version: u16, shapes: &[Data]) -> Vec<u8> {
    let streams: Vec<_> = shapes.iter().map(|d| compress(&raw(d, version))).collect();
    file_of(version, &streams)
}

fn parse(bytes: &[u8], index: u32) -> Result<Shape, LoadError> {
    parse_serialized(bytes, index, Path::new("t.serialized"))
}

/// The error of shape `index` of `bytes`, with the bytes inflated on the way.
fn refused(bytes: &[u8], index: u32) -> (LoadError, u64) {
    let mut inflated = 0;
    match decode(
        bytes,
        index,
        Path::new("t.serialized"),
        &Limits::DEFAULT,
        &mut inflated,
    ) {
        Ok(_) => panic!("shape {index} should be refused"),
        Err(e) => {
            assert!(!e.to_string().contains('\n'), "{e}");
            (e, inflated)
        }
    }
}

fn f32s<const N: usize>(v: &[[f64; N]]) -> Vec<[f32; N]> {
    v.iter().map(|a| a.map(|x| x as f32)).collect()
}

#[test]
fn every_flag_combination_and_precision_reads_back() {
    for version in VERSIONS {
        for precision in [SINGLE, DOUBLE, 0] {
            for arrays in 0..8u32 {
                let flags = precision
                    | ((arrays & 1) * HAS_NORMALS)
                    | (((arrays >> 1) & 1) * HAS_UVS)
                    | (((arrays >> 2) & 1) * HAS_COLORS);
                let d = tetra(flags);
                let case = format!("version {version}, flags {flags:#06x}");
                let s = parse(&file(version, std::slice::from_ref(&d)), 0)
                    .unwrap_or_else(|e| panic!("{case}: {e}"));
                let m = &s.mesh;
                assert_eq!(s.name, if version == 4 { "tetra" } else { "" }, "{case}");
                let positions: Vec<[f32; 3]> = m.positions.iter().map(|p| p.to_array()).collect();
                assert_eq!(positions, f32s(&d.positions), "{case}");
                assert_eq!(m.triangles, d.triangles, "{case}");
                let normals: Vec<Vec3> = f32s(&d.normals)
                    .into_iter()
                    .map(|n| Vec3::from_array(n).normalize())
                    .collect();
                let expect = |on: bool, v: Vec<Vec3>| if on { v } else { vec![] };
                assert_eq!(
                    m.normals,
                    expect(flags & HAS_NORMALS != 0, normals),
                    "{case}"
                );
                let uvs: Vec<Vec2> = f32s(&d.uvs).into_iter().map(Vec2::from_array).collect();
                assert_eq!(m.uvs.is_empty(), flags & HAS_UVS == 0, "{case}");
                if flags & HAS_UVS != 0 {
                    assert_eq!(m.uvs, uvs, "{case}: as written, v not flipped");
                }
                let colors: Vec<Rgb> = f32s(&d.colors).into_iter().map(Rgb::from).collect();
                assert_eq!(m.colors.is_empty(), flags & HAS_COLORS == 0, "{case}");
                if flags & HAS_COLORS != 0 {
                    assert_eq!(m.colors, colors, "{case}");
                }
                m.validate().unwrap();
            }
        }
    }
}

#[test]
fn normals_are_made_unit_length_however_small() {
    // Found by the fuzzer: a normal whose squares are denormals came out 5% too long.
    let mut d = tetra(SINGLE | HAS_NORMALS);
    d.normals[0] = [1e-22, 0.0, -1e-22];
    d.normals[1] = [0.0, 0.0, 0.0];
    d.normals[2] = [3e38, 3e38, 0.0];
    let m = parse(&file(4, &[d]), 0).unwrap().mesh;
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert!(
        m.normals[0].abs_diff_eq(Vec3::new(h, 0.0, -h), 1e-6),
        "{}",
        m.normals[0]
    );
    assert_eq!(m.normals[1], Vec3::ZERO);
    assert!(
        m.normals[2].abs_diff_eq(Vec3::new(h, h, 0.0), 1e-6),
        "{}",
        m.normals[2]
    );
}

#[test]
fn the_face_normals_flag_is_read_past_as_mitsuba_3_does() {
    let d = tetra(SINGLE | HAS_NORMALS | FACE_NORMALS);
    let m = parse(&file(4, &[d]), 0).unwrap().mesh;
    assert_eq!(m.normals.len(), 4);
}

#[test]
fn shape_index_picks_each_shape_of_a_file() {
    let shapes: Vec<Data> = (0..3)
        .map(|k| {
            let mut d = tetra(SINGLE | HAS_UVS);
            d.positions.iter_mut().for_each(|p| p[0] += k as f64);
            d.triangles.truncate(k + 1);
            d
        })
        .collect();
    for version in VERSIONS {
        let bytes = file(version, &shapes);
        assert_eq!(shape_count(&bytes, Path::new("t")).unwrap(), 3);
        for (k, d) in shapes.iter().enumerate() {
            let m = parse(&bytes, k as u32).unwrap().mesh;
            assert_eq!(m.positions[0].x, d.positions[0][0] as f32);
            assert_eq!(m.triangles.len(), k + 1, "version {version}, shape {k}");
        }
        let (e, inflated) = refused(&bytes, 3);
        assert_eq!(
            e.message,
            "shape index 3 is out of range: the file holds 3 shapes (0 to 2)"
        );
        assert_eq!(inflated, 0);
    }
}

#[test]
fn a_part_is_a_decimal_shape_index() {
    let path = Path::new("m.serialized");
    assert_eq!(shape_index(None, path).unwrap(), 0);
    assert_eq!(shape_index(Some("12"), path).unwrap(), 12);
    for bad in ["", "-1", "+1", " 1", "one", "1.0"] {
        let e = shape_index(Some(bad), path).unwrap_err();
        assert!(e.message.contains("is not a shape index"), "{bad}: {e}");
    }
    let e = shape_index(Some("99999999999"), path).unwrap_err();
    assert!(e.message.contains("out of range"), "{e}");
}

#[test]
fn a_vertex_count_of_2_to_the_60_is_refused_before_anything_is_allocated() {
    let mut d = tetra(SINGLE);
    d.counts = Some((1 << 60, 4));
    let began = Instant::now();
    let (e, inflated) = refused(&file(4, &[d]), 0);
    assert!(began.elapsed().as_secs_f32() < 1.0);
    assert!(
        e.message.starts_with(
            "shape 0: it claims 1152921504606846976 vertices and 4 triangles, over the budget of 134217728 (`--limit geometry=N` raises it)"
        ),
        "{e}"
    );
    assert!(inflated <= CHUNK as u64, "{inflated}");
    // The triangle count too, and the two together.
    for counts in [(4, u64::MAX), (Limits::DEFAULT.geometry, 1)] {
        let mut d = tetra(SINGLE);
        d.counts = Some(counts);
        let (e, _) = refused(&file(3, &[d]), 0);
        assert!(e.message.contains("budget"), "{e}");
    }
}

/// A zlib stream of `header` (inflated) then `copies` × 1 MiB of zeros, never ended: a
/// zip bomb of about a kilobyte per inflated mebibyte.
fn bomb(header: &[u8], copies: usize) -> Vec<u8> {
    let mut z = Compress::new(Compression::best(), true);
    let mut out = deflate(&mut z, header, FlushCompress::Full);
    // A full flush forgets the data before it: the compressed mebibyte can be repeated.
    let zeros = deflate(&mut z, &vec![0; 1 << 20], FlushCompress::Full);
    for _ in 0..copies {
        out.extend_from_slice(&zeros);
    }
    out
}

fn header(version: u16, vertices: u64, triangles: u64) -> Vec<u8> {
    let mut d = tetra(SINGLE);
    d.counts = Some((vertices, triangles));
    d.positions.clear();
    d.triangles.clear();
    raw(&d, version)
}

#[test]
fn counts_a_small_stream_cannot_hold_are_refused_before_inflating_them() {
    // A few kilobytes that claim 2^25 vertices and triangles (800 MB of arrays), backed
    // by 4 MiB of zeros: refused from the counts, before the arrays are inflated.
    let stream = bomb(&header(4, 1 << 25, 1 << 25), 4);
    let bytes = file_of(4, &[stream]);
    assert!(bytes.len() < 8 << 10, "{}", bytes.len());
    let began = Instant::now();
    let (e, inflated) = refused(&bytes, 0);
    assert!(began.elapsed().as_secs_f32() < 1.0);
    assert!(e.message.contains("more than its"), "{e}");
    assert!(e.message.contains("zip bombs"), "{e}");
    assert!(inflated <= CHUNK as u64, "{inflated}");
}

#[test]
fn a_zip_bomb_is_refused_after_a_bounded_inflate() {
    // 4 MiB that inflate to 4 GiB, claiming 800 MB of arrays: a claim its size allows
    // (deflate inflates up to 1032 times), so the stream is inflated, and refused once it
    // has inflated more than MAX_RATIO times what it used.
    let stream = bomb(&header(4, 1 << 25, 1 << 25), 4096);
    let bytes = file_of(4, &[stream]);
    assert!(bytes.len() < 5 << 20, "{}", bytes.len());
    let began = Instant::now();
    let (e, inflated) = refused(&bytes, 0);
    let took = began.elapsed().as_secs_f32();
    assert!(e.message.contains("refused as a zip bomb"), "{e}");
    assert!(inflated <= RATIO_FREE + CHUNK as u64, "{inflated}");
    assert!(took < 5.0, "{took} s");
}

#[test]
fn a_stream_longer_than_its_counts_is_inflated_no_further() {
    // One triangle, then 4 GiB of zeros that are never inflated.
    let d = tetra(SINGLE);
    let stream = bomb(&raw(&d, 4), 4096);
    let bytes = file_of(4, &[stream]);
    let mut inflated = 0;
    let began = Instant::now();
    let s = decode(&bytes, 0, Path::new("t"), &Limits::DEFAULT, &mut inflated).unwrap();
    assert_eq!(s.mesh.triangles.len(), 4);
    assert!(inflated <= CHUNK as u64, "{inflated}");
    assert!(began.elapsed().as_secs_f32() < 1.0);
}

#[test]
fn truncated_streams_and_files_are_refused_never_a_panic() {
    let d = tetra(DOUBLE | HAS_NORMALS | HAS_UVS | HAS_COLORS);
    let stream = compress(&raw(&d, 4));
    let whole = parse(&file_of(4, std::slice::from_ref(&stream)), 0).unwrap();
    for cut in 0..stream.len() {
        let bytes = file_of(4, &[stream[..cut].to_vec()]);
        match parse(&bytes, 0) {
            // What follows the data (its checksum, which Mitsuba does not read either) is
            // not needed.
            Ok(s) => assert!(s == whole && cut + 8 > stream.len(), "cut at {cut}"),
            Err(e) => assert!(
                ["end", "corrupt", "no progress", "dictionary"]
                    .iter()
                    .any(|w| e.message.contains(w)),
                "cut at {cut}: {e}"
            ),
        }
    }
    let bytes = file(4, &[d.clone(), d]);
    for cut in 0..bytes.len() {
        for index in [0, 1] {
            assert!(parse(&bytes[..cut], index).is_err(), "cut at {cut}");
        }
    }
    // A whole stream with a vertex fewer than its count: the arrays shift by one vertex,
    // and the stream (170 bytes) ends in the triangles.
    let mut d = tetra(SINGLE | HAS_NORMALS);
    d.counts = Some((5, 4));
    let (e, _) = refused(&file(4, &[d]), 0);
    assert_eq!(
        e.message,
        "shape 0: the compressed stream ends after 170 bytes, in the middle of the triangles"
    );
}

/// Overwrites the dictionary entry `i` of a version-4 file.
fn set_offset(bytes: &mut [u8], count: usize, i: usize, offset: u64) {
    let at = bytes.len() - 4 - 8 * (count - i);
    bytes[at..at + 8].copy_from_slice(&offset.to_le_bytes());
}

#[test]
fn a_lying_dictionary_is_refused() {
    let good = file(4, &[tetra(SINGLE), tetra(DOUBLE), tetra(SINGLE)]);
    let n = good.len();
    let second = u64::from_le_bytes(good[n - 20..n - 12].try_into().unwrap());
    // The shape count, or shape i's offset, replaced.
    enum Lie {
        Count(u32),
        Offset(usize, u64),
    }
    let cases = [
        ("more than the file's", Lie::Count(1 << 30)),
        ("holds no shapes", Lie::Count(0)),
        ("shape 0 starts at byte 7, not 0", Lie::Offset(0, 7)),
        ("not past shape 1", Lie::Offset(2, second)),
        ("not past shape 0", Lie::Offset(1, 3)),
        ("past the end of the shapes", Lie::Offset(2, u64::MAX)),
        // An offset inside a stream: the header there is not a shape's.
        ("is not the file's", Lie::Offset(1, second + 2)),
    ];
    for (words, lie) in cases {
        let mut bytes = good.clone();
        match lie {
            Lie::Count(c) => bytes[n - 4..].copy_from_slice(&c.to_le_bytes()),
            Lie::Offset(i, offset) => set_offset(&mut bytes, 3, i, offset),
        }
        let (e, _) = refused(&bytes, 1);
        assert!(e.message.contains(words), "`{words}` not in: {e}");
    }
    // Version 3's dictionary holds 32-bit offsets: read as version 4, it lies.
    let mut bytes = file(3, &[tetra(SINGLE), tetra(SINGLE)]);
    bytes[2] = 4;
    let (e, _) = refused(&bytes, 0);
    assert!(e.message.contains("the dictionary lies"), "{e}");
}

#[test]
fn out_of_range_indices_are_refused() {
    let mut d = tetra(SINGLE);
    d.triangles[2] = [0, 4, 1];
    let (e, _) = refused(&file(4, &[d]), 0);
    assert_eq!(
        e.to_string(),
        "t.serialized: shape 0: triangle 2 uses vertex 4, but there are 4 vertices"
    );
    let mut d = tetra(SINGLE);
    d.positions.clear();
    d.counts = Some((0, 4));
    let (e, _) = refused(&file(4, &[d]), 0);
    assert!(e.message.contains("but there are 0 vertices"), "{e}");
}

#[test]
fn numbers_that_are_not_finite_are_refused() {
    let cases = [
        (
            SINGLE,
            f64::NAN,
            "vertex 1's position [NaN, 0.0, 0.0] is not finite",
        ),
        (
            DOUBLE,
            f64::INFINITY,
            "vertex 1's position [inf, 0.0, 0.0] is not finite",
        ),
        // Finite in double precision, but not in single.
        (
            DOUBLE,
            1e300,
            "vertex 1's position [inf, 0.0, 0.0] is not finite",
        ),
    ];
    for (precision, x, words) in cases {
        let mut d = tetra(precision);
        d.positions[1][0] = x;
        let (e, _) = refused(&file(4, &[d]), 0);
        assert!(e.message.contains(words), "{e}");
    }
    let mut d = tetra(SINGLE | HAS_NORMALS | HAS_UVS | HAS_COLORS);
    d.uvs[3][1] = f64::NAN;
    let (e, _) = refused(&file(4, &[d.clone()]), 0);
    assert!(e.message.contains("vertex 3's texture coordinate"), "{e}");
    d.uvs[3][1] = 0.0;
    d.normals[0][2] = f64::NEG_INFINITY;
    let (e, _) = refused(&file(4, &[d.clone()]), 0);
    assert!(e.message.contains("vertex 0's normal"), "{e}");
    d.normals[0][2] = 1.0;
    d.colors[2][0] = f64::NAN;
    let (e, _) = refused(&file(4, &[d]), 0);
    assert!(e.message.contains("vertex 2's colour"), "{e}");
}

#[test]
fn unknown_formats_versions_and_flags_are_refused() {
    let good = file(4, &[tetra(SINGLE)]);
    let mut bytes = good.clone();
    bytes[0] = 0x1D;
    assert!(
        refused(&bytes, 0)
            .0
            .message
            .contains("not the format id 0x041c")
    );
    let mut bytes = good.clone();
    bytes[2] = 5;
    assert!(
        refused(&bytes, 0)
            .0
            .message
            .contains("version 5 is not read")
    );
    assert!(
        refused(&good[..7], 0)
            .0
            .message
            .contains("7 bytes, too few")
    );
    for (flags, words) in [
        (SINGLE | 0x40, "unknown flags 0x0040"),
        (SINGLE | HAS_TANGENTS, "tangents"),
        (SINGLE | DOUBLE, "both single and double"),
    ] {
        let (e, _) = refused(&file(3, &[tetra(flags)]), 0);
        assert!(e.message.contains(words), "{e}");
    }
    let mut d = tetra(SINGLE);
    let long: &'static str = "n".repeat(MAX_NAME).leak();
    d.name = long;
    let (e, _) = refused(&file(4, &[d]), 0);
    assert!(e.message.contains("name runs past 4096 bytes"), "{e}");
    // A name of MAX_NAME − 1 bytes is read.
    let mut d = tetra(SINGLE);
    d.name = &long[1..];
    assert_eq!(parse(&file(4, &[d]), 0).unwrap().name.len(), MAX_NAME - 1);
    // Not a zlib stream.
    let bytes = file_of(4, &[b"not zlib at all".to_vec()]);
    assert!(refused(&bytes, 0).0.message.contains("corrupt"));
}

#[test]
fn mangled_files_are_read_or_refused_never_a_panic() {
    let good = file(
        4,
        &[
            tetra(SINGLE | HAS_NORMALS | HAS_UVS),
            tetra(DOUBLE | HAS_COLORS),
        ],
    );
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let (mut read, mut refused) = (0, 0);
    for _ in 0..3000 {
        let mut bytes = good.clone();
        for _ in 0..1 + next() % 3 {
            let at = (next() % bytes.len() as u64) as usize;
            bytes[at] = match next() % 3 {
                0 => bytes[at] ^ (1 << (next() % 8)),
                1 => 0xFF,
                _ => next() as u8,
            };
        }
        for index in [0, 1] {
            match parse(&bytes, index) {
                Ok(s) => {
                    s.mesh.validate().unwrap();
                    assert!(s.mesh.positions.iter().all(|p| p.is_finite()));
                    read += 1;
                }
                Err(e) => {
                    assert!(!e.message.is_empty());
                    refused += 1;
                }
            }
        }
    }
    assert!(
        read > 100 && refused > 1000,
        "{read} read, {refused} refused"
    );
}
