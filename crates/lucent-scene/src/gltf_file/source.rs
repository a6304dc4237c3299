//! The bytes around a glTF document: the GLB container, `data:` URIs (base64 or
//! percent-encoded) and percent-encoded file names.
//!
//! Every length read from a file is checked against the bytes that are really there before it
//! is used, so a truncated or hostile file gives a message, never a panic or a huge allocation.

/// The chunks of a binary glTF (`.glb`) file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Glb<'a> {
    /// The JSON chunk: the glTF document.
    pub json: &'a [u8],
    /// The BIN chunk, the data of buffer 0, when the file has one.
    pub bin: Option<&'a [u8]>,
}

const JSON_CHUNK: u32 = 0x4E4F_534A; // "JSON", little-endian
const BIN_CHUNK: u32 = 0x004E_4942; // "BIN\0", little-endian

/// Splits a GLB file: a 12-byte header (`glTF`, version 2, the total length), then chunks of
/// (length, type, data). The first chunk must be JSON; a BIN chunk may follow; chunks of other
/// types are skipped, as the specification asks.
pub(super) fn split_glb(bytes: &[u8]) -> Result<Glb<'_>, String> {
    if bytes.get(..4) != Some(b"glTF") {
        return Err("not a GLB file: it does not start with `glTF`".into());
    }
    let (Some(version), Some(length)) = (word(bytes, 4), word(bytes, 8)) else {
        return Err(format!(
            "the GLB file is truncated: {} bytes, shorter than its 12-byte header",
            bytes.len()
        ));
    };
    if version != 2 {
        return Err(format!(
            "GLB version {version} is not supported (only glTF 2.0)"
        ));
    }
    let length = length as usize;
    if length > bytes.len() {
        return Err(format!(
            "the GLB file is truncated: its header says {length} bytes, the file has {}",
            bytes.len()
        ));
    }
    let data = &bytes[..length];
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    let mut index = 0;
    while at < data.len() {
        let (Some(len), Some(kind)) = (word(data, at), word(data, at + 4)) else {
            return Err(format!(
                "the GLB file is truncated in the header of chunk {index} (byte {at})"
            ));
        };
        let start = at + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&end| end <= data.len())
            .ok_or_else(|| {
                format!(
                    "the GLB file is truncated: chunk {index} claims {len} bytes, {} remain",
                    data.len() - start.min(data.len())
                )
            })?;
        let chunk = &data[start..end];
        match (index, kind) {
            (0, JSON_CHUNK) => json = Some(chunk),
            (0, _) => return Err("the GLB file's first chunk is not JSON".into()),
            (1, BIN_CHUNK) => bin = Some(chunk),
            _ => {} // unknown chunks are ignored; a second BIN chunk has no meaning
        }
        // Chunk lengths are multiples of 4 when the writer pads them; be lenient when it does not.
        at = end.saturating_add(3) & !3;
        index += 1;
    }
    let json = json.ok_or("the GLB file has no JSON chunk")?;
    Ok(Glb { json, bin })
}

/// The little-endian `u32` at byte `at`, if the bytes are there.
fn word(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes(b.try_into().ok()?))
}

/// The bytes of a `data:` URI, given what follows `data:`: `[media type][;base64],payload`.
pub(super) fn decode_data_uri(rest: &str) -> Result<Vec<u8>, String> {
    let (header, payload) = rest
        .split_once(',')
        .ok_or("the data: URI has no `,` before its data")?;
    if header.ends_with(";base64") {
        decode_base64(payload)
    } else {
        percent_decode(payload)
    }
}

/// Standard base64 (RFC 4648; the URL-safe `-` and `_` are accepted too), `=` padding optional.
pub(super) fn decode_base64(text: &str) -> Result<Vec<u8>, String> {
    let text = text.trim_end_matches('=');
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, c) in text.chars().enumerate() {
        let v = match c {
            'A'..='Z' => c as u32 - 'A' as u32,
            'a'..='z' => c as u32 - 'a' as u32 + 26,
            '0'..='9' => c as u32 - '0' as u32 + 52,
            '+' | '-' => 62,
            '/' | '_' => 63,
            _ => {
                return Err(format!(
                    "the base64 data has `{}` at character {i}",
                    c.escape_default()
                ));
            }
        };
        acc = (acc << 6) | v;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    if text.len() % 4 == 1 {
        return Err("the base64 data ends with a lone character".into());
    }
    Ok(out)
}

/// `%XX` escapes replaced by their bytes.
fn percent_decode(text: &str) -> Result<Vec<u8>, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("`{text}` has a `%` not followed by two hex digits"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Ok(out)
}

/// A URI naming a file (`textures/wood%20grain.png`) as the relative file name it encodes.
pub(super) fn file_name_of_uri(uri: &str) -> Result<String, String> {
    if has_scheme(uri) {
        return Err(format!(
            "`{uri}` is not a relative file name (only files beside the glTF file and data: URIs are read)"
        ));
    }
    let decoded = percent_decode(uri)?;
    let name = String::from_utf8(decoded)
        .map_err(|_| format!("`{uri}` does not decode to a UTF-8 file name"))?;
    if name.is_empty() {
        return Err("an empty URI".into());
    }
    Ok(name)
}

/// True for `scheme:...` (RFC 3986: a letter, then letters, digits, `+`, `-`, `.`); a single
/// letter is taken for a Windows drive, not a scheme.
fn has_scheme(uri: &str) -> bool {
    let Some((scheme, _)) = uri.split_once(':') else {
        return false;
    };
    scheme.len() > 1
        && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
        && scheme
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips_known_values() {
        assert_eq!(decode_base64("TWFu").unwrap(), b"Man");
        assert_eq!(decode_base64("TWE=").unwrap(), b"Ma");
        assert_eq!(decode_base64("TQ==").unwrap(), b"M");
        assert_eq!(decode_base64("TQ").unwrap(), b"M");
        assert_eq!(decode_base64("").unwrap(), b"");
        assert_eq!(decode_base64("AAAAgD8=").unwrap(), [0, 0, 0, 0x80, 0x3f]);
        assert!(decode_base64("TW*u").unwrap_err().contains("character 2"));
        assert!(decode_base64("TWFuT").unwrap_err().contains("lone"));
    }

    #[test]
    fn data_uris_and_file_names_decode() {
        assert_eq!(
            decode_data_uri("application/octet-stream;base64,TWFu").unwrap(),
            b"Man"
        );
        assert_eq!(decode_data_uri(",a%20b").unwrap(), b"a b");
        assert!(decode_data_uri("text/plain").is_err());
        assert_eq!(
            file_name_of_uri("tex/wood%20grain.png").unwrap(),
            "tex/wood grain.png"
        );
        assert_eq!(file_name_of_uri("C:/x.bin").unwrap(), "C:/x.bin");
        assert!(file_name_of_uri("https://example.com/x.bin").is_err());
        assert!(file_name_of_uri("a%2").unwrap_err().contains("two hex"));
        assert!(file_name_of_uri("%ff").unwrap_err().contains("UTF-8"));
    }

    fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
        let mut out = b"glTF".to_vec();
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&0u32.to_le_bytes()); // set below
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(&JSON_CHUNK.to_le_bytes());
        out.extend_from_slice(json);
        if let Some(bin) = bin {
            out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
            out.extend_from_slice(&BIN_CHUNK.to_le_bytes());
            out.extend_from_slice(bin);
        }
        let n = out.len() as u32;
        out[8..12].copy_from_slice(&n.to_le_bytes());
        out
    }

    #[test]
    fn glb_chunks_split_and_lengths_are_checked() {
        let file = glb(b"{}  ", Some(&[1, 2, 3, 4]));
        let g = split_glb(&file).unwrap();
        assert_eq!(g.json, b"{}  ");
        assert_eq!(g.bin, Some(&[1u8, 2, 3, 4][..]));
        assert_eq!(split_glb(&glb(b"{}  ", None)).unwrap().bin, None);
        for cut in 0..file.len() {
            assert!(split_glb(&file[..cut]).is_err(), "cut at {cut}");
        }
        let mut lying = file.clone();
        lying[12..16].copy_from_slice(&1000u32.to_le_bytes());
        assert!(
            split_glb(&lying)
                .unwrap_err()
                .contains("chunk 0 claims 1000 bytes")
        );
        let mut v1 = file.clone();
        v1[4] = 1;
        assert!(split_glb(&v1).unwrap_err().contains("version 1"));
    }
}
