use std::path::Path;

use super::{checksum, ReplayError, ReplayErrorKind, ReplayHeader, FORMAT_VERSION, MAGIC};

/// A replay file, checked and in memory.
#[derive(Clone, Debug)]
pub struct Replay {
    pub header: ReplayHeader,
    commands: Vec<u8>,
    hashes: Vec<u64>,
}

impl Replay {
    pub fn read(path: &Path) -> Result<Self, ReplayError> {
        let bytes = scene::limits::read_file(path, scene::limits::MAX_REPLAY_BYTES)
            .map_err(|e| ReplayError::new(path, ReplayErrorKind::Io(e)))?;
        Self::parse(&bytes, path)
    }

    /// Parses and checks a whole file; `path` only names it in errors.
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, ReplayError> {
        let err = |kind| ReplayError::new(path, kind);
        let mut r = Cursor { bytes, at: 0 };
        let truncated = |r: &Cursor| ReplayErrorKind::Truncated { needed: r.at as u64 + 1, found: bytes.len() as u64 };
        if bytes.len() < MAGIC.len() || bytes[..MAGIC.len()] != MAGIC {
            return Err(err(ReplayErrorKind::NotAReplay));
        }
        r.at = MAGIC.len();
        let version = r.u32().ok_or_else(|| err(truncated(&r)))?;
        if version != FORMAT_VERSION {
            return Err(err(ReplayErrorKind::UnknownVersion(version)));
        }
        let header = read_header(&mut r).map_err(|kind| err(kind.unwrap_or_else(|| truncated(&r))))?;
        let count = r.u32().ok_or_else(|| err(truncated(&r)))? as u64;
        let per_tick = header.command_size as u64 + 8;
        let expected = r.at as u64 + count * per_tick + 8;
        let found = bytes.len() as u64;
        if found < expected {
            return Err(err(ReplayErrorKind::Truncated { needed: expected, found }));
        }
        if found > expected {
            return Err(err(ReplayErrorKind::TrailingBytes { expected, found }));
        }
        let body_end = bytes.len() - 8;
        let stored = u64::from_le_bytes(bytes[body_end..].try_into().expect("8 bytes"));
        let computed = checksum(&bytes[..body_end]);
        if stored != computed {
            return Err(err(ReplayErrorKind::ChecksumMismatch { stored, computed }));
        }
        let size = header.command_size;
        let mut commands = Vec::with_capacity(count as usize * size);
        let mut hashes = Vec::with_capacity(count as usize);
        for tick in bytes[r.at..body_end].chunks_exact(size + 8) {
            commands.extend_from_slice(&tick[..size]);
            hashes.push(u64::from_le_bytes(tick[size..].try_into().expect("8 bytes")));
        }
        Ok(Self { header, commands, hashes })
    }

    pub fn tick_count(&self) -> usize {
        self.hashes.len()
    }

    /// The command simulated on tick `i` (0-based).
    pub fn command(&self, i: usize) -> &[u8] {
        let size = self.header.command_size;
        &self.commands[i * size..(i + 1) * size]
    }

    /// The state hash recorded after tick `i`.
    pub fn state_hash(&self, i: usize) -> u64 {
        self.hashes[i]
    }
}

/// Reads the header fields after the version; `Err(None)` means the bytes ran out.
fn read_header(r: &mut Cursor) -> Result<ReplayHeader, Option<ReplayErrorKind>> {
    let bad = |what: String| Some(ReplayErrorKind::BadHeader(what));
    let tick_rate = r.u32().ok_or(None)?;
    if !(1..=1000).contains(&tick_rate) {
        return Err(bad(format!("tick rate {tick_rate} Hz is outside 1..=1000")));
    }
    let seed = r.u64().ok_or(None)?;
    let level_hash = r.u64().ok_or(None)?;
    let level_id = r.str().ok_or(None)?.map_err(|_| bad("the level id is not UTF-8".into()))?;
    let n = r.u16().ok_or(None)? as usize;
    if n > super::MAX_SETTINGS {
        return Err(bad(format!("{n} settings (at most {})", super::MAX_SETTINGS)));
    }
    let mut settings = Vec::with_capacity(n);
    for i in 0..n {
        let key = r.str().ok_or(None)?.map_err(|_| bad(format!("setting {i}'s name is not UTF-8")))?;
        let value = r.str().ok_or(None)?.map_err(|_| bad(format!("setting '{key}' is not UTF-8")))?;
        settings.push((key, value));
    }
    let command_size = r.u16().ok_or(None)? as usize;
    if !(1..=super::MAX_COMMAND_SIZE).contains(&command_size) {
        return Err(bad(format!("command size {command_size} is outside 1..={}", super::MAX_COMMAND_SIZE)));
    }
    Ok(ReplayHeader { level_id, level_hash, tick_rate, seed, settings, command_size })
}

struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn take(&mut self, n: usize) -> Option<&[u8]> {
        let s = self.bytes.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(s)
    }
    fn u16(&mut self) -> Option<u16> {
        self.take(2).map(|b| u16::from_le_bytes(b.try_into().expect("2 bytes")))
    }
    fn u32(&mut self) -> Option<u32> {
        self.take(4).map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
    }
    fn u64(&mut self) -> Option<u64> {
        self.take(8).map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")))
    }
    /// A u16-length-prefixed string: None when the bytes run out, Some(Err) when not UTF-8.
    fn str(&mut self) -> Option<Result<String, std::string::FromUtf8Error>> {
        let n = self.u16()? as usize;
        Some(String::from_utf8(self.take(n)?.to_vec()))
    }
}
