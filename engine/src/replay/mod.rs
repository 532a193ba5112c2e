//! The `.replay` container: a header saying what a recording needs to be re-simulated, then one
//! fixed-size input command per tick with the state hash the simulation reached after it
//! (Doom's demo model: what is recorded is what was simulated, never timestamps).
//!
//! The engine treats commands as opaque bytes; the game defines what they mean. Layout of
//! format version 1, all integers little-endian:
//!
//! | bytes     | field                                                              |
//! |-----------|--------------------------------------------------------------------|
//! | 8         | magic `HLREPLAY`                                                   |
//! | 4         | format version (u32) = 1                                           |
//! | 4         | tick rate in Hz (u32)                                              |
//! | 8         | RNG seed (u64)                                                     |
//! | 8         | level content hash (u64, `scene::Level::content_hash`)             |
//! | 2 + n     | level id: length (u16), UTF-8                                      |
//! | 2         | number of settings (u16), then per setting: key and value, each   |
//! |           | length (u16) + UTF-8                                               |
//! | 2         | command size C in bytes (u16)                                      |
//! | 4         | tick count N (u32)                                                 |
//! | N·(C + 8) | per tick: the command (C bytes), then the state hash after it (u64)|
//! | 8         | FNV-1a 64 of every byte before it                                  |

mod error;
mod reader;
mod writer;

pub use error::{ReplayError, ReplayErrorKind};
pub use reader::Replay;
pub use writer::ReplayWriter;

/// First bytes of every replay file.
pub const MAGIC: [u8; 8] = *b"HLREPLAY";
/// The format version this build writes and the only one it reads.
pub const FORMAT_VERSION: u32 = 1;
/// Bounds that keep a damaged header from asking for absurd amounts of memory.
pub const MAX_COMMAND_SIZE: usize = 1024;
pub const MAX_SETTINGS: usize = 1024;

/// Everything about a recording except its ticks.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReplayHeader {
    /// Which level was played: the game's name for it (e.g. its folder name).
    pub level_id: String,
    /// The level's content hash at recording time; a replay of a changed level is refused.
    pub level_hash: u64,
    pub tick_rate: u32,
    pub seed: u64,
    /// Settings the recording was made with, as ordered key/value text.
    pub settings: Vec<(String, String)>,
    /// Bytes per tick command.
    pub command_size: usize,
}

impl ReplayHeader {
    pub fn setting(&self, key: &str) -> Option<&str> {
        self.settings.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }
}

/// The checksum that ends a replay file: FNV-1a 64 of every byte before it.
pub fn checksum(bytes: &[u8]) -> u64 {
    let mut h = scene::Fnv1a::default();
    h.write(bytes);
    h.finish()
}

#[cfg(test)]
mod tests;
