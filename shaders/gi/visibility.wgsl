// GI visibility: whether a reflection light's light reaches a receiver, by a march of the
// segment between them through the depth the camera sees (the G-buffer's view depth, at half
// its resolution: sight_depth.wgsl). A point of the segment that lies behind the surface the
// camera sees there, by more than a sliver and less than VISIBILITY_THICKNESS, is inside that
// surface's solid: something stands between. Points off the screen or behind the camera are taken as clear (the screen knows
// nothing there). Included by the sight pass (sight.wgsl), which binds `sight_depth`.

// At most this many points are tested along a segment, evenly spaced, the ends left out...
const VISIBILITY_STEPS: u32 = 6u;
// ...and about one every this many texels of the sight depth (twice as many of the G-buffer)
// of its length on the screen.
const VISIBILITY_STEP_TEXELS: f32 = 6.0;
// How deep behind a surface the camera sees a point still counts as inside it (metres):
// thinner than a wall, thicker than the space behind a pillar would be a guess either way.
const VISIBILITY_THICKNESS: f32 = 1.0;

// What the screen knows of a segment (`clip_segment_sight`): a surface the camera sees stands
// between; every point tested lies in front of what the camera sees there, or on it, in the
// space the camera sees to be empty; or neither, some point off the screen or deep behind a
// surface, where the screen knows nothing.
const SIGHT_BLOCKED: u32 = 0u;
const SIGHT_CLEAR: u32 = 1u;
const SIGHT_UNKNOWN: u32 = 2u;

// What the screen knows of a segment, and where it is UNKNOWN, the part of it it cannot
// vouch for (fractions of the way from its first end to its second): from the last point
// before the first it could not tell to the first point after the last, so that a march of
// that part through the world covers what the screen's points do not.
struct ScreenSight {
    sight: u32,
    unknown: vec2f,
};

// What the screen knows of the segment between two points given in clip space
// (`globals.view_proj` of each: the points of a segment are linear in clip space, so its ends
// are projected once).
fn clip_segment_sight(a: vec4f, b: vec4f) -> ScreenSight {
    let size = vec2f(textureDimensions(sight_depth));
    var steps = VISIBILITY_STEPS;
    if a.w > 0.0 && b.w > 0.0 {
        let length = distance(a.xy / a.w, b.xy / b.w) * 0.5 * max(size.x, size.y);
        steps = clamp(u32(ceil(length / VISIBILITY_STEP_TEXELS)), 1u, VISIBILITY_STEPS);
    }
    // A step's own change of depth can carry it that far behind a surface it crosses.
    let thickness = max(VISIBILITY_THICKNESS, 2.0 * abs(b.w - a.w) / f32(steps));
    var sight = SIGHT_CLEAR;
    // The first and last points the screen could not tell.
    var first = steps;
    var last = 0u;
    for (var k = 0u; k < steps; k++) {
        let clip = mix(a, b, (f32(k) + 0.5) / f32(steps));
        let ndc = clip.xy / clip.w;
        var unknown = clip.w <= 0.0 || any(abs(ndc) >= vec2f(1.0));
        if !unknown {
            let texel = vec2i((ndc * vec2f(0.5, -0.5) + 0.5) * size);
            let seen = textureLoad(sight_depth, texel, 0).x;
            // (clip.w is the point's view depth; 0 seen: nothing there, empty all the way.)
            let behind = clip.w - seen;
            if seen > 0.0 && behind > 0.02 * clip.w {
                if behind < thickness {
                    return ScreenSight(SIGHT_BLOCKED, vec2f(0.0));
                }
                unknown = true;
            }
        }
        if unknown {
            sight = SIGHT_UNKNOWN;
            first = min(first, k);
            last = k;
        }
    }
    let span = vec2f((f32(first) - 0.5) / f32(steps), (f32(last) + 1.5) / f32(steps));
    return ScreenSight(sight, clamp(span, vec2f(0.0), vec2f(1.0)));
}

// Whether the segment passes no surface the camera sees.
fn clip_segment_seen(a: vec4f, b: vec4f) -> bool {
    return clip_segment_sight(a, b).sight != SIGHT_BLOCKED;
}
