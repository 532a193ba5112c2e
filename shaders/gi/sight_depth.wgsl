// GI sight depth: the view depth the sight pass marches (visibility.wgsl), one texel for each
// 2×2 of the G-buffer, its top-left one's (the march samples points along a segment, a dozen
// G-buffer texels apart: a point sample at half the resolution serves as well). A quarter of
// the texels and a quarter of each one's bytes keep the march's scattered loads in a CPU
// device's caches: the G-buffer's Rgba32Float positions at 640×360 are 3.7 MB, this 0.2 MB.

@group(1) @binding(0) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(1) var depth: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let size = textureDimensions(depth);
    if any(id.xy >= size) {
        return;
    }
    let source = min(2u * id.xy, textureDimensions(gbuffer_position) - 1u);
    textureStore(depth, id.xy, vec4f(textureLoad(gbuffer_position, source, 0).w));
}
