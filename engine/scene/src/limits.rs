//! Sizes beyond which input is refused as absurd.
//!
//! A level is hand-made content for a real-time renderer; anything past these bounds is either
//! corrupt or hostile, and refusing it early beats an out-of-memory abort halfway through.

/// Most triangles a whole scene may have after instancing.
pub const MAX_TRIANGLES: usize = 50_000_000;
/// Most vertices one accessor / OBJ mesh may declare (three per triangle, un-shared).
pub const MAX_VERTICES: usize = 3 * MAX_TRIANGLES;
/// Widest or tallest texture accepted, in pixels (the common GPU 2D texture limit).
pub const MAX_TEXTURE_SIZE: u32 = 16384;
/// Largest single file read (glTF buffer, image, OBJ...), in bytes.
pub const MAX_FILE_BYTES: u64 = 4 << 30;
/// Deepest node hierarchy walked; deeper is treated as corrupt rather than risking the stack.
pub const MAX_NODE_DEPTH: usize = 1024;
