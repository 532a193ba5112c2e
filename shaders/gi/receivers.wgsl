// Where each receiver of the indirect target is evaluated (cuts and gather passes, which
// declare `gbuffer_normal` and `gbuffer_position`; the cuts pass finds it once a frame and
// records the texel in `receiver_texels` for the gather and temporal passes). A receiver
// stands for a cell of view pixels and is evaluated on one G-buffer texel of it: the centre,
// unless the centre's surface is also at a neighbouring cell's centre and another part of the
// cell shows a surface that no neighbouring centre does. Evaluated on centres alone, a door's
// jamb or a lintel narrower than a cell would be lit only in the frames where a centre fell
// on it, and take the wall's light in the others, blinking as the view slid the cells over
// it. The cell's centre surface is then evaluated by its neighbour, a cell away. The composite
// still weighs each sample by its cell's centre (at most half a cell off); the temporal pass
// looks up a moved receiver's history as far from where its point was as it lies from the
// centre.

struct SurfacePoint {
    x: vec3f,
    n: vec3f,
    valid: bool,
    // View depth (the G-buffer position's w).
    depth: f32,
};

fn surface_point(t: vec2i) -> SurfacePoint {
    var s: SurfacePoint;
    if any(t < vec2i(0)) || any(t >= vec2i(textureDimensions(gbuffer_normal))) {
        return s;
    }
    let n = textureLoad(gbuffer_normal, t, 0);
    s.valid = n.w > 0.0;
    s.n = n.xyz;
    let x = textureLoad(gbuffer_position, t, 0);
    s.x = x.xyz;
    s.depth = x.w;
    return s;
}

// Whether b lies on a's surface (its plane, facing its way).
fn same_plane(a: SurfacePoint, b: SurfacePoint) -> bool {
    return a.valid && b.valid && on_plane(a.x, a.n, length(a.x - globals.camera_pos.xyz), b.x, b.n);
}

// Whether the centre of a cell next to q (across or down) lies on s's surface.
fn at_a_neighbour(s: SurfacePoint, q: vec2i, view: vec2u, indirect: vec2u) -> bool {
    var found = false;
    for (var k = 0; k < 4; k++) {
        let o = select(vec2i(0, 2 * (k & 1) - 1), vec2i(2 * (k & 1) - 1, 0), k < 2);
        let r = q + o;
        if all(r >= vec2i(0)) && all(r < vec2i(indirect)) {
            found = found || same_plane(s, surface_point(receiver_texel(vec2u(r), view, indirect, params.receiver_offset)));
        }
    }
    return found;
}

// A receiver's G-buffer texel and what the G-buffer holds there.
struct PlacedReceiver {
    texel: vec2i,
    surface: SurfacePoint,
};

// The G-buffer texel receiver q is evaluated on (see above): the cell's centre, or the first
// of the centres of its four quarters that shows a surface no neighbouring centre shows. One
// loop takes the centre and then the quarters: a CPU device runs a loop's first turn and every
// branch for its whole SIMD row, so a separate test of the centre cost the quarters' loop once
// more for rows whose centres all pass.
fn receiver_at(q: vec2u, view: vec2u, indirect: vec2u) -> PlacedReceiver {
    let c = receiver_texel(q, view, indirect, params.receiver_offset);
    let qi = vec2i(q);
    let cell = vec2f(view) / vec2f(indirect);
    var centre: SurfacePoint;
    // k = −1: the centre; 0–3: its quarters'.
    for (var k = -1; k < 4; k++) {
        var t = c;
        if k >= 0 {
            // (In a cell one texel wide each way this is its centre again, and is passed over.)
            let corner = vec2f(q) + params.receiver_offset;
            t = min(vec2i((corner + vec2f(0.25 + 0.5 * f32(k & 1), 0.25 + 0.5 * f32(k >> 1u))) * cell), vec2i(view) - 1);
        }
        let s = surface_point(t);
        if k < 0 {
            centre = s;
        }
        let seen_at_centre = k >= 0 && centre.valid && same_plane(centre, s);
        if s.valid && !seen_at_centre && !at_a_neighbour(s, qi, view, indirect) {
            return PlacedReceiver(t, s);
        }
    }
    return PlacedReceiver(c, centre);
}
