//! The conformance samples: one small glTF document per feature a loader must get right.
//!
//! Each function returns the document; [`SAMPLES`] names them all with a file name. Buffers and
//! images are embedded (`data:` URIs, or a bufferView), so a sample is one self-contained file.

use glam::Vec3;
use serde_json::{json, Value};

use crate::writer::{png, png_data_uri, Bin, FLOAT, QUAD, TRI, UNSIGNED_BYTE, UNSIGNED_SHORT};

/// A sample: builds its document.
pub type Sample = fn() -> Value;

/// Every sample with the file name it is written under.
pub const SAMPLES: [(&str, Sample); 7] = [
    ("red_box.gltf", red_box),
    ("cameras.gltf", cameras),
    ("vertex_colours.gltf", vertex_colours),
    ("textured_box.gltf", textured_box),
    ("texture_coordinates.gltf", texture_coordinates),
    ("orientation.gltf", orientation),
    ("simple_meshes.gltf", simple_meshes),
];

// --- A unit cube, shared by the boxes -------------------------------------------------------

/// Outward normal and "up" of each face of the cube, as seen from outside: +Y on the sides,
/// towards -Z on top and +Z underneath.
const FACES: [([f32; 3], [f32; 3]); 6] = [
    ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ([0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
    ([0.0, -1.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
    ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
];

/// A face's corners as steps along its right and up from its centre, with their uvs: top-left,
/// bottom-left, bottom-right, top-right.
const CORNERS: [(f32, f32, [f32; 2]); 4] =
    [(-1.0, 1.0, [0.0, 0.0]), (-1.0, -1.0, [0.0, 1.0]), (1.0, -1.0, [1.0, 1.0]), (1.0, 1.0, [1.0, 0.0])];

/// A unit cube centred on the origin with four vertices per face (each carrying its face's
/// normal), 16-bit indices, counter-clockwise seen from outside.
struct Cube {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// (0, 0) at each face's top-left corner seen from outside: the image upright on every face.
    uvs: Vec<[f32; 2]>,
    indices: Vec<u16>,
}

fn cube() -> Cube {
    let mut cube = Cube { positions: vec![], normals: vec![], uvs: vec![], indices: vec![] };
    for (normal, up) in FACES {
        let (n, up) = (Vec3::from(normal), Vec3::from(up));
        let right = up.cross(n); // seen from outside, looking along -n
        let first = cube.positions.len() as u16;
        for (x, y, uv) in CORNERS {
            cube.positions.push((0.5 * (n + x * right + y * up)).into());
            cube.normals.push(normal);
            cube.uvs.push(uv);
        }
        cube.indices.extend([0, 1, 2, 0, 2, 3].map(|i| first + i));
    }
    cube
}

// --- The samples ---------------------------------------------------------------------------

/// [`red_box`]'s material colour.
pub const RED: [f32; 4] = [0.8, 0.0, 0.0, 1.0];
/// [`red_box`]'s root: a column-major node `matrix` turning +Y to -Z and +Z to +Y (a rotation of
/// -90° about X, how a Z-up model is made Y-up).
pub const SWAP_Y_Z: [f32; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
/// The box node's translation and scale, inside the root.
pub const BOX_TRANSLATION: [f32; 3] = [0.0, 2.0, 0.0];
pub const BOX_SCALE: [f32; 3] = [1.0, 3.0, 1.0];

/// Node matrices and a hierarchy: the cube (normals, 16-bit indices, material [`RED`]) on a
/// child node (translation and scale) of a root with the node matrix [`SWAP_Y_Z`].
pub fn red_box() -> Value {
    let cube = cube();
    let mut bin = Bin::default();
    let positions = bin.vec3(&cube.positions);
    let normals = bin.vec3(&cube.normals);
    let indices = bin.u16s(&cube.indices);
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "root", "matrix": SWAP_Y_Z, "children": [1]},
            {"name": "box", "mesh": 0, "translation": BOX_TRANSLATION, "scale": BOX_SCALE},
        ],
        "meshes": [{"name": "box", "primitives": [
            {"attributes": {"POSITION": positions, "NORMAL": normals}, "indices": indices, "material": 0},
        ]}],
        "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": RED, "metallicFactor": 0.0}}],
    }))
}

/// [`cameras`]' quad: a rotation of -45° about X (x, y, z, w), tilting its +Z face up.
pub const QUAD_ROTATION: [f32; 4] = [-0.382_683_43, 0.0, 0.0, 0.923_879_5];
/// The perspective camera: turned 30° to the left (about +Y) at `PERSPECTIVE_AT`, looking at the quad.
pub const PERSPECTIVE_ROTATION: [f32; 4] = [0.0, 0.258_819_04, 0.0, 0.965_925_8];
pub const PERSPECTIVE_AT: [f32; 3] = [2.0, 0.35, 2.25];
/// The orthographic camera: turned -90° about X (looking down) at `ORTHOGRAPHIC_AT`.
pub const ORTHOGRAPHIC_ROTATION: [f32; 4] = [-0.707_106_77, 0.0, 0.0, 0.707_106_77];
pub const ORTHOGRAPHIC_AT: [f32; 3] = [0.5, 3.0, -0.35];

/// Cameras from the file: a perspective (yfov 0.7, aspect 1.5, znear 0.05, zfar 50) and an
/// orthographic one (xmag 0.8, ymag 0.6, znear 0.01, zfar 10), in that order, on nodes with a
/// quaternion and a translation; both see the unit quad [`QUAD`] on a node rotated by
/// [`QUAD_ROTATION`]. The quad has no normals (flat ones are made) and no material (the spec's
/// default one).
pub fn cameras() -> Value {
    let mut bin = Bin::default();
    let positions = bin.vec3(&QUAD);
    let indices = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "quad", "mesh": 0, "rotation": QUAD_ROTATION},
            {"name": "perspective", "camera": 0, "rotation": PERSPECTIVE_ROTATION, "translation": PERSPECTIVE_AT},
            {"name": "orthographic", "camera": 1, "rotation": ORTHOGRAPHIC_ROTATION, "translation": ORTHOGRAPHIC_AT},
        ],
        "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": positions}, "indices": indices}]}],
        "cameras": [
            {"name": "perspective", "type": "perspective",
             "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.05, "zfar": 50.0}},
            {"name": "orthographic", "type": "orthographic",
             "orthographic": {"xmag": 0.8, "ymag": 0.6, "znear": 0.01, "zfar": 10.0}},
        ],
    }))
}

/// [`vertex_colours`]' colours at the quad's four corners (in [`QUAD`]'s order), as 8-bit
/// values so every encoding holds them exactly: `c / 255`.
pub const CORNER_COLOURS: [[u8; 4]; 4] = [[255, 0, 0, 255], [0, 255, 0, 128], [0, 0, 255, 0], [255, 255, 255, 64]];
/// How each primitive of [`vertex_colours`] stores `COLOR_0`, in order: componentType and
/// type (the integer ones normalized).
pub const COLOUR_ENCODINGS: [(u32, &str); 6] = [
    (FLOAT, "VEC4"),
    (FLOAT, "VEC3"),
    (UNSIGNED_BYTE, "VEC4"),
    (UNSIGNED_BYTE, "VEC3"),
    (UNSIGNED_SHORT, "VEC4"),
    (UNSIGNED_SHORT, "VEC3"),
];
/// Its (opaque) material's base colour; the colours' alphas are read but not used.
pub const GREY: [f32; 4] = [0.8, 0.8, 0.8, 1.0];

/// Vertex colours: one mesh of six primitives, each the quad (side by side along +X, with
/// normals) with `COLOR_0` = [`CORNER_COLOURS`] in one of the [`COLOUR_ENCODINGS`].
pub fn vertex_colours() -> Value {
    let mut bin = Bin::default();
    let normals = bin.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let indices = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let mut primitives = vec![];
    for (k, (component, ty)) in COLOUR_ENCODINGS.into_iter().enumerate() {
        let positions = bin.vec3(&QUAD.map(|[x, y, z]| [x + 1.5 * k as f32, y, z]));
        let channels = if ty == "VEC4" { 4 } else { 3 };
        let values = CORNER_COLOURS.iter().flat_map(|c| &c[..channels]);
        let bytes: Vec<u8> = match component {
            FLOAT => values.flat_map(|&v| (f32::from(v) / 255.0).to_le_bytes()).collect(),
            UNSIGNED_BYTE => values.copied().collect(),
            _ => values.flat_map(|&v| (u16::from(v) * 257).to_le_bytes()).collect(),
        };
        let colours = bin.typed(&bytes, component, 4, ty, component != FLOAT);
        primitives.push(json!({
            "attributes": {"POSITION": positions, "NORMAL": normals, "COLOR_0": colours},
            "indices": indices,
            "material": 0,
        }));
    }
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "colours", "mesh": 0}],
        "meshes": [{"name": "colours", "primitives": primitives}],
        "materials": [{"name": "grey", "alphaMode": "OPAQUE", "pbrMetallicRoughness": {"baseColorFactor": GREY}}],
    }))
}

/// The 2×2 image of the textured samples, row-major from its top-left: red, green / blue, white.
pub const QUADRANT_COLOURS: [[u8; 4]; 4] = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]];

fn quadrants_png() -> Vec<u8> {
    png(2, 2, QUADRANT_COLOURS.as_flattened())
}

/// A textured box: the cube with `TEXCOORD_0` (the image upright on each face) and a base
/// colour texture, the PNG of [`QUADRANT_COLOURS`] in a bufferView, with a sampler.
pub fn textured_box() -> Value {
    let cube = cube();
    let mut bin = Bin::default();
    let positions = bin.vec3(&cube.positions);
    let normals = bin.vec3(&cube.normals);
    let uvs = bin.vec2(&cube.uvs);
    let indices = bin.u16s(&cube.indices);
    let image = bin.view(&quadrants_png());
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "box", "mesh": 0}],
        "meshes": [{"name": "box", "primitives": [{
            "attributes": {"POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs},
            "indices": indices,
            "material": 0,
        }]}],
        "materials": [{"name": "quadrants",
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        // magFilter LINEAR, minFilter NEAREST_MIPMAP_LINEAR, wrapS REPEAT, wrapT MIRRORED_REPEAT:
        // every field set, S and T different so a swap shows.
        "samplers": [{"magFilter": 9729, "minFilter": 9986, "wrapS": 10497, "wrapT": 33648}],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
    }))
}

/// [`texture_coordinates`]' quad corners, top-left, top-right, bottom-right, bottom-left (a
/// 1 m square centred on the origin, facing +Z), and the `TEXCOORD_0` at each: glTF's uv
/// origin is the image's top-left, so the image appears upright seen from +Z.
pub const TEXCOORD_CORNERS: [([f32; 3], [f32; 2]); 4] = [
    ([-0.5, 0.5, 0.0], [0.0, 0.0]),
    ([0.5, 0.5, 0.0], [1.0, 0.0]),
    ([0.5, -0.5, 0.0], [1.0, 1.0]),
    ([-0.5, -0.5, 0.0], [0.0, 1.0]),
];
/// Its camera's distance in front of the quad; with tan(yfov / 2) = 1/2 the quad fills the
/// middle half of a square frame, across and down.
pub const TEXCOORD_CAMERA_DISTANCE: f32 = 2.0;

/// Texture coordinates: the quad [`TEXCOORD_CORNERS`] textured with the image of
/// [`QUADRANT_COLOURS`] (a `data:` URI; nearest filtering, clamped), seen straight on from a
/// perspective camera on +Z.
pub fn texture_coordinates() -> Value {
    let mut bin = Bin::default();
    let positions = bin.vec3(&TEXCOORD_CORNERS.map(|(p, _)| p));
    let normals = bin.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uvs = bin.vec2(&TEXCOORD_CORNERS.map(|(_, uv)| uv));
    let indices = bin.u16s(&[0, 3, 2, 0, 2, 1]);
    let yfov = 2.0 * 0.5f32.atan();
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "quad", "mesh": 0},
            {"name": "camera", "camera": 0, "translation": [0.0, 0.0, TEXCOORD_CAMERA_DISTANCE]},
        ],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs},
            "indices": indices,
            "material": 0,
        }]}],
        "materials": [{"name": "quadrants",
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        // NEAREST, CLAMP_TO_EDGE: each quadrant one flat colour up to its edges.
        "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}],
        "images": [{"uri": png_data_uri(&quadrants_png())}],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": yfov, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}],
    }))
}

/// [`orientation`]'s arrow: a right triangle, legs 1 along +X and 2 along +Y (so every turn
/// and mirror shows), facing +Z, with normals and 8-bit indices.
pub const ARROW: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]];

/// Orientation: the arrow on five nodes, each with a mesh named after its transform —
/// `quaternion` (90° about +Z, then +5 X), `matrix` (a column-major 90° about +X, then +5 Y),
/// `scaled` (scale 2 along X, 90° about +Y, then +5 Z), `mirrored` (scale -1 along X, then -5 X),
/// `child` (+1 X inside a parent turned 90° about +Z and moved -5 Y).
pub fn orientation() -> Value {
    let mut bin = Bin::default();
    let positions = bin.vec3(&ARROW);
    let normals = bin.vec3(&[[0.0, 0.0, 1.0]; 3]);
    let indices = bin.u8s(&[0, 1, 2]);
    let names = ["quaternion", "matrix", "scaled", "mirrored", "child"];
    let meshes: Vec<Value> = names
        .iter()
        .map(|name| {
            json!({"name": name, "primitives": [
                {"attributes": {"POSITION": positions, "NORMAL": normals}, "indices": indices},
            ]})
        })
        .collect();
    let s = std::f32::consts::FRAC_1_SQRT_2;
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
        "nodes": [
            {"name": "quaternion", "mesh": 0, "rotation": [0.0, 0.0, s, s], "translation": [5.0, 0.0, 0.0]},
            {"name": "matrix", "mesh": 1,
             "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 5.0, 0.0, 1.0]},
            {"name": "scaled", "mesh": 2, "scale": [2.0, 1.0, 1.0], "rotation": [0.0, s, 0.0, s],
             "translation": [0.0, 0.0, 5.0]},
            {"name": "mirrored", "mesh": 3, "scale": [-1.0, 1.0, 1.0], "translation": [-5.0, 0.0, 0.0]},
            {"name": "parent", "rotation": [0.0, 0.0, s, s], "translation": [0.0, -5.0, 0.0], "children": [5]},
            {"name": "child", "mesh": 4, "translation": [1.0, 0.0, 0.0]},
        ],
        "meshes": meshes,
    }))
}

/// [`simple_meshes`]' triangles without indices: two, as six positions (a unit quad).
pub const UNINDEXED: [[f32; 3]; 6] =
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

/// Several meshes and a non-indexed primitive: mesh `triangle` ([`TRI`], 32-bit indices) on two
/// nodes (the second at +2 X), and mesh `unindexed` ([`UNINDEXED`], no indices) at +4 X. No
/// normals and no materials.
pub fn simple_meshes() -> Value {
    let mut bin = Bin::default();
    let triangle = bin.vec3(&TRI);
    let indices = bin.u32s(&[0, 1, 2]);
    let unindexed = bin.vec3(&UNINDEXED);
    bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 0, "translation": [2.0, 0.0, 0.0]},
            {"mesh": 1, "translation": [4.0, 0.0, 0.0]},
        ],
        "meshes": [
            {"name": "triangle", "primitives": [{"attributes": {"POSITION": triangle}, "indices": indices}]},
            {"name": "unindexed", "primitives": [{"attributes": {"POSITION": unindexed}}]},
        ],
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_are_counter_clockwise_seen_from_outside() {
        let cube = cube();
        assert_eq!((cube.positions.len(), cube.indices.len()), (24, 36));
        for t in cube.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(cube.positions[t[k] as usize]));
            let n = Vec3::from(cube.normals[t[0] as usize]);
            assert!((b - a).cross(c - a).normalize().dot(n) > 0.999);
            assert!(a.dot(n) > 0.0, "each face's normal points away from the centre");
        }
    }
}
