//! The detached headlamp: its shadow map keeps docs/gi.md's radiometry (no self-shadowing acne
//! on facing or tilted planes), occluders cast exact umbrae, and its own G-buffer (`lamp.*`)
//! holds the world positions and normals it sees.

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::{Quat, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{read_texture, HeadlessTarget, ImageKind, RenderedImage};
use engine::passes::LAMP_MAP_SIZE;
use engine::renderer::Renderer;
use engine::scene::{HeadlampProfile, IntensityDistribution, Material, Mesh, Scene, Vertex};

const SIZE: (u32, u32) = (160, 120);
const FOV_Y: f32 = 60.0 * PI / 180.0;
const POWER: f32 = 2.0;

/// A square of half-size `half` through `centre`, facing `normal`, albedo `rho`.
#[derive(Clone, Copy)]
struct Quad {
    centre: Vec3,
    normal: Vec3,
    half: f32,
    rho: f32,
}

impl Quad {
    fn axes(&self) -> (Vec3, Vec3, Vec3) {
        let n = self.normal.normalize();
        let u = n.cross(if n.y.abs() > 0.9 { Vec3::X } else { Vec3::Y }).normalize();
        (n, u, n.cross(u))
    }

    /// Where the ray `origin + t·dir` (t > 0) meets the quad, if it does.
    fn hit(&self, origin: Vec3, dir: Vec3) -> Option<Vec3> {
        let (n, u, v) = self.axes();
        let denom = dir.dot(n);
        if denom.abs() < 1e-6 {
            return None;
        }
        let t = (self.centre - origin).dot(n) / denom;
        let p = origin + dir * t;
        let local = p - self.centre;
        (t > 0.0 && local.dot(u).abs() <= self.half && local.dot(v).abs() <= self.half).then_some(p)
    }
}

fn scene(quads: &[Quad]) -> Scene {
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    for (i, q) in quads.iter().enumerate() {
        let (n, u, v) = q.axes();
        let (u, v) = (u * q.half, v * q.half);
        let corners = [q.centre - u - v, q.centre + u - v, q.centre + u + v, q.centre - u + v];
        let vertices = corners.iter().map(|p| Vertex::new(p.to_array(), n.to_array(), [0.0; 2])).collect();
        meshes.push(Mesh { name: format!("quad{i}"), vertices, indices: vec![0, 1, 2, 0, 2, 3], material: i });
        materials.push(Material { base_color: [q.rho, q.rho, q.rho, 1.0], ..Material::default() });
    }
    Scene { meshes, materials, ..Scene::default() }
}

fn uniform_lamp() -> Headlamp {
    Headlamp::new(HeadlampProfile {
        power: POWER,
        fov_y: FOV_Y,
        color: [1.0; 3],
        distribution: IntensityDistribution::Uniform,
    })
}

/// A uniform lamp put down at `eye` looking at `target`.
fn detached(eye: Vec3, target: Vec3) -> Headlamp {
    let mut lamp = uniform_lamp();
    lamp.detach_looking_at(eye, target);
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

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

/// Linear direct radiance of one frame.
fn render(gpu: &Gpu, renderer: &mut Renderer, view: &ViewState) -> image::Rgba32FImage {
    renderer.set_view("direct").unwrap();
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    match target.render(gpu, renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

fn render_scene(quads: &[Quad], view: &ViewState) -> image::Rgba32FImage {
    let gpu = gpu();
    let mut renderer = Renderer::new(&gpu, &scene(quads), vec![]).unwrap();
    render(&gpu, &mut renderer, view)
}

/// World direction through the centre of pixel (x, y).
fn pixel_ray(camera: &Camera, x: u32, y: u32) -> Vec3 {
    let tan_half = (FOV_Y * 0.5).tan();
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let ndc_x = (x as f32 + 0.5) / SIZE.0 as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / SIZE.1 as f32 * 2.0;
    (camera.rotation * Vec3::new(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0)).normalize()
}

/// Largest |NDC| of `p` in the lamp's frustum (≤ 1 inside it).
fn lamp_ndc(lamp: &Headlamp, p: Vec3) -> f32 {
    let f = lamp.frustum(&Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y), 1.0);
    let ndc = f.view_proj.project_point3(p);
    ndc.x.abs().max(ndc.y.abs())
}

/// ρ/π · P · max(0, n·l) / r² for a uniform lamp at `lamp`.
fn expected(rho: f32, normal: Vec3, lamp: Vec3, p: Vec3) -> f32 {
    let to_lamp = lamp - p;
    let r2 = to_lamp.length_squared();
    rho / PI * POWER * normal.normalize().dot(to_lamp / r2.sqrt()).max(0.0) / r2
}

fn relative_error(got: f32, want: f32) -> f32 {
    (got - want).abs() / want
}

/// Mean red radiance of the 2×2 centre texels (the exact centre lies between texels).
fn centre(img: &image::Rgba32FImage) -> f32 {
    let (cx, cy) = (SIZE.0 / 2, SIZE.1 / 2);
    [(cx - 1, cy - 1), (cx, cy - 1), (cx - 1, cy), (cx, cy)].iter().map(|&(x, y)| img.get_pixel(x, y)[0]).sum::<f32>()
        / 4.0
}

/// Every pixel that sees `plane` inside the lamp's frustum (away from its edge, where T
/// steps to 0) and not behind `occluders`, with the plane point it sees.
fn lit_plane_pixels(camera: &Camera, lamp: &Headlamp, plane: &Quad, occluders: &[Quad]) -> Vec<(u32, u32, Vec3)> {
    let mut out = Vec::new();
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let dir = pixel_ray(camera, x, y);
            let Some(p) = plane.hit(camera.position, dir) else { continue };
            let hidden = occluders.iter().any(|o| {
                let grown = Quad { half: o.half + 0.02, ..*o };
                grown
                    .hit(camera.position, dir)
                    .is_some_and(|q| (q - camera.position).length() < (p - camera.position).length())
            });
            if !hidden && lamp_ndc(lamp, p) < 0.95 {
                out.push((x, y, p));
            }
        }
    }
    out
}

#[test]
fn detached_lamp_on_a_facing_plane_matches_attached_radiometry() {
    let (rho, lamp_pos) = (0.6, Vec3::ZERO);
    for d in [2.0_f32, 5.0] {
        let plane = Quad { centre: Vec3::new(0.0, 0.0, -d), normal: Vec3::Z, half: 10.0, rho };
        let eye = Camera::perspective(lamp_pos, Quat::IDENTITY, FOV_Y);
        let lamp = detached(lamp_pos, Vec3::new(0.0, 0.0, -d));

        // Seen from the lamp itself: the detached frame equals the attached one, pixel by
        // pixel, inside the (square) lamp frustum — and its centre is ρ·P/(π d²).
        let attached_img = render_scene(&[plane], &view(eye, uniform_lamp()));
        let detached_img = render_scene(&[plane], &view(eye, lamp.clone()));
        let texel_angle = ((FOV_Y * 0.5).tan() / (SIZE.1 as f32 / 2.0) * 0.5 * 2f32.sqrt()).atan();
        let want = rho * POWER / (PI * d * d) * texel_angle.cos().powi(3);
        let got = centre(&detached_img);
        assert!(relative_error(got, want) <= 0.01, "d = {d}: centre {got}, expected ρP/(πd²) = {want}");
        let pixels = lit_plane_pixels(&eye, &lamp, &plane, &[]);
        assert!(pixels.len() > 5000, "only {} pixels inside the lamp frustum", pixels.len());
        for &(x, y, _) in &pixels {
            let (a, b) = (attached_img.get_pixel(x, y)[0], detached_img.get_pixel(x, y)[0]);
            assert!(relative_error(b, a) <= 0.01, "d = {d}, pixel ({x}, {y}): detached {b}, attached {a}");
        }

        // Seen from elsewhere: every lit pixel still reads ρ/π · P · cos / r².
        let camera = Camera::look_at(Vec3::new(1.5, 1.0, 0.5), Vec3::new(0.0, 0.0, -d), FOV_Y);
        let img = render_scene(&[plane], &view(camera, lamp.clone()));
        let pixels = lit_plane_pixels(&camera, &lamp, &plane, &[]);
        assert!(pixels.len() > 2000, "only {} pixels see the lit plane", pixels.len());
        for (x, y, p) in pixels {
            let (got, want) = (img.get_pixel(x, y)[0], expected(rho, plane.normal, lamp_pos, p));
            assert!(relative_error(got, want) <= 0.01, "d = {d}, pixel ({x}, {y}) at {p}: got {got}, expected {want}");
        }
    }
}

#[test]
fn an_occluder_casts_an_exact_umbra_and_leaves_the_rest_unchanged() {
    let rho = 0.7;
    let plane = Quad { centre: Vec3::new(0.0, 0.0, -4.0), normal: Vec3::Z, half: 10.0, rho };
    // A 0.5 m square halfway: its umbra on the plane is the 1 m square |x|, |y| ≤ 0.5.
    let occluder = Quad { centre: Vec3::new(0.0, 0.0, -2.0), normal: Vec3::Z, half: 0.25, rho: 0.5 };
    let lamp = detached(Vec3::ZERO, Vec3::new(0.0, 0.0, -4.0));
    // From the side, so the shadow is not hidden behind the occluder.
    let camera = Camera::look_at(Vec3::new(2.0, 0.8, 0.5), Vec3::new(0.0, 0.0, -4.0), FOV_Y);
    let img = render_scene(&[plane, occluder], &view(camera, lamp.clone()));

    let (mut umbra, mut lit) = (0, 0);
    for (x, y, p) in lit_plane_pixels(&camera, &lamp, &plane, &[occluder]) {
        let extent = p.x.abs().max(p.y.abs());
        let px = img.get_pixel(x, y);
        if extent < 0.45 {
            umbra += 1;
            assert!(px[0] == 0.0 && px[1] == 0.0 && px[2] == 0.0, "umbra pixel ({x}, {y}) at {p} reads {px:?}");
        } else if extent > 0.6 {
            lit += 1;
            let want = expected(rho, plane.normal, Vec3::ZERO, p);
            let got = px[0];
            assert!(relative_error(got, want) <= 0.01, "lit pixel ({x}, {y}) at {p}: got {got}, expected {want}");
        }
    }
    assert!(umbra > 100 && lit > 2000, "too few pixels tested: {umbra} in the umbra, {lit} lit");
}

#[test]
fn a_tilted_plane_shows_no_acne() {
    let (d, rho) = (2.5, 0.7);
    let eye = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    let lamp = detached(Vec3::ZERO, Vec3::new(0.0, 0.0, -d));
    for degrees in [60.0_f32, 75.0] {
        let normal = Quat::from_rotation_y(degrees.to_radians()) * Vec3::Z;
        let plane = Quad { centre: Vec3::new(0.0, 0.0, -d), normal, half: 10.0, rho };
        let img = render_scene(&[plane], &view(eye, lamp.clone()));
        // On the axis the lamp direction is +Z: n·l = cos(tilt), distance d.
        let want = rho * POWER / (PI * d * d) * degrees.to_radians().cos();
        let got = centre(&img);
        assert!(relative_error(got, want) <= 0.01, "plane tilted {degrees}°: centre {got}, expected {want}");
        // Everywhere the light is not grazing (n·l ≥ 0.2, i.e. up to 78° from the normal).
        let mut tested = 0;
        for (x, y, p) in lit_plane_pixels(&eye, &lamp, &plane, &[]) {
            if normal.dot(-p.normalize()) < 0.2 {
                continue;
            }
            tested += 1;
            let (got, want) = (img.get_pixel(x, y)[0], expected(rho, normal, Vec3::ZERO, p));
            assert!(
                relative_error(got, want) <= 0.01,
                "{degrees}°, pixel ({x}, {y}) at {p}: got {got}, expected {want}"
            );
        }
        assert!(tested > 1000, "{degrees}°: only {tested} pixels tested");
    }
}

#[test]
fn picking_the_lamp_up_again_restores_the_attached_frame_exactly() {
    let plane = Quad { centre: Vec3::new(0.0, 0.0, -3.0), normal: Vec3::Z, half: 10.0, rho: 0.5 };
    let occluder = Quad { centre: Vec3::new(0.3, 0.0, -1.5), normal: Vec3::Z, half: 0.3, rho: 0.5 };
    let gpu = gpu();
    let mut renderer = Renderer::new(&gpu, &scene(&[plane, occluder]), vec![]).unwrap();
    let eye = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    let before = render(&gpu, &mut renderer, &view(eye, uniform_lamp()));
    let put_down =
        render(&gpu, &mut renderer, &view(eye, detached(Vec3::new(1.0, 0.5, 0.0), Vec3::new(0.0, 0.0, -3.0))));
    let after = render(&gpu, &mut renderer, &view(eye, uniform_lamp()));
    assert!(before.as_raw() != put_down.as_raw(), "moving the lamp changed nothing");
    assert!(before.as_raw() == after.as_raw(), "the attached frame differs after the lamp was put down and picked up");
}

/// `lamp.*` of the last frame, read back from the graph.
fn lamp_map(gpu: &Gpu, renderer: &Renderer, name: &str) -> Vec<u8> {
    let texture = renderer.graph().texture_by_label(name).unwrap_or_else(|| panic!("{name} is not allocated"));
    assert_eq!((texture.width(), texture.height()), (LAMP_MAP_SIZE, LAMP_MAP_SIZE), "{name}");
    read_texture(gpu, texture)
}

fn f32_at(bytes: &[u8], index: usize) -> f32 {
    f32::from_le_bytes(bytes[index * 4..index * 4 + 4].try_into().unwrap())
}

fn f16_at(bytes: &[u8], index: usize) -> f32 {
    half::f16::from_le_bytes([bytes[index * 2], bytes[index * 2 + 1]]).to_f32()
}

#[test]
fn the_lamp_view_holds_world_position_normal_and_albedo() {
    // A 3 m square tilted away from the lamp, its normal facing *away* from the lamp: the lamp
    // view must turn the normal towards the lamp. Texels past its edges see nothing.
    let normal = (Quat::from_rotation_x(0.4) * Quat::from_rotation_y(-0.5) * Vec3::NEG_Z).normalize();
    let plane = Quad { centre: Vec3::new(-1.0, 0.5, -4.0), normal, half: 1.5, rho: 0.4 };
    let (eye, target) = (Vec3::new(0.5, 1.5, 1.0), Vec3::new(-1.0, 0.5, -4.0));
    let lamp = detached(eye, target);
    let gpu = gpu();
    let mut renderer = Renderer::new(&gpu, &scene(&[plane]), vec![]).unwrap();
    let camera = Camera::perspective(Vec3::new(0.0, 1.6, 5.0), Quat::IDENTITY, FOV_Y);
    render(&gpu, &mut renderer, &view(camera, lamp.clone()));

    let positions = lamp_map(&gpu, &renderer, "lamp.position");
    let normals = lamp_map(&gpu, &renderer, "lamp.normal");
    let albedos = lamp_map(&gpu, &renderer, "lamp.albedo");
    let depths = lamp_map(&gpu, &renderer, "lamp.depth");
    let facing = if normal.dot(eye - plane.centre) < 0.0 { -normal } else { normal };
    assert!(facing.dot(normal) < 0.0, "the test wants a plane facing away from the lamp");

    let (tan_half, forward) = ((FOV_Y * 0.5).tan(), lamp.rotation * Vec3::NEG_Z);
    let (mut hits, mut empty) = (0, 0);
    let step = 7; // every 7th texel in each direction: ~21 000 texels
    for ty in (0..LAMP_MAP_SIZE).step_by(step) {
        for tx in (0..LAMP_MAP_SIZE).step_by(step) {
            let ndc_x = (tx as f32 + 0.5) / LAMP_MAP_SIZE as f32 * 2.0 - 1.0;
            let ndc_y = 1.0 - (ty as f32 + 0.5) / LAMP_MAP_SIZE as f32 * 2.0;
            let dir = (lamp.rotation * Vec3::new(ndc_x * tan_half, ndc_y * tan_half, -1.0)).normalize();
            let i = (ty * LAMP_MAP_SIZE + tx) as usize;
            let position =
                Vec3::new(f32_at(&positions, i * 4), f32_at(&positions, i * 4 + 1), f32_at(&positions, i * 4 + 2));
            let w = f32_at(&positions, i * 4 + 3);
            let n = Vec3::new(f16_at(&normals, i * 4), f16_at(&normals, i * 4 + 1), f16_at(&normals, i * 4 + 2));
            let nw = f16_at(&normals, i * 4 + 3);
            let depth = f32_at(&depths, i);
            // Stay a texel clear of the quad's edges, where coverage is a rasteriser choice.
            let inner = Quad { half: plane.half - 0.02, ..plane };
            let outer = Quad { half: plane.half + 0.02, ..plane };
            if let Some(p) = inner.hit(eye, dir) {
                hits += 1;
                assert!((position - p).length() < 1e-3, "texel ({tx}, {ty}): position {position}, expected {p}");
                let axis = (p - eye).dot(forward);
                assert!((w - axis).abs() < 1e-3, "texel ({tx}, {ty}): w = {w}, expected axis distance {axis}");
                assert!(
                    (n - facing).length() < 2e-3 && nw == 1.0,
                    "texel ({tx}, {ty}): normal {n} w {nw}, expected {facing}"
                );
                let rho = f16_at(&albedos, i * 4);
                assert!((rho - plane.rho).abs() < 0.001, "texel ({tx}, {ty}): albedo {rho}, expected {}", plane.rho);
                // Reversed infinite Z: depth = near / axis distance.
                let want = Camera::DEFAULT_NEAR / axis;
                assert!((depth - want).abs() <= want * 1e-4, "texel ({tx}, {ty}): depth {depth}, expected {want}");
            } else if outer.hit(eye, dir).is_none() {
                empty += 1;
                assert!(
                    position == Vec3::ZERO && w == 0.0,
                    "empty texel ({tx}, {ty}) holds position {position}, w {w}"
                );
                assert!(nw == 0.0 && depth == 0.0, "empty texel ({tx}, {ty}): normal w {nw}, depth {depth}");
            }
        }
    }
    assert!(hits > 3000 && empty > 3000, "{hits} texels on the plane, {empty} empty: the framing is off");
}
