//! From lit patches to the light they reflect onto receivers: E = Σ Φ·cos_s·cos_r / (π d²)
//! over every lit patch, the point form, except within [`NEAR_EDGES`] patch edges of the
//! receiver, where each patch is integrated exactly: Lambert's point-to-polygon form factor of
//! the patch triangle clipped to the receiver's hemisphere (as shaders/gi/reference.wgsl does
//! for its texel footprints). No clustering, no cutoff, no clamp: the far sum runs over all the
//! lit patches, O(receivers × patches), in chunks of eight the compiler turns into SIMD.
//!
//! The patches are kept in groups of one triangle (at most 2,048 patches a group) to skip what
//! is exactly zero: a group whose plane the receiver is not in front of (to a hundredth of a
//! patch's size, as the polygon form) or whose every patch lies behind the receiver's own plane.
//! That is about a third of the pairs in a room (the receiver's own wall, the walls behind it).

use std::collections::HashMap;
use std::f64::consts::PI;

use engine::glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::patch::LitPatch;
use crate::visibility::{Cover, Occluders, Seen, VisibilityCube};

/// How far off its surface a receiver looks from, for the visibility test (metres): its own
/// surface then lies wholly behind it.
const RECEIVER_LIFT: f32 = 1e-3;

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

/// A group's chunks are summed in f32 lanes, then go into the f64 total: at most this many
/// (18 KiB, so a group stays in the L1 cache while a block of receivers sums it).
const CHUNKS_PER_GROUP: usize = 64;

/// Receivers that sum each group in turn: the patches stream from memory once a block, not
/// once a receiver (a frame's patches are ~100 MB).
const RECEIVER_BLOCK: usize = 32;

/// Chunks a block of a group seen in part: one test of the hiders' masks for 64 patches.
const BLOCK_CHUNKS: usize = 8;

/// The box (centre, half size) that holds the centres of `chunks`' patches (not the padding).
fn chunks_box(chunks: &[Chunk]) -> (Vec3, Vec3) {
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for c in chunks {
        for l in 0..LANES {
            if c.px[l] < 1e5 {
                let p = Vec3::new(c.px[l], c.py[l], c.pz[l]);
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
    }
    ((lo + hi) * 0.5, (hi - lo) * 0.5)
}

/// Patches of one triangle, lit on one side: its chunks, the plane they lie on, and the box
/// that holds their centres.
#[derive(Clone, Copy, Debug)]
struct Group {
    chunks: (u32, u32),
    /// Its patches in `LitPatches::patches`.
    patches: (u32, u32),
    normal: [f32; 3],
    /// normal · (a centre): the plane.
    offset: f32,
    /// A receiver within this of the plane (or behind it) gets nothing from the group.
    tolerance: f32,
    centre: [f32; 3],
    half: [f32; 3],
}

/// Lit patches ready to light receivers.
pub struct LitPatches {
    patches: Vec<LitPatch>,
    chunks: Vec<Chunk>,
    groups: Vec<Group>,
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
    /// `NEAR_EDGES × max_edge`. Consecutive patches of one triangle make a group.
    pub fn new(patches: &[LitPatch], max_edge: f32) -> Self {
        let near_radius = NEAR_EDGES * max_edge;
        let mut groups = Vec::new();
        let mut start = 0;
        for k in 1..=patches.len() {
            let (a, b) = (&patches[start], patches.get(k));
            let same = b.is_some_and(|b| b.patch.triangle == a.patch.triangle && b.normal == a.normal);
            if !same || k - start == CHUNKS_PER_GROUP * LANES {
                groups.push((start, k));
                start = k;
            }
        }
        // Padding lanes: far away, no normal, no flux; they add exactly 0.
        let pad = Chunk { px: [1e6; LANES], ..Chunk::default() };
        let mut chunks = Vec::with_capacity(patches.len() / LANES + groups.len());
        let groups = groups
            .into_iter()
            .map(|(a, b)| {
                let first = chunks.len() as u32;
                let members = &patches[a..b];
                for (i, p) in members.iter().enumerate() {
                    if i % LANES == 0 {
                        chunks.push(pad);
                    }
                    let (c, l) = (chunks.last_mut().expect("pushed above"), i % LANES);
                    let f = p.flux / std::f32::consts::PI;
                    (c.px[l], c.py[l], c.pz[l]) = p.patch.centre.into();
                    (c.nx[l], c.ny[l], c.nz[l]) = p.normal.into();
                    (c.fr[l], c.fg[l], c.fb[l]) = f.into();
                }
                let (lo, hi) = members.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p.patch.centre), hi.max(p.patch.centre))
                });
                let normal = members[0].normal;
                let offset = members.iter().map(|p| normal.dot(p.patch.centre)).fold(f32::NEG_INFINITY, f32::max);
                Group {
                    chunks: (first, chunks.len() as u32),
                    patches: (a as u32, b as u32),
                    normal: normal.to_array(),
                    offset,
                    tolerance: 0.01 * members[0].patch.area.sqrt(),
                    centre: ((lo + hi) * 0.5).to_array(),
                    half: ((hi - lo) * 0.5).to_array(),
                }
            })
            .collect();
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
        Self { patches: patches.to_vec(), chunks, groups, near_radius, cells, by_cell }
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
        self.irradiance_f64(receivers).into_iter().map(|e| e.as_vec3().to_array()).collect()
    }

    /// Reflected radiance L = ρ/π · E (W·sr⁻¹·m⁻²) at each receiver.
    pub fn radiance(&self, receivers: &[Receiver]) -> Vec<[f32; 3]> {
        let e = self.irradiance_f64(receivers);
        e.iter().zip(receivers).map(|(e, r)| (*e * r.albedo.as_dvec3() / PI).as_vec3().to_array()).collect()
    }

    /// Irradiance E at each receiver with every sender tested for occlusion by the level's
    /// triangles (`occluders`, [`World::occluders`](crate::World::occluders)): a [`VisibilityCube`] of `cube` texels a side around each receiver
    /// decides for each triangle's patches whether all, none or which are seen (rays at its
    /// silhouettes). The receivers are independent; each costs its cube (O(triangles + texels))
    /// and the sum over the patches it may see.
    pub fn irradiance_visible(&self, receivers: &[Receiver], occluders: &Occluders, cube: usize) -> Vec<[f32; 3]> {
        self.irradiance_visible_f64(receivers, occluders, cube).into_iter().map(|e| e.as_vec3().to_array()).collect()
    }

    /// Reflected radiance L = ρ/π · E with visibility ([`LitPatches::irradiance_visible`]).
    pub fn radiance_visible(&self, receivers: &[Receiver], occluders: &Occluders, cube: usize) -> Vec<[f32; 3]> {
        let e = self.irradiance_visible_f64(receivers, occluders, cube);
        e.iter().zip(receivers).map(|(e, r)| (*e * r.albedo.as_dvec3() / PI).as_vec3().to_array()).collect()
    }

    fn irradiance_visible_f64(&self, receivers: &[Receiver], occluders: &Occluders, cube: usize) -> Vec<DVec3> {
        receivers
            .par_iter()
            // (Each thread keeps one cube and moves it from receiver to receiver.)
            .map_init(
                || None,
                |slot: &mut Option<VisibilityCube>, r| {
                    if r.normal == Vec3::ZERO || self.patches.is_empty() {
                        return DVec3::ZERO;
                    }
                    let origin = r.position + r.normal * RECEIVER_LIFT;
                    let view = match slot {
                        Some(view) => {
                            view.move_to(occluders, origin);
                            view
                        }
                        None => slot.insert(VisibilityCube::new(occluders, origin, cube)),
                    };
                    self.irradiance_seen(r, view, occluders)
                },
            )
            .collect()
    }

    /// E at `r` from the patches `view` (around r) sees.
    fn irradiance_seen(&self, r: &Receiver, view: &mut VisibilityCube, occluders: &Occluders) -> DVec3 {
        let r2 = self.near_radius * self.near_radius;
        let (x, n) = (r.position.to_array(), r.normal.to_array());
        let mut e = [0.0f64; 3];
        let mut add = |a: [f64; 3]| e.iter_mut().zip(a).for_each(|(t, a)| *t += a);
        for g in self.groups.iter().filter(|g| !group_gives_nothing(g, x, n)) {
            let members = &self.patches[g.patches.0 as usize..g.patches.1 as usize];
            let group = &self.chunks[g.chunks.0 as usize..g.chunks.1 as usize];
            let triangle = members[0].patch.triangle;
            match view.seen(occluders, triangle) {
                Seen::Nothing => {}
                Seen::All => add(group_sum(group, x, n, r2)),
                // Blocks of chunks that the triangle's hiders leave wholly clear or wholly
                // hidden go at once; the rest patch by patch.
                Seen::Part => {
                    for (b, block) in group.chunks(BLOCK_CHUNKS).enumerate() {
                        let (centre, half) = chunks_box(block);
                        match view.cover_of_box(triangle, centre, half) {
                            Some(Cover::Hidden) => {}
                            Some(Cover::Clear) => add(group_sum(block, x, n, r2)),
                            _ => {
                                let first = b * BLOCK_CHUNKS * LANES;
                                let last = (first + BLOCK_CHUNKS * LANES).min(members.len());
                                for p in &members[first..last] {
                                    if view.sees(occluders, p.patch.centre, triangle) {
                                        add(point_form(p, x, n, r2));
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        DVec3::from(e) + self.near_field_where(r, r2, |p| view.sees(occluders, p.patch.centre, p.patch.triangle))
    }
    /// E at one receiver, in double precision.
    pub fn irradiance_at(&self, r: &Receiver) -> DVec3 {
        self.irradiance_f64(std::slice::from_ref(r))[0]
    }

    fn irradiance_f64(&self, receivers: &[Receiver]) -> Vec<DVec3> {
        let r2 = self.near_radius * self.near_radius;
        let mut out = vec![DVec3::ZERO; receivers.len()];
        out.par_chunks_mut(RECEIVER_BLOCK).zip(receivers.par_chunks(RECEIVER_BLOCK)).for_each(|(out, block)| {
            let points: Vec<([f32; 3], [f32; 3])> = block
                .iter()
                .filter(|r| r.normal != Vec3::ZERO)
                .map(|r| (r.position.to_array(), r.normal.to_array()))
                .collect();
            let mut far = vec![[0.0f64; 3]; points.len()];
            if !self.patches.is_empty() {
                far_field(&self.chunks, &self.groups, &points, r2, &mut far);
            }
            let mut far = far.into_iter();
            for (e, r) in out.iter_mut().zip(block).filter(|(_, r)| r.normal != Vec3::ZERO) {
                *e = DVec3::from(far.next().expect("one a receiver")) + self.near_field(r, r2);
            }
        });
        out
    }

    /// The patches within the near radius (exactly those the far sum left out: the same f32
    /// distance, the same comparison), each by its polygon form.
    fn near_field(&self, r: &Receiver, r2: f32) -> DVec3 {
        self.near_field_where(r, r2, |_| true)
    }

    /// [`LitPatches::near_field`] over the patches `keep` keeps.
    fn near_field_where(&self, r: &Receiver, r2: f32, mut keep: impl FnMut(&LitPatch) -> bool) -> DVec3 {
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
                        if d2 <= r2 && keep(p) {
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

/// The point-form sum over every patch outside the near radius, Φ/π · cos_s · cos_r / d², at
/// each of `points` (position, unit normal), added to `out`.
fn far_field(chunks: &[Chunk], groups: &[Group], points: &[([f32; 3], [f32; 3])], r2: f32, out: &mut [[f64; 3]]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU has AVX2.
            return unsafe { far_field_avx2(chunks, groups, points, r2, out) };
        }
    }
    far_field_lanes(chunks, groups, points, r2, out)
}

/// The same loop compiled for AVX2: eight lanes a register instead of four. No FMA: the sums
/// are bit for bit those of the plain build.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn far_field_avx2(chunks: &[Chunk], groups: &[Group], points: &[([f32; 3], [f32; 3])], r2: f32, out: &mut [[f64; 3]]) {
    far_field_lanes(chunks, groups, points, r2, out)
}

#[inline(always)]
fn far_field_lanes(chunks: &[Chunk], groups: &[Group], points: &[([f32; 3], [f32; 3])], r2: f32, out: &mut [[f64; 3]]) {
    for g in groups {
        let group = &chunks[g.chunks.0 as usize..g.chunks.1 as usize];
        for (&(x, n), total) in points.iter().zip(out.iter_mut()) {
            if group_gives_nothing(g, x, n) {
                continue;
            }
            for (t, a) in total.iter_mut().zip(group_sum(group, x, n, r2)) {
                *t += a;
            }
        }
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Exact zeros: the receiver at `x` (normal `n`) not in front of the group's plane, or every
/// patch of the group behind the receiver's plane (the box's nearest corner to it is).
#[inline(always)]
fn group_gives_nothing(g: &Group, x: [f32; 3], n: [f32; 3]) -> bool {
    let reach = n[0].abs() * g.half[0] + n[1].abs() * g.half[1] + n[2].abs() * g.half[2];
    dot(g.normal, x) - g.offset <= g.tolerance || dot(n, g.centre) - dot(n, x) + reach <= 0.0
}

/// The point-form sum of a group's patches outside the near radius at `x` (normal `n`).
// One lane index reads nine arrays: a range loop is what vectorises.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn group_sum(group: &[Chunk], x: [f32; 3], n: [f32; 3], r2: f32) -> [f64; 3] {
    let mut acc = [[0.0f32; LANES]; 3];
    for c in group {
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
    acc.map(|a| a.iter().map(|&v| v as f64).sum::<f64>())
}

/// One patch's term of [`group_sum`], the same arithmetic (0 inside the near radius).
fn point_form(p: &LitPatch, x: [f32; 3], n: [f32; 3], r2: f32) -> [f64; 3] {
    let c = p.patch.centre;
    let (vx, vy, vz) = (x[0] - c.x, x[1] - c.y, x[2] - c.z);
    let d2 = vx * vx + vy * vy + vz * vz;
    let s = (p.normal.x * vx + p.normal.y * vy + p.normal.z * vz).max(0.0);
    let r = (n[0] * vx + n[1] * vy + n[2] * vz).min(0.0);
    let w = if d2 > r2 { s * r / (d2 * d2) } else { 0.0 };
    let f = p.flux / std::f32::consts::PI;
    [-(w * f.x) as f64, -(w * f.y) as f64, -(w * f.z) as f64]
}
