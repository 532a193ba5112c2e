use std::path::Path;

use super::{checksum, ReplayError, ReplayErrorKind, ReplayHeader, FORMAT_VERSION, MAGIC};

/// Builds a replay in memory, one tick at a time, and writes it out whole.
#[derive(Clone, Debug)]
pub struct ReplayWriter {
    header: ReplayHeader,
    ticks: Vec<u8>,
    count: u32,
}

impl ReplayWriter {
    pub fn new(header: ReplayHeader) -> Self {
        assert!(
            (1..=super::MAX_COMMAND_SIZE).contains(&header.command_size),
            "command size {} out of range",
            header.command_size
        );
        assert!(header.settings.len() <= super::MAX_SETTINGS, "too many settings");
        Self { header, ticks: Vec::new(), count: 0 }
    }

    pub fn header(&self) -> &ReplayHeader {
        &self.header
    }

    /// Appends one simulated tick: the command it consumed and the state hash after it.
    pub fn push(&mut self, command: &[u8], state_hash: u64) {
        assert_eq!(command.len(), self.header.command_size, "every command has the header's size");
        self.ticks.extend_from_slice(command);
        self.ticks.extend_from_slice(&state_hash.to_le_bytes());
        self.count += 1;
    }

    pub fn tick_count(&self) -> u32 {
        self.count
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let h = &self.header;
        let mut out = Vec::with_capacity(64 + self.ticks.len());
        out.extend_from_slice(&MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.extend_from_slice(&h.tick_rate.to_le_bytes());
        out.extend_from_slice(&h.seed.to_le_bytes());
        out.extend_from_slice(&h.level_hash.to_le_bytes());
        put_str(&mut out, &h.level_id);
        out.extend_from_slice(&(h.settings.len() as u16).to_le_bytes());
        for (k, v) in &h.settings {
            put_str(&mut out, k);
            put_str(&mut out, v);
        }
        out.extend_from_slice(&(h.command_size as u16).to_le_bytes());
        out.extend_from_slice(&self.count.to_le_bytes());
        out.extend_from_slice(&self.ticks);
        let sum = checksum(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    /// Writes the file through a temporary beside it, so an interrupted write never leaves a
    /// half replay under the real name (nor destroys an older one).
    pub fn save(&self, path: &Path) -> Result<(), ReplayError> {
        let io = |e| ReplayError::new(path, ReplayErrorKind::Io(e));
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".partial");
        std::fs::write(&tmp, self.to_bytes()).map_err(io)?;
        std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io(e)
        })
    }
}

/// Strings longer than a u16 length are cut at a character boundary (ids and settings are short).
fn put_str(out: &mut Vec<u8>, s: &str) {
    let mut end = s.len().min(u16::MAX as usize);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    out.extend_from_slice(&(end as u16).to_le_bytes());
    out.extend_from_slice(&s.as_bytes()[..end]);
}
