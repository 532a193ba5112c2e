//! The byte-level parts of glTF the `gltf` crate would otherwise do for us: splitting a GLB
//! container and decoding buffer/image URIs.
//!
//! They are done here because the crate's versions can panic on truncated input (an
//! unchecked subtraction on the GLB length) and read files behind our back, which would skip
//! the level-folder check and the content hash.

/// The JSON and optional BIN chunk of a GLB file.
pub(crate) struct Glb<'a> {
    pub json: &'a [u8],
    pub bin: Option<&'a [u8]>,
}

pub(crate) fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(b"glTF")
}

/// A chunk's type, its data, and where the next chunk starts.
type Chunk<'a> = ([u8; 4], &'a [u8], usize);

/// Splits a GLB container, checking every length against the bytes actually present.
/// A GLB container of `json` and `bin`: the 12-byte header, the JSON chunk padded with spaces
/// and the BIN chunk padded with zeros, as the spec lays them out (what the loader reads).
pub fn pack_glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |bytes: &[u8], with: u8| {
        let mut out = bytes.to_vec();
        out.resize(bytes.len().next_multiple_of(4), with);
        out
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend(bin);
    out
}

pub(crate) fn split_glb(bytes: &[u8]) -> Result<Glb<'_>, String> {
    let u32_at = |at: usize| -> Option<u32> {
        let b = bytes.get(at..at.checked_add(4)?)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    if bytes.len() < 12 {
        return Err(format!("truncated GLB: {} bytes, shorter than the 12-byte header", bytes.len()));
    }
    let version = u32_at(4).unwrap_or(0);
    if version != 2 {
        return Err(format!("GLB version {version} (only version 2 is supported)"));
    }
    let declared = u32_at(8).unwrap_or(0) as usize;
    if declared > bytes.len() {
        return Err(format!("truncated GLB: header says {declared} bytes but the file has {}", bytes.len()));
    }
    let bytes = &bytes[..declared.max(12)];

    // Returns (type, data, offset of the next chunk).
    let chunk = |at: usize| -> Result<Option<Chunk<'_>>, String> {
        if at >= bytes.len() {
            return Ok(None);
        }
        let (Some(len), Some(ty)) = (u32_at(at), bytes.get(at + 4..at + 8)) else {
            return Err(format!("truncated GLB: chunk header at byte {at} is cut off"));
        };
        let start = at + 8;
        let data = start.checked_add(len as usize).and_then(|end| bytes.get(start..end)).ok_or_else(|| {
            format!("truncated GLB: chunk at byte {at} claims {len} bytes, only {} remain", bytes.len() - start)
        })?;
        // Chunks are padded to 4 bytes; tolerate a missing final pad.
        let next = (start + len as usize).next_multiple_of(4);
        Ok(Some(([ty[0], ty[1], ty[2], ty[3]], data, next)))
    };

    let Some((ty, json, mut at)) = chunk(12)? else {
        return Err("GLB has no JSON chunk".into());
    };
    if &ty != b"JSON" {
        return Err("GLB's first chunk is not JSON".into());
    }
    let mut bin = None;
    while let Some((ty, data, next)) = chunk(at)? {
        // Unknown chunk types must be ignored (glTF 2.0 §4.4.3.3); only the first BIN counts.
        if &ty == b"BIN\0" && bin.is_none() {
            bin = Some(data);
        }
        at = next;
    }
    Ok(Glb { json, bin })
}

/// What a buffer or image `uri` refers to.
pub(crate) enum UriTarget {
    /// The payload of a `data:` URI.
    Embedded(Vec<u8>),
    /// A path relative to the glTF file, percent-decoded.
    File(String),
}

pub(crate) fn parse_uri(uri: &str) -> Result<UriTarget, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (header, payload) = rest.split_once(',').ok_or("malformed data: URI (no ',')")?;
        let bytes = if header.ends_with(";base64") { decode_base64(payload)? } else { percent_decode(payload)? };
        return Ok(UriTarget::Embedded(bytes));
    }
    if let Some((scheme, _)) = uri.split_once(':') {
        let is_scheme = scheme.len() > 1
            && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
            && scheme.chars().all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c));
        if is_scheme {
            return Err(format!("unsupported URI scheme '{scheme}:' (only relative paths and data: URIs)"));
        }
    }
    let path = String::from_utf8(percent_decode(uri)?).map_err(|_| format!("URI '{uri}' is not UTF-8 once decoded"))?;
    Ok(UriTarget::File(path))
}

fn percent_decode(s: &str) -> Result<Vec<u8>, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok());
            let v = hex
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad percent-escape in URI '{s}'"))?;
            out.push(v);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Ok(out)
}

/// Standard base64 with padding: how a glTF embeds a file in a `data:` URI (what the loader's
/// decoder reads back).
pub fn encode_base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = chunk.iter().enumerate().fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
        for i in 0..4 {
            out.push(if i <= chunk.len() { ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char } else { '=' });
        }
    }
    out
}

/// Standard or URL-safe base64, padding optional.
fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
    let s = s.trim_end_matches('=');
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, c) in s.bytes().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return Err(format!("invalid base64 character {:?} at position {i} of a data: URI", c as char)),
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    if s.len() % 4 == 1 {
        return Err("truncated base64 in a data: URI".into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGVsbG8").unwrap(), b"hello");
        assert_eq!(decode_base64("AAECAw==").unwrap(), [0, 1, 2, 3]);
        assert!(decode_base64("a").is_err());
        assert!(decode_base64("a*bc").is_err());
        for bytes in [&b""[..], b"h", b"he", b"hel", b"hello", &[0, 255, 254, 1]] {
            assert_eq!(decode_base64(&encode_base64(bytes)).unwrap(), bytes);
        }
        assert_eq!(encode_base64(b"hello"), "aGVsbG8=");
    }

    #[test]
    fn uris() {
        assert!(matches!(parse_uri("my%20mesh.bin"), Ok(UriTarget::File(p)) if p == "my mesh.bin"));
        assert!(parse_uri("http://example.com/x.bin").is_err());
        assert!(
            matches!(parse_uri("data:application/octet-stream;base64,AAEC"), Ok(UriTarget::Embedded(b)) if b == [0, 1, 2])
        );
    }

    #[test]
    fn glb_lengths_are_checked() {
        assert!(split_glb(b"glTF").is_err());
        let mut glb = b"glTF".to_vec();
        glb.extend(2u32.to_le_bytes());
        glb.extend(8u32.to_le_bytes()); // declared shorter than the header: must not underflow
        assert!(split_glb(&glb).is_err());
    }
}
