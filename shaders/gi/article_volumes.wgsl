// The article's deferred shading of reflection lights: every light of the instance stream
// (article_stream.wgsl) is one instance of a light-volume mesh, drawn additively into the
// receivers it can reach, whose positions and normals it reads (the camera G-buffer's, at the
// receivers' texels: article_sub_images.wgsl). One indirect draw, whatever the number of lights.
//
// Interleaved sampling (Segovia et al. 2006): the receivers are split into N×N sub-images,
// sub-image (i, j) holding every receiver q with q mod N = (i, j), and each light is drawn
// into the sub-image of its subset only: it shades 1/N² of the receivers. article_sub_images.wgsl's
// `join` then gives each receiver every subset's light from its neighbours on its surface.
//
// A coarse light covers its whole sub-image (a quad); a fine light an icosahedron around the
// sphere of its volume (see article_stream.wgsl), its back faces only, so each receiver inside
// is shaded once wherever the camera is, and at a fixed depth, so no face is clipped. With
// `gi.visibility` (`fs_sight`, in place of `fs_main`) each fragment marches the segment from
// its receiver to its light (visibility.wgsl), as the sight pass does for the cuts' nine
// receivers a tile.
#include "common.wgsl"
#include "gi_common.wgsl"
#include "article_sub_image_layout.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<storage, read> stream: array<VolumeLight>;
// Each receiver's position (as bits) and packed normal (NO_NORMAL: no surface), where its
// sub-image holds it (article_sub_images.wgsl).
@group(1) @binding(2) var receivers: texture_2d<u32>;
// `fs_sight`'s and `fs_world`'s: the view depth the march reads (sight_depth.wgsl).
@group(2) @binding(0) var sight_depth: texture_2d<f32>;
// `fs_world`'s: the level's surfaces as voxels (plugin_gi/src/world_grid.rs).
@group(3) @binding(0) var<uniform> world: WorldGrid;
@group(3) @binding(1) var<storage, read> world_bits: array<u32>;
@group(3) @binding(2) var<storage, read> world_distances: array<u32>;

#include "visibility.wgsl"
#include "world_sight.wgsl"

// A segment's ends leave their surfaces along their normals by this many voxels, and the
// world march leaves out as many at each end (as the sight pass's, sight.wgsl).
const WORLD_LIFT: f32 = 1.5;

// An icosahedron: 12 vertices on the unit sphere's axes' golden rectangles, 20 faces, each
// counter-clockwise seen from outside.
const T: f32 = 1.618034;
const ICO_VERTICES = array<vec3f, 12>(
    vec3f(-1.0, T, 0.0), vec3f(1.0, T, 0.0), vec3f(-1.0, -T, 0.0), vec3f(1.0, -T, 0.0),
    vec3f(0.0, -1.0, T), vec3f(0.0, 1.0, T), vec3f(0.0, -1.0, -T), vec3f(0.0, 1.0, -T),
    vec3f(T, 0.0, -1.0), vec3f(T, 0.0, 1.0), vec3f(-T, 0.0, -1.0), vec3f(-T, 0.0, 1.0),
);
const ICO_INDICES = array<u32, 60>(
    0u, 11u, 5u, 0u, 5u, 1u, 0u, 1u, 7u, 0u, 7u, 10u, 0u, 10u, 11u,
    1u, 5u, 9u, 5u, 11u, 4u, 11u, 10u, 2u, 10u, 7u, 6u, 7u, 1u, 8u,
    3u, 9u, 4u, 3u, 4u, 2u, 3u, 2u, 6u, 3u, 6u, 8u, 3u, 8u, 9u,
    4u, 9u, 5u, 2u, 4u, 11u, 6u, 2u, 10u, 8u, 6u, 7u, 9u, 8u, 1u,
);
// The circumradius that puts the faces of the unit-circumradius icosahedron at distance 1
// from its centre (1 / 0.7947), and a little more: a receiver's place in its sub-image is
// rounded to whole receivers, up to N/2 of the view's receivers off.
const ENCLOSING: f32 = 1.30;

// The light travels with its fragments (flat), so a fragment loads nothing of it.
struct VolumeOut {
    @builtin(position) clip: vec4f,
    // position, area; normal, radius; flux; proxy position, proxy area; proxy normal.
    @location(0) @interpolate(flat) position_area: vec4f,
    @location(1) @interpolate(flat) normal_radius: vec4f,
    @location(2) @interpolate(flat) flux: vec3f,
    @location(3) @interpolate(flat) proxy: vec4f,
    @location(4) @interpolate(flat) proxy_normal: vec3f,
    @location(5) @interpolate(flat) subset: u32,
    // The light in clip space (`globals.view_proj`), for `fs_sight`.
    @location(6) @interpolate(flat) light_clip: vec4f,
};

// A point of the camera's clip space, placed in sub-image `s` of the target (the sub-images
// side by side, N·sub_size each way) where the receivers it falls among are: receiver q is
// evaluated at view pixel (q + ½ + receiver_offset) of the indirect target and shaded at
// pixel (q + shift) / N of its sub-image (article_sub_image_layout.wgsl). Linear in clip space, so it
// keeps perspective.
fn into_sub_image(clip: vec4f, s: u32) -> vec4f {
    let n = f32(sub_side());
    let tile = vec2f(f32(s % sub_side()), f32(s / sub_side()));
    let size = vec2f(sub_size());
    let r = vec2f(params.indirect_size);
    // The sub-image pixel (target pixels) of the view's centre, and its pixels per NDC unit.
    let centre = tile * size + (r * 0.5 - params.receiver_offset + vec2f(sub_shift()) - tile - 0.5) / n + 0.5;
    let a = r / (n * n * size);
    let b = 2.0 * centre / (n * size);
    let x = clip.x * a.x + clip.w * (b.x - 1.0);
    let y = clip.y * a.y + clip.w * (1.0 - b.y);
    // (Depth is not tested: every fragment at mid-depth, never clipped by near or far.)
    return vec4f(x, y, 0.5 * clip.w, clip.w);
}

// Corner c (−1 or 1 each way, NDC) of sub-image `s` in the target.
fn tile_corner(c: vec2f, s: u32) -> vec4f {
    let n = f32(sub_side());
    let tile = vec2f(f32(s % sub_side()), f32(s / sub_side()));
    let x = -1.0 + (2.0 * tile.x + c.x + 1.0) / n;
    let y = 1.0 - (2.0 * tile.y + 1.0 - c.y) / n;
    return vec4f(x, y, 0.5, 1.0);
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VolumeOut {
    let light = stream[i];
    var out: VolumeOut;
    out.position_area = vec4f(light.position, light.area);
    out.normal_radius = vec4f(light.normal, light.radius);
    out.flux = light.flux;
    out.subset = light.subset;
    out.light_clip = globals.view_proj * vec4f(light.position, 1.0);
    out.proxy = vec4f(light.proxy_position, light.proxy_area);
    out.proxy_normal = light.proxy_normal;
    if light.radius < 0.0 {
        // The sub-image's quad: two triangles, clockwise in the target's NDC (back faces, the
        // ones this pipeline draws).
        let corners = array<vec2f, 6>(vec2f(-1.0, -1.0), vec2f(-1.0, 1.0), vec2f(1.0, 1.0), vec2f(-1.0, -1.0),
            vec2f(1.0, 1.0), vec2f(1.0, -1.0));
        out.clip = select(vec4f(0.0), tile_corner(corners[v % 6u], light.subset), v < 6u);
        return out;
    }
    let corner = normalize(ICO_VERTICES[ICO_INDICES[v]]) * ENCLOSING * light.radius;
    out.clip = into_sub_image(globals.view_proj * vec4f(light.proxy_position + corner, 1.0), light.subset);
    return out;
}

// The fade of a fine light's volume: whole over its inner half, to nothing at its edge.
fn fade(distance: f32, radius: f32) -> f32 {
    return clamp(2.0 - 2.0 * distance / radius, 0.0, 1.0);
}

// A fragment's irradiance from its volume's light, and the receiver it is at.
struct Shaded {
    e: vec3f,
    x: vec3f,
    normal: vec3f,
};

fn shade(in: VolumeOut) -> Shaded {
    let light = VolumeLight(in.position_area.xyz, in.position_area.w, in.normal_radius.xyz, in.normal_radius.w,
        in.flux, in.subset, in.proxy.xyz, in.proxy.w, in.proxy_normal, 0u);
    let p = vec2u(in.clip.xy);
    // Only the light's own sub-image (a volume spills into its neighbours' at their edges),
    // and only receivers of the view.
    let at = sub_pixel(p);
    if at.subset != light.subset || at.q.x < 0 {
        discard;
    }
    let r = textureLoad(receivers, vec2i(p), 0);
    if r.w == NO_NORMAL {
        discard;
    }
    let x = bitcast<vec3f>(r.xyz);
    let normal = unpack_normal(r.w);
    if light.radius < 0.0 {
        return Shaded(disc_irradiance(light.flux, light.area, light.position, light.normal, x, normal), x, normal);
    }
    let w = fade(length(x - light.proxy_position), light.radius);
    if w <= 0.0 {
        discard;
    }
    let own = disc_irradiance(light.flux, light.area, light.position, light.normal, x, normal);
    let share = disc_irradiance(light.flux, light.proxy_area, light.proxy_position, light.proxy_normal, x, normal);
    return Shaded(w * (own - share), x, normal);
}

@fragment
fn fs_main(in: VolumeOut) -> @location(0) vec4f {
    return vec4f(shade(in).e, 0.0);
}

// With the light stopped where a surface stands between. (One march, to the light, for both
// of a fine light's terms: its coarse light lies about it, and a second march cost the frame
// a tenth more.)
@fragment
fn fs_sight(in: VolumeOut) -> @location(0) vec4f {
    let s = shade(in);
    let seen = select(0.0, 1.0, clip_segment_seen(globals.view_proj * vec4f(s.x, 1.0), in.light_clip));
    return vec4f(s.e * seen, 0.0);
}

// … and where the screen cannot tell (`gi.world_sight`), stopped by the level's walls.
@fragment
fn fs_world(in: VolumeOut) -> @location(0) vec4f {
    let s = shade(in);
    let screen = clip_segment_sight(globals.view_proj * vec4f(s.x, 1.0), in.light_clip);
    var seen = screen.sight != SIGHT_BLOCKED;
    if screen.sight == SIGHT_UNKNOWN {
        let lift = WORLD_LIFT * world.voxel;
        let light = in.position_area.xyz + in.normal_radius.xyz * lift;
        seen = world_segment_clear(s.x + s.normal * lift, light, lift, screen.unknown);
    }
    return vec4f(s.e * select(0.0, 1.0, seen), 0.0);
}
