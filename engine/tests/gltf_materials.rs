//! glTF material features as the renderer draws them, read back as linear values (what
//! `headlamp render --view albedo|direct|final --out x.exr` writes): vertex colours, the spec's
//! default material, samplers, alpha cut-outs (camera view, the detached lamp's shadows and its
//! own G-buffer, which the GI's flux reads), sidedness, emissive textures with
//! `KHR_materials_emissive_strength`, and `KHR_texture_transform` with the second uv set.
//!
//! Scenes are tiny quads in front of a camera at the origin looking down -Z. Some come from
//! glTF files written here (to test the loader and renderer together), the rest are built as
//! `Scene`s directly (the loader's side of those is in engine/scene/tests/gltf.rs).

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::{Quat, Vec2, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{read_texture, HeadlessTarget, ImageKind, RenderedImage};
use engine::passes::LAMP_MAP_SIZE;
use engine::renderer::Renderer;
use engine::scene::{
    encode_base64 as base64, load_gltf, AlphaMode, Filter, HeadlampProfile, IntensityDistribution, Material, Mesh,
    Sampler, Scene, Texture, TextureRef, TextureTransform, Vertex, Wrap,
};

const SIZE: (u32, u32) = (96, 64);
const FOV_Y: f32 = 60.0 * PI / 180.0;

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

fn lamp() -> Headlamp {
    Headlamp::new(HeadlampProfile {
        power: 1.0,
        fov_y: FOV_Y,
        color: [1.0; 3],
        distribution: IntensityDistribution::Uniform,
    })
}

fn lamp_off() -> Headlamp {
    let mut lamp = lamp();
    lamp.on = false;
    lamp
}

fn view(camera: Camera, headlamp: Headlamp) -> ViewState {
    ViewState {
        camera,
        headlamp,
        lights: vec![],
        exposure: 1.0,
        instances: vec![],
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

/// The camera of most tests: at the origin, looking down -Z.
fn camera() -> Camera {
    Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y)
}

/// One frame of view `name` (linear values), and the renderer (for its graph textures).
fn render(gpu: &Gpu, scene: &Scene, name: &str, view: &ViewState) -> (Renderer, image::Rgba32FImage) {
    let mut renderer = Renderer::new(gpu, scene, vec![]).unwrap();
    renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    match target.render(gpu, &mut renderer, view).unwrap() {
        RenderedImage::Linear(img) => (renderer, img),
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

/// World direction (not normalised) through the centre of pixel (x, y) of `camera`.
fn pixel_ray(camera: &Camera, x: u32, y: u32) -> Vec3 {
    let tan_half = (FOV_Y * 0.5).tan();
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let ndc_x = (x as f32 + 0.5) / SIZE.0 as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / SIZE.1 as f32 * 2.0;
    camera.rotation * Vec3::new(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0)
}

/// Where the ray through pixel (x, y) of [`camera`] meets the plane z = `z`: (x, y) in metres.
fn on_plane(x: u32, y: u32, z: f32) -> Vec2 {
    let d = pixel_ray(&camera(), x, y);
    Vec2::new(d.x, d.y) * (z / d.z)
}

fn pixels() -> impl Iterator<Item = (u32, u32)> {
    (0..SIZE.1).flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
}

fn rgb(img: &image::Rgba32FImage, x: u32, y: u32) -> Vec3 {
    let p = img.get_pixel(x, y);
    Vec3::new(p[0], p[1], p[2])
}

/// An axis-aligned rectangle [x0, x1] × [y0, y1] at depth `z`, facing +Z (counter-clockwise
/// seen from the camera), uv (0, 0) at its top-left and (1, 1) at its bottom-right; uv1 is
/// (1 − u, v), the image mirrored.
#[derive(Clone, Copy)]
struct Rect {
    x: [f32; 2],
    y: [f32; 2],
    z: f32,
}

impl Rect {
    fn new(x0: f32, x1: f32, y0: f32, y1: f32, z: f32) -> Self {
        Self { x: [x0, x1], y: [y0, y1], z }
    }

    fn corners(&self) -> [[f32; 3]; 4] {
        let ([x0, x1], [y0, y1], z) = (self.x, self.y, self.z);
        [[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
    }

    fn uvs(&self) -> [[f32; 2]; 4] {
        [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]
    }

    /// Vertices with colour `color` (all four), the winding facing +Z or, `flipped`, -Z.
    fn mesh(&self, name: &str, material: usize, color: [f32; 4], flipped: bool) -> Mesh {
        let normal = if flipped { [0.0, 0.0, -1.0] } else { [0.0, 0.0, 1.0] };
        let vertices = self
            .corners()
            .iter()
            .zip(self.uvs())
            .map(|(&p, uv)| Vertex { color, uv1: [1.0 - uv[0], uv[1]], ..Vertex::new(p, normal, uv) })
            .collect();
        let indices = if flipped { vec![0, 2, 1, 0, 3, 2] } else { vec![0, 1, 2, 0, 2, 3] };
        Mesh { name: name.into(), vertices, indices, material }
    }

    /// The rectangle's uv at a point (x, y) of its plane, if the point lies at least `margin`
    /// (in uv units) inside it.
    fn uv_at(&self, p: Vec2, margin: f32) -> Option<Vec2> {
        let u = (p.x - self.x[0]) / (self.x[1] - self.x[0]);
        let v = (self.y[1] - p.y) / (self.y[1] - self.y[0]);
        let inside = |t: f32| t >= margin && t <= 1.0 - margin;
        (inside(u) && inside(v)).then_some(Vec2::new(u, v))
    }

    /// The uv seen at pixel (x, y) of [`camera`], `margin` inside the rectangle.
    fn uv_at_pixel(&self, x: u32, y: u32, margin: f32) -> Option<Vec2> {
        self.uv_at(on_plane(x, y, self.z), margin)
    }
}

/// A big wall at z = -4 of albedo `rho`, drawn from both sides (the engine's default material).
fn back_wall(scene: &mut Scene, rho: f32) {
    scene.materials.push(Material { base_color: [rho, rho, rho, 1.0], ..Material::default() });
    let m = scene.materials.len() - 1;
    scene.meshes.push(Rect::new(-20.0, 20.0, -20.0, 20.0, -4.0).mesh("wall", m, [1.0; 4], false));
}

/// A texture of two texels side by side, left then right, RGBA8 (sRGB colour, linear alpha).
fn two_texels(left: [u8; 4], right: [u8; 4]) -> Texture {
    Texture { name: "two texels".into(), width: 2, height: 1, rgba8: [left, right].concat() }
}

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];

fn nearest(wrap: Wrap) -> Sampler {
    Sampler {
        wrap_u: wrap,
        wrap_v: wrap,
        mag_filter: Filter::Nearest,
        min_filter: Filter::Nearest,
        mipmap_filter: Some(Filter::Nearest),
    }
}

fn textured(texture: usize, sampler: Sampler) -> Material {
    Material {
        name: "textured".into(),
        base_color: [1.0; 4],
        base_color_texture: Some(TextureRef { sampler, ..TextureRef::new(texture) }),
        ..Material::default()
    }
}

/// Which of [`RED`] (0) or [`GREEN`] (1) a pure pixel is; None for anything else.
fn texel_of(c: Vec3) -> Option<usize> {
    if (c - Vec3::X).abs().max_element() < 1e-3 {
        Some(0)
    } else if (c - Vec3::Y).abs().max_element() < 1e-3 {
        Some(1)
    } else {
        None
    }
}

// --- A minimal glTF writer: one quad, its buffer embedded as base64. ---

fn png_uri(width: u32, height: u32, rgba: &[u8]) -> String {
    let img = image::RgbaImage::from_raw(width, height, rgba.to_vec()).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    format!("data:image/png;base64,{}", base64(&out.into_inner()))
}

/// Loads a glTF file (written to a scratch folder, removed again) with `rect` as one
/// primitive: POSITION, NORMAL, TEXCOORD_0 (accessors 0-2), indices (3) and, given as (bytes,
/// accessor JSON fields), a COLOR_0 accessor (4). `material` is the material's JSON (None: the
/// primitive has none); `rest` adds top-level members (",\"textures\": [...]").
fn load_quad_gltf(name: &str, rect: Rect, colors: Option<(&[u8], &str)>, material: Option<&str>, rest: &str) -> Scene {
    let mut data: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut push = |bytes: &[u8], data: &mut Vec<u8>| {
        while !data.len().is_multiple_of(4) {
            data.push(0);
        }
        views.push(format!("{{\"buffer\": 0, \"byteOffset\": {}, \"byteLength\": {}}}", data.len(), bytes.len()));
        data.extend_from_slice(bytes);
    };
    let f32s = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    push(&f32s(rect.corners().as_flattened()), &mut data);
    push(&f32s(&[0.0, 0.0, 1.0].repeat(4)), &mut data);
    push(&f32s(rect.uvs().as_flattened()), &mut data);
    push(&[0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()).collect::<Vec<u8>>(), &mut data);
    let ([x0, x1], [y0, y1], z) = (rect.x, rect.y, rect.z);
    let mut accessors = vec![
        format!("{{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [{x0}, {y0}, {z}], \"max\": [{x1}, {y1}, {z}]}}"),
        "{\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}".to_string(),
        "{\"bufferView\": 2, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"}".to_string(),
        "{\"bufferView\": 3, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}".to_string(),
    ];
    let mut attributes = "\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2".to_string();
    if let Some((bytes, fields)) = colors {
        push(bytes, &mut data);
        accessors.push(format!("{{\"bufferView\": 4, \"count\": 4, {fields}}}"));
        attributes.push_str(", \"COLOR_0\": 4");
    }
    let (material_ref, materials) = match material {
        Some(m) => (", \"material\": 0".to_string(), format!(", \"materials\": [{m}]")),
        None => (String::new(), String::new()),
    };
    let json = format!(
        "{{\"asset\": {{\"version\": \"2.0\"}}, \"scenes\": [{{\"nodes\": [0]}}], \"nodes\": [{{\"mesh\": 0}}],
          \"meshes\": [{{\"primitives\": [{{\"attributes\": {{{attributes}}}, \"indices\": 3{material_ref}}}]}}],
          \"buffers\": [{{\"byteLength\": {}, \"uri\": \"data:application/octet-stream;base64,{}\"}}],
          \"bufferViews\": [{}], \"accessors\": [{}]{materials}{rest}}}",
        data.len(),
        base64(&data),
        views.join(", "),
        accessors.join(", "),
    );
    let dir = std::env::temp_dir().join(format!("headlamp-gltf-materials-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, json).unwrap();
    let scene = load_gltf(&path);
    let _ = std::fs::remove_dir_all(&dir);
    scene.unwrap_or_else(|e| panic!("{e}"))
}

// --- The tests. ---

#[test]
fn vertex_colours_tint_the_albedo_per_vertex() {
    // Left corners red, right corners blue (normalized unsigned bytes), times a base colour
    // factor (0.5, 1, 1): across the quad the albedo runs from (0.5, 0, 0) to (0, 0, 1).
    let rect = Rect::new(-1.0, 1.0, -0.6, 0.6, -2.0);
    let colours: Vec<u8> = [[255, 0, 0, 255], [0, 0, 255, 255], [0, 0, 255, 255], [255, 0, 0, 255]].concat();
    let scene = load_quad_gltf(
        "colours",
        rect,
        Some((&colours, "\"componentType\": 5121, \"normalized\": true, \"type\": \"VEC4\"")),
        Some("{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.5, 1.0, 1.0, 1.0], \"metallicFactor\": 0.0}}"),
        "",
    );

    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let (mut checked, mut worst) = (0, 0.0f32);
    for (x, y) in pixels() {
        if let Some(uv) = rect.uv_at_pixel(x, y, 0.02) {
            let t = uv.x;
            let want = Vec3::new(0.5 * (1.0 - t), 0.0, t);
            let err = (rgb(&albedo, x, y) - want).abs().max_element();
            worst = worst.max(err);
            assert!(err < 4e-3, "pixel ({x}, {y}), u = {t}: albedo {}, expected {want}", rgb(&albedo, x, y));
            checked += 1;
        }
    }
    assert!(checked > 1500, "only {checked} pixels on the quad");
    println!("vertex colours: {checked} pixels, worst error {worst:.5}");
}

#[test]
fn a_primitive_without_material_is_the_specs_white_rough_metal() {
    // glTF 2.0's default material: base colour 1, metallic 1, roughness 1. A metal has no
    // diffuse albedo (nothing for the GI to reflect); its specular lobe under the lamp at the
    // eye gives f·cos = F·D·V·cos = 1·(1/π)·(1/(4 cos))·cos: radiance I/(4π d²) at any angle.
    let rect = Rect::new(-1.0, 1.0, -0.6, 0.6, -2.0);
    let scene = load_quad_gltf("no_material", rect, None, None, "");
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let (_, direct) = render(&gpu, &scene, "direct", &view(camera(), lamp()));
    let mut checked = 0;
    for (x, y) in pixels() {
        if rect.uv_at_pixel(x, y, 0.02).is_some() {
            assert_eq!(rgb(&albedo, x, y), Vec3::ZERO, "pixel ({x}, {y})");
            // The ray's z is -1: the quad at z = -2 is twice it away.
            let d2 = (pixel_ray(&camera(), x, y) * 2.0).length_squared();
            let want = 1.0 / (4.0 * std::f32::consts::PI * d2);
            let got = rgb(&direct, x, y);
            assert!(
                ((got - Vec3::splat(want)).abs() / want).max_element() < 0.01,
                "pixel ({x}, {y}): {got}, expected {want}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1500, "only {checked} pixels on the quad");
}

#[test]
fn a_metallic_roughness_texture_is_read_linearly_from_blue_and_scales_the_metallic_factor() {
    // Base colour 0.5, metallicFactor 1 × texture [blue 255 | blue 128] (nearest): the left half
    // is a metal (diffuse albedo 0), the right half metallic 128/255 read linearly (an sRGB
    // decode would give 0.216), diffuse albedo (1 − 0.502)·0.5.
    let rect = Rect::new(-1.0, 1.0, -0.6, 0.6, -2.0);
    let texture = png_uri(2, 1, &[0, 255, 255, 255, 0, 255, 128, 255]);
    let material = "{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.5, 0.5, 0.5, 1.0],
        \"metallicRoughnessTexture\": {\"index\": 0}}}";
    let rest = format!(
        ", \"textures\": [{{\"source\": 0, \"sampler\": 0}}],
          \"samplers\": [{{\"magFilter\": 9728, \"minFilter\": 9728, \"wrapS\": 33071, \"wrapT\": 33071}}],
          \"images\": [{{\"uri\": \"{texture}\"}}]"
    );
    let scene = load_quad_gltf("metallic_roughness", rect, None, Some(material), &rest);
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let mut counts = [0; 2];
    for (x, y) in pixels() {
        let Some(uv) = rect.uv_at_pixel(x, y, 0.02) else { continue };
        if (uv.x - 0.5).abs() < 0.05 {
            continue;
        }
        let right = uv.x > 0.5;
        let want = if right { (1.0 - 128.0 / 255.0) * 0.5 } else { 0.0 };
        let got = rgb(&albedo, x, y);
        assert!(
            (got - Vec3::splat(want)).abs().max_element() < 2e-3,
            "pixel ({x}, {y}), u = {}: {got}, expected {want}",
            uv.x
        );
        counts[usize::from(right)] += 1;
    }
    assert!(counts.iter().all(|&n| n > 500), "{counts:?}");
}

/// The texel a nearest-filtering sampler picks along u for a two-texel-wide image.
fn nearest_texel(wrap: Wrap, u: f32) -> usize {
    let u = match wrap {
        Wrap::Repeat => u - u.floor(),
        Wrap::ClampToEdge => u.clamp(0.0, 1.0),
        Wrap::MirroredRepeat => {
            let m = u.rem_euclid(2.0);
            if m < 1.0 {
                m
            } else {
                2.0 - m
            }
        }
    };
    ((u * 2.0).floor() as usize).min(1)
}

#[test]
fn clamp_mirror_and_repeat_samplers_differ_where_uvs_leave_the_unit_square() {
    // Four strips, each u from -1 to 2 across, sampling [red | green]: repeat, clamp and
    // mirror with nearest filtering, then repeat with linear filtering.
    let strips = [
        Rect::new(-1.5, 1.5, 0.6, 1.05, -2.0),
        Rect::new(-1.5, 1.5, 0.05, 0.5, -2.0),
        Rect::new(-1.5, 1.5, -0.5, -0.05, -2.0),
        Rect::new(-1.5, 1.5, -1.05, -0.6, -2.0),
    ];
    let linear = Sampler { wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat, ..Sampler::default() };
    let samplers = [nearest(Wrap::Repeat), nearest(Wrap::ClampToEdge), nearest(Wrap::MirroredRepeat), linear];
    let mut scene = Scene { textures: vec![two_texels(RED, GREEN)], ..Scene::default() };
    for (i, (strip, sampler)) in strips.iter().zip(samplers).enumerate() {
        scene.materials.push(textured(0, sampler));
        let mut mesh = strip.mesh(&format!("strip{i}"), i, [1.0; 4], false);
        for v in &mut mesh.vertices {
            v.uv[0] = v.uv[0] * 3.0 - 1.0;
        }
        scene.meshes.push(mesh);
    }
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));

    // u across a strip: its uv_at (0..1) mapped like the vertices.
    let u_at = |strip: &Rect, x: u32, y: u32| strip.uv_at_pixel(x, y, 0.01).map(|uv| uv.x * 3.0 - 1.0);
    let wraps = [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat];
    // Per strip, per column outside u in [0, 1]: the texel seen there.
    let mut outside = [[None; SIZE.0 as usize]; 3];
    for (i, (strip, wrap)) in strips.iter().zip(wraps).enumerate() {
        let mut checked = 0;
        for (x, y) in pixels() {
            let Some(u) = u_at(strip, x, y) else { continue };
            // Clear of texel boundaries (every half unit of u), where the choice is the rasteriser's.
            let f = (u * 2.0).rem_euclid(1.0);
            if !(0.1..=0.9).contains(&f) {
                continue;
            }
            let want = nearest_texel(wrap, u);
            let got = texel_of(rgb(&albedo, x, y));
            assert_eq!(got, Some(want), "{wrap:?} strip, pixel ({x}, {y}), u = {u}: albedo {}", rgb(&albedo, x, y));
            if !(0.0..=1.0).contains(&u) {
                outside[i][x as usize] = got;
            }
            checked += 1;
        }
        assert!(checked > 400, "{wrap:?}: only {checked} pixels");
    }
    // The three wrap modes show different texels outside the unit square.
    let differ = |a: usize, b: usize| (0..SIZE.0 as usize).filter(|&x| outside[a][x] != outside[b][x]).count();
    let (repeat_clamp, clamp_mirror, mirror_repeat) = (differ(0, 1), differ(1, 2), differ(2, 0));
    println!("columns outside [0, 1] that differ: repeat/clamp {repeat_clamp}, clamp/mirror {clamp_mirror}, mirror/repeat {mirror_repeat}");
    assert!(repeat_clamp > 10 && clamp_mirror > 10 && mirror_repeat > 10);

    // Nearest keeps every pixel a pure texel; linear (magnified ~14×) blends almost all.
    let (mut blended, mut total) = (0, 0);
    for (x, y) in pixels() {
        if u_at(&strips[3], x, y).is_some() {
            total += 1;
            let c = rgb(&albedo, x, y);
            if c.x > 0.02 && c.y > 0.02 {
                blended += 1;
            }
        }
    }
    println!("linear: {blended} of {total} pixels blend red and green");
    assert!(blended * 10 > total * 8, "linear filtering blended only {blended} of {total} pixels");
}

#[test]
fn a_mask_cut_out_shows_the_wall_behind_it_and_blend_is_cut_at_one_half() {
    // MASK, cutoff 0.45: alpha = factor 0.8 × texture (1 | 0.8) × vertex 0.625 = 0.5 | 0.4, so
    // the left half stays and the right half is a hole onto the wall behind. Dropping any of
    // the three factors keeps both halves.
    let mut scene = Scene::default();
    back_wall(&mut scene, 0.3);
    scene.textures.push(two_texels([255; 4], [255, 255, 255, 204]));
    scene.textures.push(two_texels([255; 4], [255, 255, 255, 77]));
    let mask = Rect::new(-1.0, 1.0, 0.1, 0.9, -2.0);
    let blend = Rect::new(-1.0, 1.0, -0.9, -0.1, -2.0);
    scene.materials.push(Material {
        base_color: [0.9, 0.9, 0.9, 0.8],
        alpha_mode: AlphaMode::Mask { cutoff: 0.45 },
        ..textured(0, nearest(Wrap::ClampToEdge))
    });
    // BLEND is drawn as MASK at 0.5: alpha 1 | 0.3.
    scene.materials.push(Material {
        base_color: [0.6, 0.6, 0.6, 1.0],
        alpha_mode: AlphaMode::Blend,
        ..textured(1, nearest(Wrap::ClampToEdge))
    });
    scene.meshes.push(mask.mesh("mask", 1, [1.0, 1.0, 1.0, 0.625], false));
    scene.meshes.push(blend.mesh("blend", 2, [1.0; 4], false));
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let (_, direct) = render(&gpu, &scene, "direct", &view(camera(), lamp()));
    let mut counts = [[0usize; 2]; 2];
    for (x, y) in pixels() {
        for (k, (rect, rho)) in [(mask, 0.9), (blend, 0.6)].into_iter().enumerate() {
            let Some(uv) = rect.uv_at_pixel(x, y, 0.02) else { continue };
            if (uv.x - 0.5).abs() < 0.05 {
                continue;
            }
            let hole = uv.x > 0.5;
            let want = if hole { 0.3 } else { rho };
            let got = rgb(&albedo, x, y);
            assert!(
                (got - Vec3::splat(want)).abs().max_element() < 1e-3,
                "{} quad, pixel ({x}, {y}), u = {}: albedo {got}, expected {want}",
                ["MASK", "BLEND"][k],
                uv.x
            );
            if hole {
                // The wall behind the hole is lit by the (attached) lamp.
                assert!(direct.get_pixel(x, y)[0] > 0.0, "pixel ({x}, {y}): the wall behind the hole is dark");
            }
            counts[k][usize::from(hole)] += 1;
        }
    }
    println!("kept / hole pixels: MASK {:?}, BLEND {:?}", counts[0], counts[1]);
    assert!(counts.iter().flatten().all(|&n| n > 200), "{counts:?}");
}

fn f32_at(bytes: &[u8], index: usize) -> f32 {
    f32::from_le_bytes(bytes[index * 4..index * 4 + 4].try_into().unwrap())
}

fn f16_at(bytes: &[u8], index: usize) -> f32 {
    half::f16::from_le_bytes([bytes[index * 2], bytes[index * 2 + 1]]).to_f32()
}

#[test]
fn a_mask_cut_out_lets_the_detached_lamp_through_to_the_floor_and_into_its_own_gbuffer() {
    // A floor (y = 0) under a horizontal occluder at y = 1.5 (x in [-1, 1], z in [-4, -2]) whose
    // texture is opaque on its left half (x < 0) and alpha 0 on its right; the lamp, put down
    // at (0, 3, -3), looks straight down. The camera looks at the floor from below the
    // occluder. A floor point P is shadowed iff (L + P) / 2 is on the occluder's opaque half.
    const FLOOR_RHO: f32 = 0.5;
    const OCCLUDER_RHO: f32 = 0.9;
    let lamp_pos = Vec3::new(0.0, 3.0, -3.0);
    let occluder_y = 1.5;
    let floor_mesh = |material| {
        let corners = [[-6.0, 0.0, 2.0], [6.0, 0.0, 2.0], [6.0, 0.0, -10.0], [-6.0, 0.0, -10.0]];
        let vertices = corners.iter().map(|&p| Vertex::new(p, [0.0, 1.0, 0.0], [0.0; 2])).collect();
        Mesh { name: "floor".into(), vertices, indices: vec![0, 1, 2, 0, 2, 3], material }
    };
    let occluder_mesh = |material| {
        // Facing +Y, u along +x (uv (0, 0) at x = -1, z = -4).
        let corners =
            [[-1.0, occluder_y, -2.0], [1.0, occluder_y, -2.0], [1.0, occluder_y, -4.0], [-1.0, occluder_y, -4.0]];
        let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
        let vertices = corners.iter().zip(uvs).map(|(&p, uv)| Vertex::new(p, [0.0, 1.0, 0.0], uv)).collect();
        Mesh { name: "occluder".into(), vertices, indices: vec![0, 1, 2, 0, 2, 3], material }
    };
    let scene_with = |occluder: Option<AlphaMode>| {
        let mut scene = Scene {
            textures: vec![two_texels([255; 4], [255, 255, 255, 0])],
            materials: vec![Material { base_color: [FLOOR_RHO, FLOOR_RHO, FLOOR_RHO, 1.0], ..Material::default() }],
            meshes: vec![floor_mesh(0)],
            ..Scene::default()
        };
        if let Some(alpha_mode) = occluder {
            scene.materials.push(Material {
                base_color: [OCCLUDER_RHO, OCCLUDER_RHO, OCCLUDER_RHO, 1.0],
                alpha_mode,
                ..textured(0, nearest(Wrap::ClampToEdge))
            });
            scene.meshes.push(occluder_mesh(1));
        }
        scene
    };
    let mut detached = lamp();
    detached.detach_looking_at(lamp_pos, Vec3::new(0.0, 0.0, -3.0));
    let cam = Camera::look_at(Vec3::new(0.0, 0.8, 1.0), Vec3::new(0.0, 0.0, -3.0), FOV_Y);
    let v = view(cam, detached.clone());
    let gpu = gpu();
    let (renderer, masked) = render(&gpu, &scene_with(Some(AlphaMode::Mask { cutoff: 0.5 })), "direct", &v);
    let (_, opaque) = render(&gpu, &scene_with(Some(AlphaMode::Opaque)), "direct", &v);
    let (_, open) = render(&gpu, &scene_with(None), "direct", &v);

    let frustum = detached.frustum(&cam, 1.0);
    let (mut lit, mut shadowed, mut worst_lit) = (0, 0, 0.0f32);
    for (x, y) in pixels() {
        let d = pixel_ray(&cam, x, y);
        if d.y >= 0.0 {
            continue;
        }
        let p = cam.position + d * (-cam.position.y / d.y);
        let ndc = frustum.view_proj.project_point3(p);
        if ndc.x.abs().max(ndc.y.abs()) > 0.9 {
            continue; // outside the lamp's frustum, or near its edge
        }
        let q = (lamp_pos + p) * 0.5; // where the ray to the lamp crosses the occluder's plane
        if q.z > -2.1 || q.z < -3.9 || q.x.abs() > 0.9 || q.x.abs() < 0.1 {
            continue; // misses the occluder, or near an edge of it or of its hole
        }
        let reference = open.get_pixel(x, y)[0];
        assert!(reference > 1e-3, "pixel ({x}, {y}) is not lit without the occluder");
        let (m, o) = (masked.get_pixel(x, y)[0], opaque.get_pixel(x, y)[0]);
        if q.x < 0.0 {
            assert!(m < reference * 1e-3, "pixel ({x}, {y}) under the opaque half: {m} of {reference}");
            shadowed += 1;
        } else {
            let rel = (m - reference).abs() / reference;
            worst_lit = worst_lit.max(rel);
            assert!(rel < 0.01, "pixel ({x}, {y}) under the hole: {m}, unoccluded {reference}");
            assert!(o < reference * 1e-3, "pixel ({x}, {y}): an opaque occluder lets light through ({o})");
            lit += 1;
        }
    }
    println!("shadow: {shadowed} pixels shadowed, {lit} lit through the hole (worst {:.4} %)", worst_lit * 100.0);
    assert!(lit > 30 && shadowed > 30, "lit {lit}, shadowed {shadowed}");

    // The lamp's own G-buffer (the GI's reflective shadow map) sees the floor through the hole.
    let read = |name| {
        let texture = renderer.graph().texture_by_label(name).unwrap_or_else(|| panic!("{name} is not allocated"));
        read_texture(&gpu, texture)
    };
    let (positions, albedos) = (read("lamp.position"), read("lamp.albedo"));
    let tan_half = (FOV_Y * 0.5).tan();
    let (mut through, mut blocked) = (0, 0);
    for ty in (0..LAMP_MAP_SIZE).step_by(8) {
        for tx in (0..LAMP_MAP_SIZE).step_by(8) {
            let ndc_x = (tx as f32 + 0.5) / LAMP_MAP_SIZE as f32 * 2.0 - 1.0;
            let ndc_y = 1.0 - (ty as f32 + 0.5) / LAMP_MAP_SIZE as f32 * 2.0;
            let dir = detached.rotation * Vec3::new(ndc_x * tan_half, ndc_y * tan_half, -1.0);
            let q = lamp_pos + dir * ((occluder_y - lamp_pos.y) / dir.y);
            if q.z > -2.05 || q.z < -3.95 || q.x.abs() > 0.95 || q.x.abs() < 0.05 {
                continue;
            }
            let i = (ty * LAMP_MAP_SIZE + tx) as usize;
            let (y, rho) = (f32_at(&positions, i * 4 + 1), f16_at(&albedos, i * 4));
            let (want_y, want_rho) = if q.x < 0.0 { (occluder_y, OCCLUDER_RHO) } else { (0.0, FLOOR_RHO) };
            assert!(
                (y - want_y).abs() < 1e-3 && (rho - want_rho).abs() < 1e-3,
                "lamp texel ({tx}, {ty}) over x = {}: y {y}, albedo {rho}; expected y {want_y}, albedo {want_rho}",
                q.x
            );
            if q.x < 0.0 {
                blocked += 1;
            } else {
                through += 1;
            }
        }
    }
    println!("lamp view: {blocked} texels on the occluder, {through} through its hole onto the floor");
    assert!(through > 500 && blocked > 500, "through {through}, blocked {blocked}");
}

#[test]
fn single_sided_materials_are_culled_from_behind() {
    // Three quads in front of a wall of albedo 0.3: a single-sided one facing the camera
    // (drawn), a single-sided one facing away (culled: the wall shows), a double-sided one
    // facing away (drawn).
    let mut scene = Scene::default();
    back_wall(&mut scene, 0.3);
    let quads = [
        Rect::new(-1.6, -0.6, -0.5, 0.5, -2.0),
        Rect::new(-0.5, 0.5, -0.5, 0.5, -2.0),
        Rect::new(0.6, 1.6, -0.5, 0.5, -2.0),
    ];
    let single = |rho: f32| Material { base_color: [rho, rho, rho, 1.0], double_sided: false, ..Material::default() };
    scene.materials.extend([
        single(0.9),
        single(0.8),
        Material { base_color: [0.7, 0.7, 0.7, 1.0], ..Material::default() },
    ]);
    for (i, (q, flipped)) in quads.iter().zip([false, true, true]).enumerate() {
        scene.meshes.push(q.mesh(&format!("quad{i}"), i + 1, [1.0; 4], flipped));
    }
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let mut counts = [0; 3];
    for (x, y) in pixels() {
        for (k, (q, want)) in quads.iter().zip([0.9, 0.3, 0.7]).enumerate() {
            if q.uv_at_pixel(x, y, 0.05).is_some() {
                let got = albedo.get_pixel(x, y)[0];
                assert!((got - want).abs() < 1e-3, "quad {k}, pixel ({x}, {y}): albedo {got}, expected {want}");
                counts[k] += 1;
            }
        }
    }
    assert!(counts.iter().all(|&n| n > 100), "{counts:?}");
}

#[test]
fn an_emissive_texture_times_emissive_strength_appears_in_the_final_image() {
    // emissiveFactor (1, 0.5, 0.25) × emissiveStrength 4 × texture [white | sRGB 128 grey];
    // the lamp is off, so the final image is the emission alone.
    let rect = Rect::new(-1.0, 1.0, -0.6, 0.6, -2.0);
    let texture = png_uri(2, 1, &[255, 255, 255, 255, 128, 128, 128, 255]);
    let material = "{\"emissiveFactor\": [1.0, 0.5, 0.25], \"emissiveTexture\": {\"index\": 0},
        \"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": 4.0}}}";
    let rest = format!(
        ", \"extensionsUsed\": [\"KHR_materials_emissive_strength\"], \"textures\": [{{\"source\": 0, \"sampler\": 0}}],
          \"samplers\": [{{\"magFilter\": 9728, \"minFilter\": 9728, \"wrapS\": 33071, \"wrapT\": 33071}}],
          \"images\": [{{\"uri\": \"{texture}\"}}]"
    );
    let scene = load_quad_gltf("emissive", rect, None, Some(material), &rest);
    let gpu = gpu();
    let (_, image) = render(&gpu, &scene, "final", &view(camera(), lamp_off()));
    let grey = ((128.0 / 255.0 + 0.055) / 1.055f32).powf(2.4); // sRGB 128 decoded: 0.2158
    let full = Vec3::new(4.0, 2.0, 1.0);
    let (mut counts, mut worst) = ([0; 2], 0.0f32);
    for (x, y) in pixels() {
        let Some(uv) = rect.uv_at_pixel(x, y, 0.02) else {
            if rect.uv_at_pixel(x, y, -0.02).is_none() {
                assert_eq!(rgb(&image, x, y), Vec3::ZERO, "pixel ({x}, {y}) off the quad");
            }
            continue;
        };
        if (uv.x - 0.5).abs() < 0.05 {
            continue;
        }
        let right = uv.x > 0.5;
        let want = if right { full * grey } else { full };
        let rel = ((rgb(&image, x, y) - want).abs() / want).max_element();
        worst = worst.max(rel);
        assert!(rel < 0.01, "pixel ({x}, {y}), u = {}: radiance {}, expected {want}", uv.x, rgb(&image, x, y));
        counts[usize::from(right)] += 1;
    }
    println!("emission: {counts:?} pixels, worst relative error {:.4} %", worst * 100.0);
    assert!(counts.iter().all(|&n| n > 500), "{counts:?}");
}

#[test]
fn texture_transforms_move_and_turn_the_texture_and_tex_coord_picks_the_uv_set() {
    // Four quads sampling [red | green] with nearest filtering, repeating:
    // A identity: red for u < 0.5;
    // B scale (2, 1) then offset 0.25: texel ⌊frac(2u + 0.25)·2⌋, red-green-red-green-red;
    // C rotated 90° (u' = v): red on the top half, whatever u;
    // D reading uv set 1 (1 − u, v): green for u < 0.5.
    let quads = [
        Rect::new(-1.5, -0.1, 0.1, 1.0, -2.0),
        Rect::new(0.1, 1.5, 0.1, 1.0, -2.0),
        Rect::new(-1.5, -0.1, -1.0, -0.1, -2.0),
        Rect::new(0.1, 1.5, -1.0, -0.1, -2.0),
    ];
    let base = TextureRef { sampler: nearest(Wrap::Repeat), ..TextureRef::new(0) };
    let refs = [
        base,
        TextureRef { transform: TextureTransform { offset: [0.25, 0.0], rotation: 0.0, scale: [2.0, 1.0] }, ..base },
        TextureRef { transform: TextureTransform { rotation: PI / 2.0, ..TextureTransform::IDENTITY }, ..base },
        TextureRef { tex_coord: 1, ..base },
    ];
    let expected: [&dyn Fn(Vec2) -> (usize, f32); 4] = [
        // (texel, distance to the nearest texel boundary in uv units)
        &|uv| (usize::from(uv.x >= 0.5), (uv.x - 0.5).abs()),
        &|uv| {
            let t = (2.0 * uv.x + 0.25) * 2.0;
            ((t.floor() as usize) % 2, (t - t.round()).abs() / 4.0)
        },
        &|uv| (usize::from(uv.y >= 0.5), (uv.y - 0.5).abs()),
        &|uv| (usize::from(uv.x < 0.5), (uv.x - 0.5).abs()),
    ];
    let mut scene = Scene { textures: vec![two_texels(RED, GREEN)], ..Scene::default() };
    for (i, (q, r)) in quads.iter().zip(refs).enumerate() {
        scene.materials.push(Material { base_color_texture: Some(r), ..textured(0, r.sampler) });
        scene.meshes.push(q.mesh(&format!("quad{i}"), i, [1.0; 4], false));
    }
    let gpu = gpu();
    let (_, albedo) = render(&gpu, &scene, "albedo", &view(camera(), lamp()));
    let mut counts = [[0usize; 2]; 4];
    for (x, y) in pixels() {
        for (k, q) in quads.iter().enumerate() {
            let Some(uv) = q.uv_at_pixel(x, y, 0.03) else { continue };
            let (want, clearance) = expected[k](uv);
            if clearance < 0.04 {
                continue;
            }
            let got = texel_of(rgb(&albedo, x, y));
            assert_eq!(got, Some(want), "quad {k}, pixel ({x}, {y}), uv {uv}: albedo {}", rgb(&albedo, x, y));
            counts[k][want] += 1;
        }
    }
    println!("red/green pixels per quad: {counts:?}");
    assert!(counts.iter().flatten().all(|&n| n > 40), "{counts:?}");
}
