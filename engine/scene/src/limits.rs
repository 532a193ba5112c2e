//! Sizes beyond which input is refused as absurd, and the one way files are read into memory.
//!
//! A level is hand-made content for a real-time renderer; anything past these bounds is either
//! corrupt or hostile, and refusing it early beats an out-of-memory abort halfway through.
//! Every reader of a user's file (levels, replays, input scripts, the config) goes through
//! [`read_file`] with one of these limits.

use std::io::Read;
use std::path::Path;

/// Most triangles a whole scene may have after instancing.
pub const MAX_TRIANGLES: usize = 50_000_000;
/// Most vertices one accessor / OBJ mesh may declare (three per triangle, un-shared).
pub const MAX_VERTICES: usize = 3 * MAX_TRIANGLES;
/// Widest or tallest texture accepted, in pixels: the 2D texture size every wgpu device
/// supports (its default limit), so a texture that loads can always be uploaded.
pub const MAX_TEXTURE_SIZE: u32 = 8192;
/// Most bytes of decoded textures one scene may hold (RGBA8): four of the largest, 8192².
pub const MAX_SCENE_TEXTURE_BYTES: u64 = 1 << 30;
/// Widest or tallest headlamp profile image, in pixels. The profile is kept as floats in
/// several copies on its way to the GPU (16 bytes a pixel each), and the lamp's own spot
/// profile is 256² texels: a larger picture only costs memory.
pub const MAX_PROFILE_SIZE: u32 = 2048;
/// Widest or tallest frame the command line renders (`--size`); the device may allow less.
pub const MAX_OUTPUT_SIZE: u32 = 16384;
/// Largest single file of a level read (glTF buffer, image, OBJ...), in bytes.
pub const MAX_FILE_BYTES: u64 = 4 << 30;
/// Largest text file read: level.toml, the config, an input script.
pub const MAX_TEXT_BYTES: u64 = 16 << 20;
/// Largest replay file read: a 5-hour game at 60 ticks a second takes about 20 MiB.
pub const MAX_REPLAY_BYTES: u64 = 256 << 20;
/// Most ticks an input script may run: 5 hours at 60 ticks a second.
pub const MAX_SCRIPT_TICKS: u64 = 5 * 3600 * 60;

/// Reads a whole file of at most `limit` bytes.
///
/// Refused without reading: a path that is not a regular file — a FIFO, a device such as
/// `/dev/zero` or `/dev/urandom`, a socket or a folder — whose reading might never end (or,
/// for a FIFO, never start), and a file larger than `limit`. A file that grows while it is
/// read is cut at `limit` + 1 bytes and refused, so no read is unbounded.
pub fn read_file(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let what = if meta.is_dir() { "a folder" } else { "not a regular file (a FIFO, device or socket)" };
        return Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, format!("is {what}, expected a file")));
    }
    let too_large = |size: u64| {
        std::io::Error::new(std::io::ErrorKind::InvalidData, format!("is {size} bytes, more than the {limit} read"))
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)?.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read_file`] as UTF-8 text.
pub fn read_text(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_file(path, limit)?)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, format!("is not UTF-8 text: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_folders_and_large_files_are_refused_without_reading() {
        #[cfg(unix)]
        for device in ["/dev/zero", "/dev/urandom"] {
            let e = read_file(Path::new(device), MAX_TEXT_BYTES).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{device}: {e}");
        }
        let dir = std::env::temp_dir().join(format!("headlamp-read-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        assert!(read_file(&dir, 10).unwrap_err().to_string().contains("is a folder"));
        let file = dir.join("ten.txt");
        std::fs::write(&file, "0123456789").unwrap();
        assert_eq!(read_file(&file, 10).unwrap(), b"0123456789");
        assert!(read_file(&file, 9).unwrap_err().to_string().contains("is 10 bytes, more than the 9 read"));
        std::fs::write(&file, [0xff, 0xfe]).unwrap();
        assert!(read_text(&file, 10).unwrap_err().to_string().contains("not UTF-8"));
        #[cfg(unix)]
        {
            // A FIFO with no writer would block the open forever: refused before opening.
            let fifo = dir.join("fifo");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success());
            assert!(made, "mkfifo is part of coreutils");
            assert!(read_file(&fifo, 10).unwrap_err().to_string().contains("not a regular file"));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
