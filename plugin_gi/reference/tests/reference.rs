//! The world-fixed reference against what it computes by definition: point and polygon forms,
//! the analytic form factor of a rectangle, the flux a lamp's solid angle delivers, shadows,
//! albedo as the G-buffer has it, and patches that stay where they are whatever the lamp does.

use std::collections::HashSet;
use std::f64::consts::PI;

use engine::camera::Camera;
use engine::glam::{DVec3, Quat, Vec3};
use engine::headlamp::Headlamp;
use engine::scene::{
    HeadlampProfile, IntensityDistribution, Material, Mesh, Reflection, Scene, Texture, TextureRef, Vertex,
};
use gi_reference::{polygon_factor, Lamp, LitPatch, LitPatches, Patch, Receiver, World, DEFAULT_MAX_EDGE};

/// Appends a quad (corners counter-clockwise seen from its front) of material `material`.
fn quad(scene: &mut Scene, corners: [Vec3; 4], material: usize) {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
    let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let vertices = corners.iter().zip(uvs).map(|(p, uv)| Vertex::new(p.to_array(), n.to_array(), uv)).collect();
    scene.meshes.push(Mesh {
        name: format!("quad{}", scene.meshes.len()),
        vertices,
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    });
}

/// A horizontal square of half-width `r` at height `y`, facing up (or down).
fn square(scene: &mut Scene, centre: Vec3, r: f32, up: bool, material: usize) {
    let c = |dx: f32, dz: f32| centre + Vec3::new(dx, 0.0, dz);
    let corners = [c(-r, r), c(r, r), c(r, -r), c(-r, -r)];
    let corners = if up { corners } else { [corners[3], corners[2], corners[1], corners[0]] };
    quad(scene, corners, material);
}

fn grey(rho: f32, double_sided: bool) -> Material {
    Material { base_color: [rho, rho, rho, 1.0], double_sided, ..Material::default() }
}

/// A uniform lamp of intensity `power` put down at `eye` looking at `target`, square frustum.
fn lamp(eye: Vec3, target: Vec3, fov_deg: f32, power: f32) -> Lamp {
    let profile = HeadlampProfile {
        power,
        fov_y: fov_deg.to_radians(),
        color: [1.0; 3],
        distribution: IntensityDistribution::Uniform,
    };
    let mut headlamp = Headlamp::new(profile);
    headlamp.detach_looking_at(eye, target);
    Lamp::new(&headlamp, &Camera::perspective(Vec3::ZERO, Quat::IDENTITY, 1.0), 1.7)
}

/// The solid angle of a pyramid with half-angles atan(tx), atan(ty) about its axis.
fn pyramid_solid_angle(tx: f64, ty: f64) -> f64 {
    let (sa, sb) = (tx / (1.0 + tx * tx).sqrt(), ty / (1.0 + ty * ty).sqrt());
    4.0 * (sa * sb).asin()
}

/// The form factor from a point to a parallel rectangle [0, a] × [0, b] at height h, the point
/// under its corner.
fn corner_form_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

bounds::tolerance! {
    /// One small patch's light at a receiver against the point form: relative.
    POINT_FORM: at_most 4e-8, measured 2.16e-8
}
bounds::tolerance! {
    /// The polygon form of the same small patch against the point form: relative (they agree to
    /// (size / distance)²).
    POLYGON_FORM: at_most 2e-5, measured 1.05e-5
}
bounds::tolerance! {
    /// A square emitter's light under it against the rectangle's analytic form factor: relative,
    /// the worst of six receivers, one in the near field.
    FORM_FACTOR: at_most 0.0003, measured 0.000181
}
bounds::tolerance! {
    /// The patches' area against their triangles': relative.
    PATCH_AREA: at_most 1.2e-7, measured 7.49e-8
}
bounds::tolerance! {
    /// A patch's centre against its corners' centroid, metres, the worst patch.
    CENTROID: at_most 6e-7, measured 3.59e-7
}
bounds::tolerance! {
    /// A uniform lamp over a floor that fills its frustum: Φ against ρ·I·Ω, relative.
    LAMP_FLUX: at_most 1.5e-5, measured 8.19e-6
}
bounds::tolerance! {
    /// A floor wider than the frustum, patches up to 15 cm that the frustum's edge crosses: Φ
    /// against ρ·I·Ω, relative.
    FRUSTUM_EDGE: at_most 0.0008, measured 0.000429
}
bounds::tolerance! {
    /// The floor under an occluder (one-sided facing the lamp, or double-sided): Φ against ρ·I·Ω
    /// less the occluder's solid angle, relative (a patch is lit or not by its centre).
    SHADOWED_FLUX: at_most 0.004, measured 0.00215
}
bounds::tolerance! {
    /// A back face between the lamp and the floor: the floor's flux against without it, relative.
    BACK_FACE: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// A textured, half-metallic floor's flux over a white one's against ρ = base colour ×
    /// texture × (1 − metallic), the worst channel.
    ALBEDO: at_most 4e-6, measured 2.04e-6
}
bounds::tolerance! {
    /// Vertex colours: the flux's ratio against the colour, the worst channel.
    VERTEX_COLOUR: at_most 0.0, measured 0.0
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn one_patch(corners: [Vec3; 3], flux: f32) -> LitPatch {
    let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    let area = 0.5 * normal.length();
    let normal = normal.normalize();
    let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
    let patch = Patch { corners, centre, normal, area, triangle: 0 };
    LitPatch { patch, normal, flux: Vec3::splat(flux) }
}

#[test]
fn a_small_patch_far_away_lights_by_the_point_form() {
    // A 1 cm triangle facing +Y at the origin, a receiver 1 m away, tilted.
    let s = 0.01;
    let corners = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, 0.0, -s)];
    let p = one_patch(corners, 2.0);
    assert_eq!(p.normal, Vec3::Y);
    let x = Vec3::new(0.3, 0.9, 0.2);
    let n = Vec3::new(-0.2, -1.0, 0.1).normalize();
    let v = x - p.patch.centre;
    let d2 = v.length_squared() as f64;
    let point = (p.normal.dot(v) as f64) * (-n.dot(v) as f64) / (d2 * d2) / PI;
    let lit = LitPatches::new(&[p], DEFAULT_MAX_EDGE);
    let e = lit.irradiance_at(&Receiver { position: x, normal: n, albedo: Vec3::ONE });
    POINT_FORM.assert("the sum against the point form", relative(e.x, 2.0 * point));
    // The polygon form of the same small patch agrees with it to (size / distance)².
    let polygon =
        polygon_factor(corners.map(Vec3::as_dvec3), DVec3::Y, p.patch.area as f64, x.as_dvec3(), n.as_dvec3());
    POLYGON_FORM.assert("the polygon form against the point form", relative(polygon, point));
    // Nothing behind the patch or facing away from it.
    let below = Receiver { position: Vec3::new(0.0, -1.0, 0.0), normal: Vec3::Y, albedo: Vec3::ONE };
    assert_eq!(lit.irradiance_at(&below), DVec3::ZERO);
    let away = Receiver { position: x, normal: -n, albedo: Vec3::ONE };
    assert_eq!(lit.irradiance_at(&away), DVec3::ZERO);
}

#[test]
fn a_receiver_under_a_large_square_emitter_gets_its_analytic_form_factor() {
    // A 2 m square at 0.5 m facing down, exitance M = 1 W/m² (flux = area on every patch).
    let mut scene = Scene { materials: vec![grey(1.0, false)], ..Scene::default() };
    let h = 0.5;
    square(&mut scene, Vec3::new(0.0, h, 0.0), 1.0, false, 0);
    let world = World::new(&scene);
    let patches: Vec<LitPatch> = world
        .patches(DEFAULT_MAX_EDGE)
        .into_iter()
        .map(|patch| LitPatch { patch, normal: patch.normal, flux: Vec3::splat(patch.area) })
        .collect();
    assert!(patches.iter().all(|p| p.normal.abs_diff_eq(-Vec3::Y, 1e-6)), "facing down");
    let mut errors = Vec::new();
    let lit = LitPatches::new(&patches, DEFAULT_MAX_EDGE);
    // Receivers facing up at various places under it, one of them within the near field.
    for (x, z, y) in
        [(0.0, 0.0, 0.0), (0.7, 0.3, 0.0), (-0.4, 0.8, 0.3), (0.2, -0.5, 0.47), (0.3, 0.1, 0.498), (0.95, 0.96, 0.4995)]
    {
        let e = lit.irradiance_at(&Receiver { position: Vec3::new(x, y, z), normal: Vec3::Y, albedo: Vec3::ONE });
        let depth = (h - y) as f64;
        let (x, z) = (x as f64, z as f64);
        let f: f64 = [(1.0 - x, 1.0 - z), (1.0 + x, 1.0 - z), (1.0 - x, 1.0 + z), (1.0 + x, 1.0 + z)]
            .iter()
            .map(|&(a, b)| corner_form_factor(a, b, depth))
            .sum();
        errors.push(relative(e.x, f));
    }
    FORM_FACTOR.assert("E against the rectangle's form factor, the worst receiver", bounds::worst(errors));
}

#[test]
fn patches_cover_their_triangles_exactly_and_are_no_larger_than_asked() {
    let mut scene = Scene { materials: vec![grey(0.5, true)], ..Scene::default() };
    let v = |x: f32, y: f32, z: f32| Vertex::new([x, y, z], [0.0, 0.0, 1.0], [0.0; 2]);
    // A long thin sliver, a small triangle, a large slanted one.
    let vertices = vec![
        v(0.0, 0.0, 0.0),
        v(1.3, 0.0, 0.0),
        v(0.6, 0.003, 0.0),
        v(2.0, 0.0, 0.0),
        v(2.004, 0.0, 0.0),
        v(2.0, 0.005, 0.0),
        v(0.0, 1.0, 1.0),
        v(0.7, 1.5, -0.3),
        v(-0.2, 2.1, 0.4),
    ];
    scene.meshes.push(Mesh { name: "t".into(), vertices: vertices.clone(), indices: (0..9).collect(), material: 0 });
    let world = World::new(&scene);
    for max_edge in [0.02, 0.013] {
        let patches = world.patches(max_edge);
        let area: f64 = patches.iter().map(|p| p.area as f64).sum();
        let triangles: f64 = vertices
            .chunks(3)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(t[k].position).as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
            .sum();
        PATCH_AREA.assert(format!("{max_edge} m: the patches' area against the triangles'"), relative(area, triangles));
        let expected: u32 = vertices
            .chunks(3)
            .map(|t| {
                let corners = [0, 1, 2].map(|k| Vec3::from(t[k].position));
                gi_reference::subdivisions(&corners, max_edge).pow(2)
            })
            .sum();
        assert_eq!(patches.len() as u32, expected, "n² patches a triangle");
        let longest = bounds::worst(patches.iter().flat_map(|p| {
            let [a, b, c] = p.corners;
            [b - a, c - b, a - c].map(|e| f64::from(e.length()))
        }));
        bounds::assert(bounds::at_most(
            format!("{max_edge} m: the longest patch edge"),
            longest,
            f64::from(max_edge) * 1.0001,
        ));
        let off = bounds::worst(patches.iter().map(|p| {
            let [a, b, c] = p.corners;
            f64::from((p.centre - (a + b + c) / 3.0).length())
        }));
        CENTROID.assert(format!("{max_edge} m: a centre off its centroid"), off);
    }
}

/// A 2 m square floor under a lamp 1 m above its centre, looking straight down with a 90°
/// square frustum: the frustum's footprint is exactly the floor.
fn floor_under_a_lamp(rho: f32) -> (Scene, Lamp) {
    let mut scene = Scene { materials: vec![grey(rho, false), grey(0.5, false), grey(0.5, true)], ..Scene::default() };
    square(&mut scene, Vec3::ZERO, 1.0, true, 0);
    let lamp = lamp(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 90.0, 3.0);
    (scene, lamp)
}

#[test]
fn a_uniform_lamp_facing_a_plane_delivers_rho_times_intensity_times_its_solid_angle() {
    let (scene, lamp) = floor_under_a_lamp(0.6);
    let lit = World::new(&scene).lit(&lamp, DEFAULT_MAX_EDGE);
    // Φ = ∫ ρ·I·cos/d² dA over the floor = ρ·I·Ω, Ω the frustum's solid angle (2π/3).
    let expected = 0.6 * 3.0 * pyramid_solid_angle(1.0, 1.0);
    let total = lit.total_flux().x;
    LAMP_FLUX.assert("Φ against ρ·I·Ω", relative(total, expected));
    assert_eq!(lit.len(), World::new(&scene).patches(DEFAULT_MAX_EDGE).len(), "every patch lit");

    let mut off = Headlamp::new(HeadlampProfile::default());
    off.on = false;
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 1.0);
    assert!(World::new(&scene).lit(&Lamp::new(&off, &camera, 1.0), DEFAULT_MAX_EDGE).is_empty(), "off is dark");
}

#[test]
fn patches_the_frustums_edge_crosses_are_lit_in_part() {
    // A floor larger than the frustum's footprint, cut into patches as large as 15 cm whose
    // grid does not follow the footprint's edges: Φ is still ρ·I·Ω.
    let mut scene = Scene { materials: vec![grey(0.6, false)], ..Scene::default() };
    square(&mut scene, Vec3::new(0.03, 0.0, -0.05), 2.0, true, 0);
    let lamp = lamp(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 90.0, 3.0);
    let expected = 0.6 * 3.0 * pyramid_solid_angle(1.0, 1.0);
    for max_edge in [0.15, 0.1, DEFAULT_MAX_EDGE] {
        let total = World::new(&scene).lit(&lamp, max_edge).total_flux().x;
        FRUSTUM_EDGE.assert(format!("{max_edge} m patches: Φ against ρ·I·Ω"), relative(total, expected));
    }
}

#[test]
fn an_occluder_shadows_the_patches_behind_it_unless_it_is_a_back_face() {
    let (mut floor, lamp) = floor_under_a_lamp(0.6);
    let floor_patches = |lit: &LitPatches| lit.patches().iter().filter(|p| p.patch.triangle < 2).count();
    let unshadowed = World::new(&floor).lit(&lamp, DEFAULT_MAX_EDGE);
    let floor_flux = |lit: &LitPatches| -> f64 {
        lit.patches().iter().filter(|p| p.patch.triangle < 2).map(|p| p.flux.x as f64).sum()
    };
    // A 0.2 m square half way up facing the lamp: its shadow is the floor's central 0.4 m square.
    let mut shadowed = floor.clone();
    square(&mut shadowed, Vec3::new(0.0, 0.5, 0.0), 0.1, true, 1);
    let lit = World::new(&shadowed).lit(&lamp, DEFAULT_MAX_EDGE);
    // (A patch is lit or not by its centre: the shadow's edge is placed to within a patch,
    // about 0.2 % of the flux here.)
    let expected = 0.6 * 3.0 * (pyramid_solid_angle(1.0, 1.0) - pyramid_solid_angle(0.2, 0.2));
    SHADOWED_FLUX.assert(
        "one-sided occluder: the floor's Φ against ρ·I·Ω less its shadow",
        relative(floor_flux(&lit), expected),
    );
    // The umbra (the central 0.38 m square) holds no lit patch: the nearest lit centre's
    // distance from the middle, along x or z.
    let nearest = bounds::least(lit.patches().iter().filter(|p| p.patch.triangle < 2).map(|p| {
        let c = p.patch.centre;
        f64::from(c.x.abs()).max(f64::from(c.z.abs()))
    }));
    bounds::assert(bounds::at_least("the lit floor patch nearest the umbra's middle", nearest, 0.19));
    let occluder_lit = lit.patches().iter().filter(|p| p.patch.triangle >= 2).count();
    bounds::assert(bounds::at_least("the occluder's lit patches", occluder_lit as f64, 1.0));
    bounds::assert(bounds::at_most(
        "the shadowed floor's flux over the open floor's",
        floor_flux(&lit) / floor_flux(&unshadowed),
        0.96,
    ));

    // Facing away from the lamp (single-sided, seen from behind): culled, as in every view.
    let mut back = floor.clone();
    square(&mut back, Vec3::new(0.0, 0.5, 0.0), 0.1, false, 1);
    let lit = World::new(&back).lit(&lamp, DEFAULT_MAX_EDGE);
    assert_eq!(floor_patches(&lit), floor_patches(&unshadowed), "a back face lets the light through");
    BACK_FACE.assert(
        "a back face: the floor's flux against without it",
        relative(floor_flux(&lit), floor_flux(&unshadowed)),
    );
    // Double-sided, the same square shadows from either side.
    square(&mut floor, Vec3::new(0.0, 0.5, 0.0), 0.1, false, 2);
    let lit = World::new(&floor).lit(&lamp, DEFAULT_MAX_EDGE);
    SHADOWED_FLUX.assert(
        "double-sided occluder: the floor's Φ against ρ·I·Ω less its shadow",
        relative(floor_flux(&lit), expected),
    );
    let top = lit.patches().iter().filter(|p| p.patch.triangle >= 2).collect::<Vec<_>>();
    assert!(!top.is_empty() && top.iter().all(|p| p.normal.abs_diff_eq(Vec3::Y, 1e-6)), "lit on its lamp side");
}

#[test]
fn shadows_reach_the_receivers() {
    // Receivers on a wall beside the floor: with the occluder, less light reaches them.
    let (floor, lamp) = floor_under_a_lamp(0.6);
    let mut shadowed = floor.clone();
    square(&mut shadowed, Vec3::new(0.0, 0.5, 0.0), 0.1, true, 1);
    let receivers: Vec<Receiver> = (0..5)
        .map(|k| Receiver {
            position: Vec3::new(-0.4 + 0.2 * k as f32, 0.3, 1.0),
            normal: Vec3::NEG_Z,
            albedo: Vec3::ONE,
        })
        .collect();
    let open = World::new(&floor).lit(&lamp, DEFAULT_MAX_EDGE).irradiance(&receivers);
    let world = World::new(&shadowed);
    let lit = world.lit(&lamp, DEFAULT_MAX_EDGE);
    let floor_only: Vec<LitPatch> = lit.patches().iter().filter(|p| p.patch.triangle < 2).copied().collect();
    let dark = LitPatches::new(&floor_only, DEFAULT_MAX_EDGE).irradiance(&receivers);
    for (k, (o, d)) in open.iter().zip(&dark).enumerate() {
        bounds::assert_all([
            bounds::at_least(format!("receiver {k}: its light in the shadow"), f64::from(d[0]), f64::MIN_POSITIVE),
            bounds::at_most(
                format!("receiver {k}: its light in the shadow over in the open"),
                f64::from(d[0] / o[0]),
                0.97,
            ),
        ]);
    }
}

#[test]
fn patches_stay_where_they_are_whatever_the_lamp_does() {
    let (mut scene, _) = floor_under_a_lamp(0.6);
    quad(
        &mut scene,
        [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(1.0, 1.5, -1.0), Vec3::new(-1.0, 1.5, -1.0)],
        0,
    );
    let world = World::new(&scene);
    let key = |p: &Patch| (p.triangle, p.centre.to_array().map(f32::to_bits));
    let all: HashSet<_> = world.patches(DEFAULT_MAX_EDGE).iter().map(key).collect();
    let a = world.lit(&lamp(Vec3::new(0.0, 1.2, 0.8), Vec3::new(0.1, 0.0, -0.5), 70.0, 1.0), DEFAULT_MAX_EDGE);
    let b = world.lit(&lamp(Vec3::new(0.3, 1.0, 0.9), Vec3::new(-0.2, 0.3, -1.0), 50.0, 1.0), DEFAULT_MAX_EDGE);
    let (ka, kb): (HashSet<_>, HashSet<_>) =
        (a.patches().iter().map(|p| key(&p.patch)).collect(), b.patches().iter().map(|p| key(&p.patch)).collect());
    assert!(ka.is_subset(&all) && kb.is_subset(&all), "lit patches are the level's own patches, bit for bit");
    let both = ka.intersection(&kb).count();
    bounds::assert_all([
        bounds::at_least("patches two views share", both as f64, 1001.0),
        bounds::at_most("patches two views share", both as f64, std::cmp::min(ka.len(), kb.len()) as f64 - 1.0),
    ]);
}

#[test]
fn albedo_is_the_gbuffers_base_colour_times_texture_times_one_minus_metallic() {
    let texel = |rgb: u8, b: u8| Texture { name: "t".into(), width: 1, height: 1, rgba8: vec![rgb, rgb, b, 255] };
    let srgb = texel(188, 188); // sRGB 188 decodes to 0.5029
    let metal = texel(0, 128); // B = 128/255, linear
    let textured = Material {
        base_color: [0.8, 0.8, 0.8, 1.0],
        base_color_texture: Some(TextureRef::new(0)),
        reflection: Reflection::MetallicRoughness { metallic: 0.5, roughness: 1.0, texture: Some(TextureRef::new(1)) },
        double_sided: false,
        ..Material::default()
    };
    let (mut plain, lamp) = floor_under_a_lamp(1.0);
    let mut scene = plain.clone();
    scene.materials[0] = textured;
    scene.textures = vec![srgb, metal];
    let flux = |s: &Scene| World::new(s).lit(&lamp, DEFAULT_MAX_EDGE).total_flux();
    let ratio = flux(&scene) / flux(&plain);
    let expected = 0.8 * 0.50289 * (1.0 - 0.5 * 128.0 / 255.0);
    ALBEDO.assert("the flux's ratio against ρ", (ratio - DVec3::splat(expected)).abs().max_element());
    // Vertex colours multiply it too.
    for v in &mut plain.meshes[0].vertices {
        v.color = [0.5, 0.25, 1.0, 1.0];
    }
    let ratio = flux(&plain) / flux(&floor_under_a_lamp(1.0).0);
    VERTEX_COLOUR
        .assert("the flux's ratio against the vertex colour", (ratio - DVec3::new(0.5, 0.25, 1.0)).abs().max_element());
}
