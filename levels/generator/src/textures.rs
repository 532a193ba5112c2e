//! Procedural base colour textures: plaster, tiles, brick, floorboards, flagstones and concrete,
//! and one metallic-roughness texture (puddles), written as small greyscale PNGs beside a
//! level's scene.
//!
//! They are detail maps: grey values near white with darker joints, grain and mottling, which a
//! material's base colour factor tints (so one brick texture serves yellow and terracotta brick).
//! Every texture tiles seamlessly (the sampler repeats): each pattern's period divides the image
//! and the noise is periodic. Values are sRGB-encoded, as glTF base colour textures are. The
//! output depends on nothing but the code: integer hashing, no random generator state.

use std::io::Cursor;

/// Edge of every texture, pixels.
pub const SIZE: u32 = 256;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum TextureKind {
    /// Smooth, faintly mottled plaster.
    Plaster,
    /// 4 x 4 square tiles (25 cm on a 1 m repeat) with grout joints.
    Tiles,
    /// Running-bond brick: 16 courses, four bricks a course, every other course offset by half.
    Brick,
    /// Eight boards across (25 cm on a 2 m repeat) with end joints and grain along them.
    Planks,
    /// Staggered flagstones, two to a row, four rows (1 m x 0.5 m on a 2 m repeat).
    Stone,
    /// Cast concrete: broad stains, pores and a few hairline cracks.
    Concrete,
    /// Not a colour: a linear roughness multiplier (glTF's metallicRoughnessTexture, read from
    /// green; blue, the same grey, multiplies a metallic factor of 0). Dry stone 0.8, puddles
    /// and damp joints down to 0.15, on [`TextureKind::Stone`]'s 2 m repeat.
    Puddles,
}

impl TextureKind {
    pub const ALL: [TextureKind; 7] = [
        TextureKind::Plaster,
        TextureKind::Tiles,
        TextureKind::Brick,
        TextureKind::Planks,
        TextureKind::Stone,
        TextureKind::Concrete,
        TextureKind::Puddles,
    ];

    /// Whether the texture is a base colour (sRGB detail map) rather than a roughness map.
    pub fn is_base_colour(self) -> bool {
        self != TextureKind::Puddles
    }

    pub fn name(self) -> &'static str {
        match self {
            TextureKind::Plaster => "plaster",
            TextureKind::Tiles => "tiles",
            TextureKind::Brick => "brick",
            TextureKind::Planks => "planks",
            TextureKind::Stone => "stone",
            TextureKind::Concrete => "concrete",
            TextureKind::Puddles => "puddles",
        }
    }

    /// The PNG's file name in the level folder.
    pub fn file_name(self) -> String {
        format!("{}.png", self.name())
    }

    /// The texture's grey values (sRGB-encoded for base colours, linear for roughness), row by
    /// row from the top left.
    pub fn pixels(self) -> Vec<u8> {
        let f: fn(u32, u32) -> f64 = match self {
            TextureKind::Plaster => plaster,
            TextureKind::Tiles => tiles,
            TextureKind::Brick => brick,
            TextureKind::Planks => planks,
            TextureKind::Stone => stone,
            TextureKind::Concrete => concrete,
            TextureKind::Puddles => puddles,
        };
        (0..SIZE * SIZE).map(|i| (f(i % SIZE, i / SIZE).clamp(0.0, 1.0) * 255.0).round() as u8).collect()
    }

    /// The texture as an 8-bit greyscale PNG.
    pub fn png(self) -> Vec<u8> {
        let image = image::GrayImage::from_raw(SIZE, SIZE, self.pixels()).expect("SIZE x SIZE pixels");
        let mut bytes = Cursor::new(Vec::new());
        image.write_to(&mut bytes, image::ImageFormat::Png).expect("PNG encoding into memory");
        bytes.into_inner()
    }
}

/// A hash of integer coordinates and a seed to [0, 1) (a few rounds of a 32-bit integer mix).
fn hash(x: i64, y: i64, seed: u32) -> f64 {
    let mut h =
        (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841) ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    f64::from(h) / 4_294_967_296.0
}

/// Value noise in [0, 1) at pixel (x, y) on a lattice of `cx` x `cy` cells over the texture,
/// wrapping at its edges (so it tiles), smoothly interpolated.
fn noise(x: f64, y: f64, cx: u32, cy: u32, seed: u32) -> f64 {
    let (u, v) = (x / f64::from(SIZE) * f64::from(cx), y / f64::from(SIZE) * f64::from(cy));
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = (u - i, v - j);
    let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
    let (su, sv) = (smooth(fu), smooth(fv));
    let at = |di: i64, dj: i64| {
        let a = (i as i64 + di).rem_euclid(i64::from(cx));
        let b = (j as i64 + dj).rem_euclid(i64::from(cy));
        hash(a, b, seed)
    };
    let top = at(0, 0) + (at(1, 0) - at(0, 0)) * su;
    let bottom = at(0, 1) + (at(1, 1) - at(0, 1)) * su;
    top + (bottom - top) * sv
}

/// Fractal noise: `octaves` layers from `cells` cells up, each twice as fine and half as strong,
/// centred on 0 (roughly within ±0.5).
fn fbm(x: f64, y: f64, cells: u32, octaves: u32, seed: u32) -> f64 {
    let (mut sum, mut amplitude, mut total) = (0.0, 1.0, 0.0);
    for o in 0..octaves {
        let c = cells << o;
        sum += amplitude * (noise(x, y, c, c, seed.wrapping_add(o * 7919)) - 0.5);
        total += amplitude;
        amplitude *= 0.5;
    }
    sum / total
}

/// Per-pixel grain, centred on 0, within ±0.5.
fn grain(x: u32, y: u32, seed: u32) -> f64 {
    hash(i64::from(x), i64::from(y), seed) - 0.5
}

/// Whether local coordinates (lx, ly) of a `w` x `h` block whose first `joint` rows and
/// columns are its joint lie on the block's outermost ring of pixels (its bevel).
fn on_bevel(lx: u32, ly: u32, w: u32, h: u32, joint: u32) -> bool {
    lx == joint || ly == joint || lx == w - 1 || ly == h - 1
}

fn plaster(x: u32, y: u32) -> f64 {
    let (fx, fy) = (f64::from(x), f64::from(y));
    0.93 + 0.07 * fbm(fx, fy, 4, 5, 11) + 0.025 * grain(x, y, 12)
}

fn tiles(x: u32, y: u32) -> f64 {
    const TILE: u32 = 64;
    const GROUT: u32 = 3;
    let (tx, ty) = (x / TILE, y / TILE);
    let (lx, ly) = (x % TILE, y % TILE);
    let (fx, fy) = (f64::from(x), f64::from(y));
    if lx < GROUT || ly < GROUT {
        return 0.62 + 0.05 * fbm(fx, fy, 32, 2, 21) + 0.03 * grain(x, y, 22);
    }
    let tone = 0.95 + 0.04 * (hash(i64::from(tx), i64::from(ty), 23) - 0.5);
    let bevel = if on_bevel(lx, ly, TILE, TILE, GROUT) { -0.06 } else { 0.0 };
    tone + bevel + 0.025 * fbm(fx, fy, 8, 3, 24) + 0.012 * grain(x, y, 25)
}

/// A running bond (bricks, flagstones): courses `course` pixels high of blocks `length` long,
/// every other course shifted by half a block. The block's column and course, and the pixel's
/// place within the block.
fn running_bond(x: u32, y: u32, course: u32, length: u32) -> (u32, u32, u32, u32) {
    let row = y / course;
    let shift = if row % 2 == 1 { length / 2 } else { 0 };
    let bx = (x + shift) % SIZE;
    (bx / length, row, bx % length, y % course)
}

fn brick(x: u32, y: u32) -> f64 {
    const COURSE: u32 = 16;
    const LENGTH: u32 = 64;
    const MORTAR: u32 = 2;
    let (col, row, lx, ly) = running_bond(x, y, COURSE, LENGTH);
    let (fx, fy) = (f64::from(x), f64::from(y));
    if ly < MORTAR || lx < MORTAR {
        return 0.58 + 0.06 * fbm(fx, fy, 32, 2, 31) + 0.05 * grain(x, y, 32);
    }
    let tone = 0.9 + 0.12 * (hash(i64::from(col), i64::from(row), 33) - 0.5);
    let bevel = if on_bevel(lx, ly, LENGTH, COURSE, MORTAR) { -0.05 } else { 0.0 };
    tone + bevel + 0.05 * fbm(fx, fy, 16, 3, 34) + 0.04 * grain(x, y, 35)
}

fn planks(x: u32, y: u32) -> f64 {
    const BOARD: u32 = 32;
    const LENGTH: u32 = 128;
    let board = y / BOARD;
    let ly = y % BOARD;
    // Each board's end joints: one every LENGTH pixels from its own offset.
    let offset = (hash(i64::from(board), 0, 41) * f64::from(SIZE)) as u32;
    let along = (x + SIZE - offset) % SIZE;
    let piece = along / LENGTH;
    let (fx, fy) = (f64::from(x), f64::from(y));
    if ly == 0 || along.is_multiple_of(LENGTH) {
        return 0.42 + 0.04 * grain(x, y, 42);
    }
    let tone = 0.86 + 0.1 * (hash(i64::from(board), i64::from(piece), 43) - 0.5);
    // Grain: noise stretched along the board (few cells along x, many across), and rings.
    let streaks = noise(fx, fy, 4, 64, 44 + board) - 0.5;
    let rings = (fy * 0.9 + 6.0 * noise(fx, fy, 8, 8, 45)).sin();
    let edge = if ly == 1 || ly == BOARD - 1 { -0.05 } else { 0.0 };
    tone + edge + 0.12 * streaks + 0.025 * rings + 0.02 * grain(x, y, 46)
}

/// The flagstones' bond, shared by [`stone`] and the [`puddles`] lying in its joints.
const FLAGSTONE_ROW: u32 = 64;
const FLAGSTONE_LENGTH: u32 = 128;
const FLAGSTONE_JOINT: u32 = 2;

fn stone(x: u32, y: u32) -> f64 {
    let (col, row, lx, ly) = running_bond(x, y, FLAGSTONE_ROW, FLAGSTONE_LENGTH);
    let (fx, fy) = (f64::from(x), f64::from(y));
    if lx < FLAGSTONE_JOINT || ly < FLAGSTONE_JOINT {
        return 0.5 + 0.06 * fbm(fx, fy, 32, 2, 51) + 0.04 * grain(x, y, 52);
    }
    let tone = 0.86 + 0.12 * (hash(i64::from(col), i64::from(row), 53) - 0.5);
    let bevel = if on_bevel(lx, ly, FLAGSTONE_LENGTH, FLAGSTONE_ROW, FLAGSTONE_JOINT) { -0.06 } else { 0.0 };
    tone + bevel + 0.1 * fbm(fx, fy, 4, 5, 54 + row * 2 + col) + 0.03 * grain(x, y, 55)
}

fn concrete(x: u32, y: u32) -> f64 {
    let (fx, fy) = (f64::from(x), f64::from(y));
    let stains = 0.1 * fbm(fx, fy, 2, 4, 61);
    // Pores: a few dark pixels where the fine hash is extreme.
    let pore = if hash(i64::from(x), i64::from(y), 62) > 0.985 { -0.12 } else { 0.0 };
    // Hairline cracks: where a low-frequency noise crosses one level, a thin dark line.
    let crack = if (noise(fx, fy, 3, 3, 63) - 0.5).abs() < 0.006 { -0.1 } else { 0.0 };
    0.88 + stains + pore + crack + 0.04 * fbm(fx, fy, 16, 2, 64) + 0.03 * grain(x, y, 65)
}

/// Roughness over [`stone`]'s flagstones: wet joints and puddles in the low spots.
fn puddles(x: u32, y: u32) -> f64 {
    let (_, _, lx, ly) = running_bond(x, y, FLAGSTONE_ROW, FLAGSTONE_LENGTH);
    let (fx, fy) = (f64::from(x), f64::from(y));
    // Water stands in the joints and their bevels.
    if lx <= FLAGSTONE_JOINT || ly <= FLAGSTONE_JOINT {
        return 0.2;
    }
    // Puddles: where broad noise is high, smoothly from dry (0.8) to standing water (0.15).
    let wet = ((fbm(fx, fy, 3, 4, 71) - 0.08) / 0.12).clamp(0.0, 1.0);
    0.8 - 0.65 * wet * wet * (3.0 - 2.0 * wet) + 0.03 * grain(x, y, 72)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn srgb_to_linear(v: f64) -> f64 {
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    }

    #[test]
    fn textures_are_deterministic_small_pngs() {
        for kind in TextureKind::ALL {
            let png = kind.png();
            assert_eq!(png, kind.png(), "{kind:?}");
            assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
            assert!(png.len() < 96 * 1024, "{kind:?}: {} bytes", png.len());
            let decoded = image::load_from_memory(&png).unwrap().to_luma8();
            assert_eq!((decoded.width(), decoded.height()), (SIZE, SIZE));
            assert_eq!(decoded.into_raw(), kind.pixels());
        }
    }

    /// Near white on average (the factor gives the colour) but not flat: each has detail.
    #[test]
    fn textures_are_bright_detail_maps() {
        for kind in TextureKind::ALL.into_iter().filter(|k| k.is_base_colour()) {
            let px = kind.pixels();
            let linear: Vec<f64> = px.iter().map(|&v| srgb_to_linear(f64::from(v) / 255.0)).collect();
            let mean = linear.iter().sum::<f64>() / linear.len() as f64;
            assert!((0.6..=0.95).contains(&mean), "{kind:?}: mean linear value {mean}");
            let (lo, hi) = (px.iter().min().unwrap(), px.iter().max().unwrap());
            assert!(hi - lo >= 12, "{kind:?}: flat ({lo}..{hi})");
        }
    }

    /// The puddles are a roughness map: mostly dry, some water (below 0.3), nothing smoother than
    /// the renderer draws (0.089) or rougher than 1.
    #[test]
    fn puddles_are_a_mostly_dry_roughness_map() {
        let px = TextureKind::Puddles.pixels();
        let values: Vec<f64> = px.iter().map(|&v| f64::from(v) / 255.0).collect();
        let wet = values.iter().filter(|&&v| v < 0.3).count() as f64 / values.len() as f64;
        assert!((0.1..=0.45).contains(&wet), "wet fraction {wet}");
        assert!(values.iter().all(|&v| (0.1..=0.9).contains(&v)));
    }

    /// The texture repeats without a seam: the jump across its left/right and top/bottom edges
    /// is no bigger than the jumps between neighbouring columns and rows inside it (give or take
    /// the grain's chance: a tenth).
    #[test]
    fn textures_tile_seamlessly() {
        let n = SIZE as usize;
        for kind in TextureKind::ALL {
            let px = kind.pixels();
            let at = |x: usize, y: usize| f64::from(px[y * n + x]);
            let column_jump = |x0: usize, x1: usize| (0..n).map(|y| (at(x0, y) - at(x1, y)).abs()).sum::<f64>();
            let row_jump = |y0: usize, y1: usize| (0..n).map(|x| (at(x, y0) - at(x, y1)).abs()).sum::<f64>();
            let max_col = (0..n - 1).map(|x| column_jump(x, x + 1)).fold(0.0, f64::max);
            let max_row = (0..n - 1).map(|y| row_jump(y, y + 1)).fold(0.0, f64::max);
            assert!(column_jump(n - 1, 0) <= 1.1 * max_col, "{kind:?}: seam between the right and left edges");
            assert!(row_jump(n - 1, 0) <= 1.1 * max_row, "{kind:?}: seam between the bottom and top edges");
        }
    }
}
