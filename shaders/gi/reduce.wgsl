// GI reduction pass: one level of the node quadtree from the level below, with the article's
// custom merge filter. Similar children (normal within the threshold of their mean, position
// within a fraction of their distance to the lamp) merge: flux sums, position and normal are
// flux-weighted. Otherwise the node keeps its most significant child's position and normal
// and is marked incoherent, so light building refines it from finer levels.
#include "common.wgsl"
#include "gi_common.wgsl"

struct Level {
    // Offsets of the source and destination levels in `nodes`, and their sizes.
    src_offset: u32,
    dst_offset: u32,
    src_size: vec2u,
    dst_size: vec2u,
    pad: vec2u,
};

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> level: Level;
@group(1) @binding(2) var<storage, read_write> nodes: array<Node>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3u) {
    if any(id.xy >= level.dst_size) {
        return;
    }
    var children: array<Node, 4>;
    var count = 0u;
    var flux = vec3f(0.0);
    var weight = 0.0;
    var position = vec3f(0.0);
    var normal = vec3f(0.0);
    var dist = 0.0;
    var all_coherent = true;
    var strongest = 0u;
    for (var i = 0u; i < 4u; i++) {
        let c = id.xy * 2u + vec2u(i & 1u, i >> 1u);
        if any(c >= level.src_size) {
            continue;
        }
        let child = nodes[level.src_offset + c.y * level.src_size.x + c.x];
        if child.weight <= 0.0 {
            continue;
        }
        children[count] = child;
        if child.weight > children[strongest].weight {
            strongest = count;
        }
        count++;
        flux += child.flux;
        weight += child.weight;
        position += child.position * child.weight;
        normal += child.normal * child.weight;
        dist += child.dist * child.weight;
        all_coherent = all_coherent && child.merged == 1u;
    }
    var node: Node;
    node.flux = flux;
    node.weight = weight;
    node.merged = 1u;
    if count > 0u {
        position /= weight;
        dist /= weight;
        normal = normalize(normal + vec3f(0.0, 0.0, 1e-12));
        var similar = all_coherent;
        for (var i = 0u; i < count; i++) {
            let c = children[i];
            similar = similar && dot(c.normal, normal) >= params.cos_merge
                && length(c.position - position) <= params.merge_distance * c.dist;
        }
        if similar {
            node.position = position;
            node.normal = normal;
            node.dist = dist;
        } else {
            let s = children[strongest];
            node.position = s.position;
            node.normal = s.normal;
            node.dist = s.dist;
            node.merged = 0u;
        }
    }
    nodes[level.dst_offset + id.y * level.dst_size.x + id.x] = node;
}
