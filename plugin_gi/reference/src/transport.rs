//! From lit patches to the light they reflect onto receivers: E = Σ Φ·cos_s·cos_r / (π d²)
//! over every lit patch, the point form, except within [`NEAR_EDGES`] patch edges of the
//! receiver, where each patch is integrated exactly: Lambert's point-to-polygon form factor of
//! the patch triangle clipped to the receiver's hemisphere (as shaders/gi/reference.wgsl does
//! for its texel footprints). No clustering, no cutoff, no clamp: the far sum runs over all the
//! lit patches, O(receivers × patches), in chunks of eight the compiler turns into SIMD.

use std::collections::HashMap;
use std::f64::consts::PI;

use engine::glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::world::LitPatch;

/// The near field's radius, in patch edges (the `max_edge` the patches were cut with): the
/// point form's error on a patch of size s at distance d goes as (s/d)², about 1/36 of a
/// patch's own share at the boundary.
pub const NEAR_EDGES: f32 = 6.0;

/// A point lit by the patches: where, which way its surface faces (unit; zero where there is
/// no surface) and its diffuse albedo ρ (for radiance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    pub position: Vec3,
    pub normal: Vec3,
    pub albedo: Vec3,
}

/// Patches a SIMD row: each field one lane per patch.
const LANES: usize = 8;

/// Eight patches, structure of arrays: position, lit normal, and flux / π per channel.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
struct Chunk {
    px: [f32; LANES],
    py: [f32; LANES],
    pz: [f32; LANES],
    nx: [f32; LANES],
    ny: [f32; LANES],
    nz: [f32; LANES],
    fr: [f32; LANES],
    fg: [f32; LANES],
    fb: [f32; LANES],
}

/// Chunks summed in f32 lanes before the lanes go into the f64 total.
const CHUNKS_PER_BLOCK: usize = 256;

/// Lit patches ready to light receivers.
pub struct LitPatches {
    patches: Vec<LitPatch>,
    chunks: Vec<Chunk>,
    near_radius: f32,
    /// The patches by grid cell (cells `near_radius` wide): cell → range of `by_cell`.
    cells: HashMap<[i32; 3], (u32, u32)>,
    by_cell: Vec<u32>,
}

fn cell_of(p: Vec3, size: f32) -> [i32; 3] {
    (p / size).floor().as_ivec3().to_array()
}

impl LitPatches {
    /// `patches` cut with edges of at most `max_edge`: their near field reaches
    /// `NEAR_EDGES × max_edge`.
    pub fn new(patches: &[LitPatch], max_edge: f32) -> Self {
        let near_radius = NEAR_EDGES * max_edge;
        // Padding lanes: far away, no normal, no flux; they add exactly 0.
        let pad = Chunk { px: [1e6; LANES], ..Chunk::default() };
        let mut chunks = vec![pad; patches.len().div_ceil(LANES)];
        for (i, p) in patches.iter().enumerate() {
            let (c, l) = (&mut chunks[i / LANES], i % LANES);
            let f = p.flux / std::f32::consts::PI;
            (c.px[l], c.py[l], c.pz[l]) = p.patch.centre.into();
            (c.nx[l], c.ny[l], c.nz[l]) = p.normal.into();
            (c.fr[l], c.fg[l], c.fb[l]) = f.into();
        }
        let mut keyed: Vec<([i32; 3], u32)> =
            patches.par_iter().enumerate().map(|(i, p)| (cell_of(p.patch.centre, near_radius), i as u32)).collect();
        keyed.par_sort_unstable();
        let mut cells = HashMap::new();
        let mut start = 0;
        for k in 1..=keyed.len() {
            if k == keyed.len() || keyed[k].0 != keyed[start].0 {
                cells.insert(keyed[start].0, (start as u32, k as u32));
                start = k;
            }
        }
        let by_cell = keyed.into_iter().map(|(_, i)| i).collect();
        Self { patches: patches.to_vec(), chunks, near_radius, cells, by_cell }
    }

    pub fn len(&self) -> usize {
        self.patches.len()
    }

    pub fn is_empty(&self) -> bool {
        self.patches.is_empty()
    }

    pub fn patches(&self) -> &[LitPatch] {
        &self.patches
    }

    /// Σ Φ over the lit patches (W).
    pub fn total_flux(&self) -> DVec3 {
        self.patches.iter().map(|p| p.flux.as_dvec3()).sum()
    }

    /// Within this distance of a receiver a patch is integrated over its triangle.
    pub fn near_radius(&self) -> f32 {
        self.near_radius
    }

    /// Irradiance E (W/m²) at each receiver.
    pub fn irradiance(&self, receivers: &[Receiver]) -> Vec<[f32; 3]> {
        receivers.par_iter().with_min_len(16).map(|r| self.irradiance_at(r).as_vec3().to_array()).collect()
    }

    /// Reflected radiance L = ρ/π · E (W·sr⁻¹·m⁻²) at each receiver.
    pub fn radiance(&self, receivers: &[Receiver]) -> Vec<[f32; 3]> {
        receivers
            .par_iter()
            .with_min_len(16)
            .map(|r| (self.irradiance_at(r) * r.albedo.as_dvec3() / PI).as_vec3().to_array())
            .collect()
    }

    /// E at one receiver, in double precision.
    pub fn irradiance_at(&self, r: &Receiver) -> DVec3 {
        if r.normal == Vec3::ZERO || self.patches.is_empty() {
            return DVec3::ZERO;
        }
        let (x, n) = (r.position.to_array(), r.normal.to_array());
        let r2 = self.near_radius * self.near_radius;
        let far = DVec3::from(far_field(&self.chunks, x, n, r2));
        far + self.near_field(r, r2)
    }

    /// The patches within the near radius (exactly those the far sum left out: the same f32
    /// distance, the same comparison), each by its polygon form.
    fn near_field(&self, r: &Receiver, r2: f32) -> DVec3 {
        let x = r.position.to_array();
        let lo = cell_of(r.position - Vec3::splat(self.near_radius), self.near_radius);
        let hi = cell_of(r.position + Vec3::splat(self.near_radius), self.near_radius);
        let mut e = DVec3::ZERO;
        for cz in lo[2]..=hi[2] {
            for cy in lo[1]..=hi[1] {
                for cx in lo[0]..=hi[0] {
                    let Some(&(a, b)) = self.cells.get(&[cx, cy, cz]) else { continue };
                    for &i in &self.by_cell[a as usize..b as usize] {
                        let p = &self.patches[i as usize];
                        let c = p.patch.centre;
                        let (vx, vy, vz) = (x[0] - c.x, x[1] - c.y, x[2] - c.z);
                        let d2 = vx * vx + vy * vy + vz * vz;
                        if d2 <= r2 {
                            let corners = p.patch.corners.map(Vec3::as_dvec3);
                            let factor = polygon_factor(
                                corners,
                                p.normal.as_dvec3(),
                                p.patch.area as f64,
                                r.position.as_dvec3(),
                                r.normal.as_dvec3(),
                            );
                            e += p.flux.as_dvec3() * factor;
                        }
                    }
                }
            }
        }
        e
    }
}

/// E/Φ at `x` (unit normal `n_x`) from a Lambertian triangle (`corners`, lit-side normal
/// `n_s`, `area`) that spreads its flux evenly: F/A, F Lambert's point-to-polygon form factor
/// of the triangle's part above x's plane, F = 1/2π · Σ over edges of the angle each subtends
/// times n_x · the unit normal of its plane with x. A receiver (all but) on the triangle's
/// plane or behind it gets nothing (to a hundredth of the patch's size, as the GPU reference).
pub fn polygon_factor(corners: [DVec3; 3], n_s: DVec3, area: f64, x: DVec3, n_x: DVec3) -> f64 {
    if area.is_nan() || area <= 0.0 || (x - corners[0]).dot(n_s) <= 0.01 * area.sqrt() {
        return 0.0;
    }
    // The triangle relative to x, clipped to x's upper hemisphere: at most four corners.
    let mut poly = [DVec3::ZERO; 4];
    let mut m = 0;
    for i in 0..3 {
        let a = corners[i] - x;
        let b = corners[(i + 1) % 3] - x;
        let (ha, hb) = (a.dot(n_x), b.dot(n_x));
        if ha >= 0.0 {
            poly[m] = a;
            m += 1;
        }
        if (ha >= 0.0) != (hb >= 0.0) {
            poly[m] = a + (b - a) * (ha / (ha - hb));
            m += 1;
        }
    }
    let mut f = 0.0;
    for i in 0..m {
        let (a, b) = (poly[i], poly[(i + 1) % m]);
        let c = a.cross(b);
        let s = c.length();
        if s > 1e-12 * a.length() * b.length() {
            f += s.atan2(a.dot(b)) * n_x.dot(c) / s;
        }
    }
    f.abs() / (2.0 * PI * area)
}

/// The point-form sum over every chunk outside the near radius: Φ/π · cos_s · cos_r / d².
fn far_field(chunks: &[Chunk], x: [f32; 3], n: [f32; 3], r2: f32) -> [f64; 3] {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU has AVX2.
            return unsafe { far_field_avx2(chunks, x, n, r2) };
        }
    }
    far_field_lanes(chunks, x, n, r2)
}

/// The same loop compiled for AVX2: eight lanes a register instead of four. No FMA: the sums
/// are bit for bit those of the plain build.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn far_field_avx2(chunks: &[Chunk], x: [f32; 3], n: [f32; 3], r2: f32) -> [f64; 3] {
    far_field_lanes(chunks, x, n, r2)
}

// One lane index reads nine arrays: a range loop is what vectorises.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn far_field_lanes(chunks: &[Chunk], x: [f32; 3], n: [f32; 3], r2: f32) -> [f64; 3] {
    let mut total = [0.0f64; 3];
    for block in chunks.chunks(CHUNKS_PER_BLOCK) {
        let mut acc = [[0.0f32; LANES]; 3];
        for c in block {
            for l in 0..LANES {
                // v from the patch to the receiver.
                let vx = x[0] - c.px[l];
                let vy = x[1] - c.py[l];
                let vz = x[2] - c.pz[l];
                let d2 = vx * vx + vy * vy + vz * vz;
                // d·cos_s and −d·cos_r, each kept to its lit side.
                let s = c.nx[l] * vx + c.ny[l] * vy + c.nz[l] * vz;
                let r = n[0] * vx + n[1] * vy + n[2] * vz;
                let s = if s > 0.0 { s } else { 0.0 };
                let r = if r < 0.0 { r } else { 0.0 };
                let w = s * r / (d2 * d2);
                let w = if d2 > r2 { w } else { 0.0 };
                acc[0][l] -= w * c.fr[l];
                acc[1][l] -= w * c.fg[l];
                acc[2][l] -= w * c.fb[l];
            }
        }
        for (t, a) in total.iter_mut().zip(&acc) {
            *t += a.iter().map(|&v| v as f64).sum::<f64>();
        }
    }
    total
}
