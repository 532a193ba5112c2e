//! What a receiver sees of the level, for the visibility-correct reference. Around the
//! receiver, a cube of n×n texels a face names the nearest of the level's triangles in each
//! direction (an item buffer, rasterised on the CPU). The cube only nominates: the triangles
//! it names over the texels a triangle touches and their neighbours (and the triangles that
//! share a corner with one found to hide it) are the candidates to hide some of it. Each is
//! tested exactly: the two projections clipped against each other, and their depths compared
//! at the overlap's corners. A triangle no candidate hides is wholly seen; one behind others
//! in all its texels is wholly hidden; the rest are judged patch by patch, through a coarse
//! mask of where their hiders lie (cells clear, hidden whole, or reached by one or more
//! hiders) and exact rays against those hiders alone. So the cube's size sets the cost, not
//! the answer, except for an occluder that covers no texel centre near the triangle and
//! touches no hider (narrower than a texel): its resolution is shown converged like the patch
//! size. Single-sided triangles seen from behind hide nothing, as in every view and in the
//! lamp's shadow rays.

use std::collections::HashMap;

use engine::glam::{Vec2, Vec3};

/// The near plane of each face (metres): nothing nearer than this hides anything.
const NEAR: f32 = 1e-5;

/// A patch this much nearer than the triangle met along its ray (relative) counts as in front
/// of it: the two are one surface within f32 rounding.
const SAME_SURFACE: f32 = 1e-4;

/// Texels each face keeps beyond its edges, drawn from a slightly wider frustum: a texel at a
/// face's edge then has all its neighbours, so a triangle that spans faces is judged whole
/// like any other.
const RING: usize = 2;

/// Cells a side of each face's coarse mask of where a triangle's hiders lie: a patch outside
/// them needs no ray.
const MASK: usize = 128;

/// A face of the cube: the axis it looks along, and the directions of its texels' x and y.
#[derive(Clone, Copy)]
struct Face {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

const FACES: [Face; 6] = [
    Face { forward: Vec3::X, right: Vec3::NEG_Z, up: Vec3::Y },
    Face { forward: Vec3::NEG_X, right: Vec3::Z, up: Vec3::Y },
    Face { forward: Vec3::Y, right: Vec3::X, up: Vec3::NEG_Z },
    Face { forward: Vec3::NEG_Y, right: Vec3::X, up: Vec3::Z },
    Face { forward: Vec3::Z, right: Vec3::X, up: Vec3::Y },
    Face { forward: Vec3::NEG_Z, right: Vec3::NEG_X, up: Vec3::Y },
];

/// The world direction through the centre of texel (x, y) of face `f` of an `n`-texel cube
/// (counted from the outer edge of its [`RING`]), scaled so its component along the face's
/// axis is 1.
fn texel_direction(f: usize, n: usize, x: usize, y: usize) -> Vec3 {
    texel_point_direction(f, n, Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
}

/// The world direction through texel coordinates (x, y) of face `f` (as [`texel_direction`]).
fn texel_point_direction(f: usize, n: usize, p: Vec2) -> Vec3 {
    let face = FACES[f];
    let u = (p.x - RING as f32) / n as f32 * 2.0 - 1.0;
    let v = 1.0 - (p.y - RING as f32) / n as f32 * 2.0;
    face.forward + face.right * u + face.up * v
}

/// The face a direction falls on (its largest component).
fn face_of(d: Vec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        usize::from(d.x < 0.0)
    } else if a.y >= a.z {
        2 + usize::from(d.y < 0.0)
    } else {
        4 + usize::from(d.z < 0.0)
    }
}

/// The level's triangles as occluders: corners, and whether they hide from both sides.
pub struct Occluders {
    triangles: Vec<[Vec3; 3]>,
    double_sided: Vec<bool>,
    /// Each triangle's plane: (b − a) × (c − a) and its dot with a.
    planes: Vec<(Vec3, f32)>,
    /// The triangles that share a corner with each: a range of `touching`.
    touching_of: Vec<(u32, u32)>,
    touching: Vec<u32>,
}

impl Occluders {
    /// From triangles (corners in their winding) and whether each hides from both sides
    /// ([`World::occluders`](crate::World::occluders) gives a level's).
    pub fn new(level: impl Iterator<Item = ([Vec3; 3], bool)>) -> Self {
        let (triangles, double_sided): (Vec<[Vec3; 3]>, _) = level.unzip();
        let planes = triangles
            .iter()
            .map(|[a, b, c]| {
                let n = (*b - *a).cross(*c - *a);
                (n, n.dot(*a))
            })
            .collect();
        let mut by_corner: HashMap<[u32; 3], Vec<u32>> = HashMap::new();
        for (i, t) in triangles.iter().enumerate() {
            for p in t {
                by_corner.entry(p.to_array().map(f32::to_bits)).or_default().push(i as u32);
            }
        }
        let (mut touching_of, mut touching) = (Vec::with_capacity(triangles.len()), Vec::new());
        for (i, t) in triangles.iter().enumerate() {
            let first = touching.len();
            for p in t {
                for &o in &by_corner[&p.to_array().map(f32::to_bits)] {
                    if o != i as u32 && !touching[first..].contains(&o) {
                        touching.push(o);
                    }
                }
            }
            touching_of.push((first as u32, touching.len() as u32));
        }
        Self { triangles, double_sided, planes, touching_of, touching }
    }

    /// The triangles that share a corner with triangle `i`.
    fn touching(&self, i: u32) -> &[u32] {
        let (a, b) = self.touching_of[i as usize];
        &self.touching[a as usize..b as usize]
    }

    /// 1/z at which the ray origin + z·dir (dir's forward component 1) meets triangle `i`'s
    /// plane (0 where it never does, ahead).
    fn plane_inv_z(&self, i: u32, origin: Vec3, dir: Vec3) -> f32 {
        let (n, offset) = self.planes[i as usize];
        let t = (offset - n.dot(origin)) / n.dot(dir);
        if t > 0.0 {
            1.0 / t
        } else {
            0.0
        }
    }

    /// How far `p` lies from triangle `i`'s plane.
    fn plane_distance(&self, i: u32, p: Vec3) -> f32 {
        let (n, offset) = self.planes[i as usize];
        (n.dot(p) - offset).abs() / n.length()
    }

    /// Whether triangle `i` can hide anything from `origin`: double-sided, or seen from its front.
    fn faces(&self, i: usize, origin: Vec3) -> bool {
        let [a, b, c] = self.triangles[i];
        self.double_sided[i] || (b - a).cross(c - a).dot(origin - a) > 0.0
    }
}

/// How much of each triangle one receiver sees, judged when first asked.
pub struct VisibilityCube {
    origin: Vec3,
    n: usize,
    /// Texels a side with the ring: n + 2·RING.
    m: usize,
    /// Per face (with its ring), row by row from the top: the nearest triangle's index + 1
    /// (0: none).
    nearest: Vec<u32>,
    /// Per texel, the nearest triangle's 1/z (larger is nearer).
    inv_z: Vec<f32>,
    /// Per triangle, how much of it is seen, once judged.
    seen: Vec<Option<Seen>>,
    /// Per triangle seen in part, the triangles that hide some of it: a range of `hiders`.
    hiders_of: Vec<(u32, u32)>,
    hiders: Vec<u32>,
    /// Per triangle seen in part, per face: where its mask starts in `cover` (u32::MAX where
    /// it has no part on that face). A mask is MASK + 2·RING cells a side.
    masks: Vec<[u32; 6]>,
    cover: Vec<Cover>,
    /// The hider (in `hiders`) that hid the last patch.
    last_hit: u32,
    /// The triangles named around the triangle being judged, by face, each once: `named[o]`
    /// is that triangle + 1 and the faces `o` was named on.
    named: Vec<(u32, u8)>,
}
/// How much of a triangle a receiver sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Seen {
    /// No triangle hides any of it (or it faces away: it sends the receiver nothing).
    All,
    /// In every texel it touches and their neighbours a triangle stands in front of its plane,
    /// so one covers each of those texels whole: none of it is seen.
    Nothing,
    /// Some triangles hide some of it: each patch is tested against them
    /// ([`VisibilityCube::sees`]).
    Part,
}

/// What a triangle's hiders do to one cell of its mask, or to a box of its patches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cover {
    /// No hider reaches into it: what of the triangle lies there is seen.
    Clear,
    /// A hider covers it whole and stands in front of the triangle all across it: hidden.
    Hidden,
    /// One hider (its index in the cube's list) reaches into it: a ray against it decides.
    One(u32),
    /// More reach into it: rays against them all decide.
    Many,
}

/// A corner in a face's frame: x right, y up, z forward.
type Corner = Vec3;

/// A point of a face in texel coordinates (x right, y down, from the ring's outer edge), and 1/z.
type TexelPoint = (f32, f32, f32);

/// Keeps the part of `poly` where `inside(p) ≥ 0` (one Sutherland–Hodgman step).
fn clip<P: Copy + std::ops::Add<Output = P> + std::ops::Sub<Output = P> + std::ops::Mul<f32, Output = P>>(
    poly: &[P],
    inside: impl Fn(P) -> f32,
) -> Vec<P> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (dp, dq) = (inside(p), inside(q));
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// Triangle `t`'s part within face `f`'s frustum around `origin`, widened by `wide` (1: the
/// face exactly), in texel coordinates of an `n`-texel face; None where nothing is left.
fn face_polygon(t: [Vec3; 3], origin: Vec3, f: usize, wide: f32, n: usize) -> Option<Vec<TexelPoint>> {
    let face = FACES[f];
    let local = t.map(|p| {
        let q = p - origin;
        Vec3::new(q.dot(face.right), q.dot(face.up), q.dot(face.forward))
    });
    let planes: [&dyn Fn(Corner) -> f32; 5] =
        [&|p| p.z - NEAR, &|p| p.z * wide - p.x, &|p| p.z * wide + p.x, &|p| p.z * wide - p.y, &|p| p.z * wide + p.y];
    let mut poly = local.to_vec();
    for plane in planes {
        poly = clip(&poly, plane);
        if poly.len() < 3 {
            return None;
        }
    }
    Some(texel_polygon(&poly, n))
}

/// Whether a point lies in the convex polygon `s` (texel coordinates), either winding.
fn convex_inside(s: &[TexelPoint]) -> impl Fn(Vec2) -> bool + '_ {
    let points: Vec<Vec2> = s.iter().map(|p| Vec2::new(p.0, p.1)).collect();
    let sign = doubled_area(&points).signum();
    move |x| {
        (0..s.len()).all(|i| {
            let (p, q) = (points[i], points[(i + 1) % points.len()]);
            sign * (q - p).perp_dot(x - p) >= 0.0
        })
    }
}

/// Twice the signed area of a polygon.
fn doubled_area(s: &[Vec2]) -> f32 {
    (0..s.len()).map(|i| s[i].perp_dot(s[(i + 1) % s.len()])).sum()
}

/// A polygon overlap smaller than this (texel²) is a shared edge, not an overlap.
const NO_AREA: f32 = 1e-6;

impl VisibilityCube {
    /// The cube around `origin`, `n` texels a side.
    pub fn new(occluders: &Occluders, origin: Vec3, n: usize) -> Self {
        assert!(n > 0, "a cube has texels");
        let m = n + 2 * RING;
        let count = occluders.triangles.len();
        let mut cube = Self {
            origin,
            n,
            m,
            nearest: vec![0; 6 * m * m],
            inv_z: vec![0.0; 6 * m * m],
            seen: vec![None; count],
            hiders_of: vec![(0, 0); count],
            hiders: Vec::new(),
            masks: vec![[u32::MAX; 6]; count],
            cover: Vec::new(),
            last_hit: u32::MAX,
            named: vec![(0, 0); count],
        };
        cube.draw(occluders);
        cube
    }

    /// This cube moved to `origin` (of the same occluders), reusing its memory.
    pub fn move_to(&mut self, occluders: &Occluders, origin: Vec3) {
        self.origin = origin;
        self.nearest.fill(0);
        self.inv_z.fill(0.0);
        self.seen.fill(None);
        self.hiders.clear();
        self.masks.fill([u32::MAX; 6]);
        self.cover.clear();
        self.last_hit = u32::MAX;
        self.named.fill((0, 0));
        self.draw(occluders);
    }

    /// Rasterises the triangles that face the origin into the item buffer.
    fn draw(&mut self, occluders: &Occluders) {
        let (n, m, origin, wide) = (self.n, self.m, self.origin, self.wide());
        for i in (0..occluders.triangles.len()).filter(|&i| occluders.faces(i, origin)) {
            for f in 0..6 {
                if let Some(poly) = face_polygon(occluders.triangles[i], origin, f, wide, n) {
                    let base = f * m * m;
                    let texels = (&mut self.nearest[base..base + m * m], &mut self.inv_z[base..base + m * m]);
                    rasterise(&poly, m, i as u32 + 1, texels);
                }
            }
        }
    }

    /// How far the drawn frustum reaches beyond each face: 1 + the ring's share.
    fn wide(&self) -> f32 {
        1.0 + 2.0 * RING as f32 / self.n as f32
    }

    /// How much of triangle `triangle` this receiver sees.
    pub fn seen(&mut self, occluders: &Occluders, triangle: u32) -> Seen {
        match self.seen[triangle as usize] {
            Some(seen) => seen,
            None => {
                let seen = self.judge(occluders, triangle);
                self.seen[triangle as usize] = Some(seen);
                seen
            }
        }
    }

    /// Whether the receiver sees point `p` of triangle `triangle` (a patch's centre): no
    /// triangle of the level lies between them.
    pub fn sees(&mut self, occluders: &Occluders, p: Vec3, triangle: u32) -> bool {
        match self.seen(occluders, triangle) {
            Seen::All => true,
            Seen::Nothing => false,
            Seen::Part => {
                let d = p - self.origin;
                let cover = self.cover_towards(triangle, d);
                let distance = d.length();
                let unit = d / distance;
                let hits = |k: u32| {
                    ray_triangle(self.origin, unit, occluders.triangles[self.hiders[k as usize] as usize])
                        .is_some_and(|s| s < distance * (1.0 - SAME_SURFACE))
                };
                match cover {
                    Some(Cover::Clear) => return true,
                    Some(Cover::Hidden) => return false,
                    Some(Cover::One(k)) => return !hits(k),
                    Some(Cover::Many) | None => {}
                }
                let (a, b) = self.hiders_of[triangle as usize];
                // Patches come in rows: the hider of the last one likely hides this one.
                let last = self.last_hit;
                if (a..b).contains(&last) && hits(last) {
                    return false;
                }
                match (a..b).find(|&k| k != last && hits(k)) {
                    Some(k) => {
                        self.last_hit = k;
                        false
                    }
                    None => true,
                }
            }
        }
    }

    /// Judges triangle `t`: the triangles named in the texels it touches and their neighbours
    /// are the candidates to hide it, each tested exactly; it is hidden whole where a triangle
    /// stands in front of its plane in every one of those texels.
    fn judge(&mut self, occluders: &Occluders, t: u32) -> Seen {
        let (n, m, origin, own) = (self.n, self.m, self.origin, t + 1);
        let parts: Vec<(usize, Vec<TexelPoint>)> = (0..6)
            .filter_map(|f| face_polygon(occluders.triangles[t as usize], origin, f, 1.0, n).map(|p| (f, p)))
            .collect();
        let mut candidates: Vec<(u32, usize)> = Vec::new();
        let mut nothing = !parts.is_empty();
        for (f, poly) in &parts {
            let base = f * m * m;
            let (nearest, inv_z, named) = (&self.nearest, &self.inv_z, &mut self.named);
            // The texels it touches and their neighbours, each once (the ring holds those of
            // the texels at a face's edge).
            let mut touched = |x: usize, y: usize| {
                let k = base + y * m + x;
                let other = nearest[k];
                if other == 0 || other == own {
                    nothing = false;
                    return true;
                }
                // Any triangle named here may hide some of this one: the exact test below
                // decides. Hidden whole needs one in front of its plane here.
                let mark = &mut named[(other - 1) as usize];
                if mark.0 != own {
                    *mark = (own, 0);
                }
                if mark.1 & (1 << f) == 0 {
                    mark.1 |= 1 << f;
                    candidates.push((other - 1, *f));
                }
                if nothing {
                    let plane = occluders.plane_inv_z(t, origin, texel_direction(*f, n, x, y));
                    nothing = plane > 0.0 && inv_z[k] > plane * (1.0 + SAME_SURFACE);
                }
                true
            };
            touch_conservatively(poly, m, 1, &mut touched);
        }
        if nothing {
            return Seen::Nothing;
        }
        let first = self.hiders.len();
        for &(o, f) in &candidates {
            let part = &parts.iter().find(|(g, _)| *g == f).expect("a candidate comes from a part").1;
            if !self.hiders[first..].contains(&o) && self.hides(occluders, o, t, f, part) {
                self.hiders.push(o);
            }
        }
        // A hider's sliver may cover no texel centre (the thin end of a triangle beside a
        // silhouette): the triangles that touch a hider are tested too, and theirs in turn.
        const TESTED: u8 = 0x80;
        let mut next = first;
        while next < self.hiders.len() {
            let h = self.hiders[next];
            next += 1;
            for &o in occluders.touching(h) {
                let mark = &mut self.named[o as usize];
                if mark.0 != own {
                    *mark = (own, 0);
                }
                if o == t || mark.1 & TESTED != 0 || !occluders.faces(o as usize, origin) {
                    continue;
                }
                mark.1 |= TESTED;
                if !self.hiders[first..].contains(&o)
                    && parts.iter().any(|(f, part)| self.hides(occluders, o, t, *f, part))
                {
                    self.hiders.push(o);
                }
            }
        }
        if self.hiders.len() == first {
            return Seen::All;
        }
        self.hiders_of[t as usize] = (first as u32, self.hiders.len() as u32);
        // Where on each face the hiders may lie, conservatively, over the faces `t` is on. The
        // masks, like the cube, see nothing nearer than NEAR: a hider whose plane passes that
        // near leaves `t` without masks, each patch then tested by rays.
        let near = |o: u32| occluders.plane_distance(o, origin) < 2.0 * NEAR;
        if self.hiders[first..].iter().any(|&o| near(o)) {
            return Seen::Part;
        }
        let side = MASK + 2 * RING;
        for (f, _) in &parts {
            self.masks[t as usize][*f] = self.cover.len() as u32;
            self.cover.resize(self.cover.len() + side * side, Cover::Clear);
        }
        for k in first..self.hiders.len() {
            let o = self.hiders[k];
            for (f, _) in &parts {
                let Some(poly) = face_polygon(occluders.triangles[o as usize], origin, *f, 1.0, MASK) else {
                    continue;
                };
                let base = self.masks[t as usize][*f] as usize;
                let cover = &mut self.cover;
                let inside = convex_inside(&poly);
                // A cell is hidden where the hider's projection holds its four corners and the
                // hider is nearer at each (1/z is linear across a cell for both planes).
                let hidden = |x: usize, y: usize| {
                    [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].iter().all(|&(a, b)| {
                        let corner = Vec2::new(x as f32 + a, y as f32 + b);
                        let dir = texel_point_direction(*f, MASK, corner);
                        let (near, far) =
                            (occluders.plane_inv_z(o, origin, dir), occluders.plane_inv_z(t, origin, dir));
                        inside(corner) && far > 0.0 && near > far * (1.0 + SAME_SURFACE)
                    })
                };
                touch_conservatively(&poly, side, 0, &mut |x, y| {
                    let cell = &mut cover[base + y * side + x];
                    *cell = match *cell {
                        Cover::Hidden => Cover::Hidden,
                        _ if hidden(x, y) => Cover::Hidden,
                        Cover::Clear => Cover::One(k as u32),
                        Cover::One(_) | Cover::Many => Cover::Many,
                    };
                    true
                });
            }
        }
        Seen::Part
    }

    /// What triangle `t`'s hiders (it is seen in part) do to its patches whose centres lie in
    /// the box `centre` ± `half`: the same to every cell the box's corners span on one face, or
    /// None.
    pub fn cover_of_box(&self, t: u32, centre: Vec3, half: Vec3) -> Option<Cover> {
        let mut f = usize::MAX;
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        for k in 0..8 {
            let sign = Vec3::new([-1.0, 1.0][k & 1], [-1.0, 1.0][(k >> 1) & 1], [-1.0, 1.0][k >> 2]);
            let d = centre + half * sign - self.origin;
            let g = face_of(d);
            if f != usize::MAX && g != f {
                return None;
            }
            f = g;
            let face = FACES[f];
            let z = d.dot(face.forward);
            if z <= NEAR {
                return None;
            }
            let cell = Vec2::new(d.dot(face.right) / z * 0.5 + 0.5, 0.5 - d.dot(face.up) / z * 0.5) * MASK as f32;
            (lo, hi) = (lo.min(cell), hi.max(cell));
        }
        let start = self.masks[t as usize][f];
        if start == u32::MAX {
            return None;
        }
        let clamp = |v: f32| (v.max(0.0) as usize).min(MASK - 1) + RING;
        let side = MASK + 2 * RING;
        let mut cover = None;
        for y in clamp(lo.y)..=clamp(hi.y) {
            for x in clamp(lo.x)..=clamp(hi.x) {
                let cell = self.cover[start as usize + y * side + x];
                if !matches!(cell, Cover::Clear | Cover::Hidden) || cover.is_some_and(|c| c != cell) {
                    return None;
                }
                cover = Some(cell);
            }
        }
        cover
    }

    /// What triangle `t`'s hiders (it is seen in part) do in direction `d`: None where its mask
    /// does not say.
    fn cover_towards(&self, t: u32, d: Vec3) -> Option<Cover> {
        let f = face_of(d);
        let start = self.masks[t as usize][f];
        if start == u32::MAX {
            return None;
        }
        let face = FACES[f];
        let z = d.dot(face.forward);
        let (u, v) = (d.dot(face.right) / z, d.dot(face.up) / z);
        let size = MASK as f32;
        let x = (((u * 0.5 + 0.5) * size).max(0.0) as usize).min(MASK - 1) + RING;
        let y = (((0.5 - v * 0.5) * size).max(0.0) as usize).min(MASK - 1) + RING;
        Some(self.cover[start as usize + y * (MASK + 2 * RING) + x])
    }

    /// Whether triangle `o` hides some of triangle `t`'s part `part` on face `f`: their
    /// projections overlap, and somewhere in the overlap `o` is nearer. (Both are planes, so
    /// their depths differ linearly across the overlap: its corners decide.)
    fn hides(&self, occluders: &Occluders, o: u32, t: u32, f: usize, part: &[TexelPoint]) -> bool {
        let n = self.n;
        let Some(other) = face_polygon(occluders.triangles[o as usize], self.origin, f, self.wide(), n) else {
            return false;
        };
        let other: Vec<Vec2> = other.iter().map(|p| Vec2::new(p.0, p.1)).collect();
        let sign = doubled_area(&other).signum();
        let mut overlap: Vec<Vec2> = part.iter().map(|p| Vec2::new(p.0, p.1)).collect();
        for k in 0..other.len() {
            let (p, q) = (other[k], other[(k + 1) % other.len()]);
            overlap = clip(&overlap, |x: Vec2| sign * (q - p).perp_dot(x - p));
            if overlap.len() < 3 {
                return false;
            }
        }
        if doubled_area(&overlap).abs() < 2.0 * NO_AREA {
            return false;
        }
        overlap.iter().any(|&x| {
            let dir = texel_point_direction(f, n, x);
            let (near, far) = (occluders.plane_inv_z(o, self.origin, dir), occluders.plane_inv_z(t, self.origin, dir));
            far > 0.0 && near > far * (1.0 + SAME_SURFACE)
        })
    }
}

/// Where the ray o + s·d (d unit) meets triangle `t` (s > 0), if it does.
fn ray_triangle(o: Vec3, d: Vec3, [a, b, c]: [Vec3; 3]) -> Option<f32> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let t = o - a;
    let u = t.dot(p) / det;
    let q = t.cross(e1);
    let v = d.dot(q) / det;
    let s = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && s > 0.0).then_some(s)
}

/// A face-frame polygon in texel coordinates (x right, y down, from the ring's outer edge)
/// with 1/z, which is linear across the face.
fn texel_polygon(poly: &[Corner], n: usize) -> Vec<TexelPoint> {
    let (size, ring) = (n as f32, RING as f32);
    poly.iter()
        .map(|p| ((p.x / p.z * 0.5 + 0.5) * size + ring, (0.5 - p.y / p.z * 0.5) * size + ring, 1.0 / p.z))
        .collect()
}

/// Calls `touched` for every texel within `reach` texels (across or along) of one whose square
/// the convex polygon `s` (texel coordinates) overlaps, or nearly (its bounding box's texels
/// that no edge of it excludes), until it returns false.
fn touch_conservatively(s: &[(f32, f32, f32)], n: usize, reach: usize, touched: &mut impl FnMut(usize, usize) -> bool) {
    let r = reach as f32;
    let x0 = (s.iter().map(|p| p.0).fold(f32::INFINITY, f32::min) - r).floor().max(0.0) as usize;
    let x1 = ((s.iter().map(|p| p.0).fold(f32::NEG_INFINITY, f32::max) + r).ceil().max(0.0) as usize).min(n);
    let y0 = (s.iter().map(|p| p.1).fold(f32::INFINITY, f32::min) - r).floor().max(0.0) as usize;
    let y1 = ((s.iter().map(|p| p.1).fold(f32::NEG_INFINITY, f32::max) + r).ceil().max(0.0) as usize).min(n);
    // The polygon's winding: its edges' inner side.
    let area: f32 = (0..s.len())
        .map(|i| {
            let (p, q) = (s[i], s[(i + 1) % s.len()]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum();
    let sign = if area >= 0.0 { 1.0 } else { -1.0 };
    for y in y0..y1 {
        for x in x0..x1 {
            let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
            let outside = (0..s.len()).any(|i| {
                let (p, q) = (s[i], s[(i + 1) % s.len()]);
                let (ex, ey) = (q.0 - p.0, q.1 - p.1);
                // The edge function's largest value over the square of the texel and `reach`
                // texels around it.
                let at_centre = sign * (ex * (cy - p.1) - ey * (cx - p.0));
                at_centre + (0.5 + r) * (ex.abs() + ey.abs()) < 0.0
            });
            if !outside && !touched(x, y) {
                return;
            }
        }
    }
}

/// Draws the convex polygon `s` (texel coordinates with 1/z) into one face's `n` × `n` texels
/// where it is nearer than what is there: `id` and its 1/z.
fn rasterise(s: &[(f32, f32, f32)], n: usize, id: u32, (nearest, inv_z): (&mut [u32], &mut [f32])) {
    for k in 1..s.len() - 1 {
        let (a, b, c) = (s[0], s[k], s[k + 1]);
        let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
        if area.abs() < 1e-12 {
            continue;
        }
        let x0 = a.0.min(b.0).min(c.0).floor().max(0.0) as usize;
        let x1 = (a.0.max(b.0).max(c.0).ceil() as usize).min(n);
        let y0 = a.1.min(b.1).min(c.1).floor().max(0.0) as usize;
        let y1 = (a.1.max(b.1).max(c.1).ceil() as usize).min(n);
        let edge =
            |p: (f32, f32, f32), q: (f32, f32, f32), x: f32, y: f32| (q.0 - p.0) * (y - p.1) - (q.1 - p.1) * (x - p.0);
        for y in y0..y1 {
            for x in x0..x1 {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let (w0, w1, w2) = (edge(b, c, px, py) / area, edge(c, a, px, py) / area, edge(a, b, px, py) / area);
                // (Half-open on the fan's inner edges, so no texel counts twice.)
                let inner_edge = k + 1 < s.len() - 1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 || (inner_edge && w1 == 0.0) {
                    continue;
                }
                let w = w0 * a.2 + w1 * b.2 + w2 * c.2;
                let k = y * n + x;
                if w > inv_z[k] {
                    inv_z[k] = w;
                    nearest[k] = id;
                }
            }
        }
    }
}
