//! The camera flash in the GI, render scale and instances: with the lamp attached the flash's
//! reflected flux joins the lamp's (Φ = ρ·(I_lamp + I_flash)·Ω) in the plugin and in the
//! brute-force reference alike; detached it lights directly only.

mod common;

use common::*;
use engine::frame::Instance;
use engine::glam::{Mat4, Vec3};
use plugin_gi::readback;

const SIZE: (u32, u32) = (80, 60);

bounds::tolerance! {
    /// A lamp and a flash against one lamp of the summed power: the G-buffer's flux, any channel.
    SUMMED_FLUX: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// A lamp and a flash against one lamp of the summed power: block error of the indirect light.
    SUMMED_INDIRECT: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// A lamp and a flash against one lamp of the summed power: block error of `reference_screen`.
    SUMMED_REFERENCE: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// The GI with the lamp and the flash against `reference_screen`: block error.
    FLASHED: at_most 0.03, measured 0.0188
}
bounds::tolerance! {
    /// The GI with the flash alone against `reference_screen`: block error.
    FLASH_ALONE: at_most 0.025, measured 0.0166
}
bounds::tolerance! {
    /// The lamp put down: the indirect light with the flash against without (block error; the
    /// sums run in the order the GPU built the lights, so equal up to rounding).
    DETACHED_FLASH: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// At half render scale, the GI against `reference_screen` at that scale: block error.
    HALF_SCALE: at_most 0.03, measured 0.0175
}
bounds::tolerance! {
    /// At half render scale: how much more the GI moves from its full-scale picture than the
    /// exact bounce moves between the two scales (a quarter of the senders), either way.
    HALF_SCALE_MOVE: magnitude 0.03, measured 0.0177
}

fn total(img: &image::Rgba32FImage) -> f64 {
    img.pixels().map(|p| (p[0] + p[1] + p[2]) as f64).sum()
}

/// A uniform white lamp and a flash of the same intensity at the same point are one lamp of
/// the summed power, so (the pipeline being linear in flux) the indirect light must be that of
/// a lamp of power P + I, in the plugin and in the reference.
#[test]
fn the_flash_adds_to_the_lamp_in_the_indirect_light_and_the_reference() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let plain = cornell_view(2.0);
    let mut flashed = plain.clone();
    flashed.camera_flash = [2.0; 3];
    let combined = cornell_view(4.0);

    let without = render_linear(&gpu, &mut r, &plain, "indirect", SIZE);
    let with = render_linear(&gpu, &mut r, &flashed, "indirect", SIZE);
    let flux_with = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let as_one_lamp = render_linear(&gpu, &mut r, &combined, "indirect", SIZE);
    let flux_one = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let (a, b) = (total(&without), total(&with));
    println!("indirect total: lamp 2 W/sr {a:.4}, + flash 2 W/sr {b:.4}; flux {flux_with:?} vs {flux_one:?}");
    bounds::assert(bounds::at_least("the indirect light with the flash over without", b / a, 1.9));
    for c in 0..3 {
        let rel = (flux_with[c] - flux_one[c]).abs() / flux_one[c];
        SUMMED_FLUX.assert(format!("channel {c}: flux of lamp and flash against one lamp"), rel);
    }
    SUMMED_INDIRECT.assert("lamp and flash against one lamp: block error", block_error(&with, &as_one_lamp));

    let reference = render_linear(&gpu, &mut r, &flashed, "reference_screen", SIZE);
    let reference_one = render_linear(&gpu, &mut r, &combined, "reference_screen", SIZE);
    let ref_error = block_error(&reference, &reference_one);
    let gi_error = block_error(&with, &reference);
    println!("reference: flash vs one lamp {ref_error:.6}; plugin vs reference with the flash {gi_error:.4}");
    bounds::assert_all([
        SUMMED_REFERENCE.check("the reference, lamp and flash against one lamp: block error", ref_error),
        FLASHED.check("the GI with the flash against the reference: block error", gi_error),
    ]);
}

#[test]
fn the_flash_alone_lights_indirectly_and_matches_the_reference() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let mut view = cornell_view(4.0);
    view.headlamp.on = false;
    view.camera_flash = [1.0, 3.0, 2.0];
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let reference = render_linear(&gpu, &mut r, &view, "reference_screen", SIZE);
    bounds::assert(bounds::at_least("the reference's light from the flash", total(&reference), f64::MIN_POSITIVE));
    FLASH_ALONE.assert("the flash alone against the reference: block error", block_error(&indirect, &reference));
}

/// Detached, the reflective shadow map is the lamp's view: the flash changes the direct light
/// and leaves the indirect light exactly as it was (the documented limitation).
#[test]
fn with_the_lamp_put_down_the_flash_lights_directly_only() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let mut view = cornell_view(4.0);
    view.headlamp.detach_at(&view.camera.clone());
    let mut flashed = view.clone();
    flashed.camera_flash = [2.0; 3];
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let flux = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let direct = render_linear(&gpu, &mut r, &view, "direct", SIZE);
    let indirect_flashed = render_linear(&gpu, &mut r, &flashed, "indirect", SIZE);
    let flux_flashed = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let direct_flashed = render_linear(&gpu, &mut r, &flashed, "direct", SIZE);
    assert_eq!(flux, flux_flashed, "detached, the flash must not reach the lamp's flux");
    // The shading sums lights in the order the GPU built them: equal up to rounding.
    DETACHED_FLASH.assert(
        "detached: the indirect light with the flash against without",
        block_error(&indirect_flashed, &indirect),
    );
    let raised = total(&direct_flashed) / total(&direct);
    bounds::assert(bounds::at_least("detached: the direct light with the flash over without", raised, 1.3));
}

/// Instances are in both reflective shadow maps: a red cube in the box reflects red flux.
#[test]
fn an_instance_reflects_the_lamp_into_the_gi() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let (vertices, indices) = engine::primitives::cuboid(Vec3::splat(0.3));
    let cube = r.renderer.add_mesh(&gpu, &vertices, &indices);
    let red = Instance {
        mesh: cube,
        transform: Mat4::from_translation(Vec3::new(-0.4, 0.6, 0.0)),
        base_color: [0.9, 0.05, 0.05],
        emissive: [0.0; 3],
    };
    let mut views = vec![cornell_view(4.0)];
    let mut detached = cornell_view(4.0);
    detached.headlamp.detach_at(&detached.camera.clone());
    views.push(detached);
    for view in views {
        let mode = if view.headlamp.attached { "attached" } else { "detached" };
        render_linear(&gpu, &mut r, &view, "indirect", SIZE);
        let before = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
        let mut with = view.clone();
        with.instances = vec![red];
        render_linear(&gpu, &mut r, &with, "indirect", SIZE);
        let after = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
        println!("{mode}: flux without the cube {before:?}, with {after:?}");
        // The cube hides some of the box and reflects mostly red: red rises against green.
        let redder = (after[0] / after[1]) / (before[0] / before[1]);
        bounds::assert(bounds::at_least(
            format!("{mode}: red over green flux with the cube, over without"),
            redder,
            1.05,
        ));
    }
}

/// At half render scale the GI runs on half-size textures and still agrees with the
/// reference computed at that scale, and roughly with the full-scale picture.
#[test]
fn the_gi_works_at_half_render_scale() {
    const SIZE: (u32, u32) = (128, 96);
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let view = cornell_view(4.0);
    let full = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let full_reference = render_linear(&gpu, &mut r, &view, "reference_screen", SIZE);
    r.renderer.set_render_scale(0.5);
    let half = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let flux = r.renderer.graph().texture_by_label(plugin_gi::names::FLUX).unwrap();
    assert_eq!((flux.width(), flux.height()), (SIZE.0 / 2, SIZE.1 / 2));
    let reference = render_linear(&gpu, &mut r, &view, "reference_screen", SIZE);
    let (against_reference, against_full) = (block_error(&half, &reference), block_error(&half, &full));
    let reference_moves = block_error(&reference, &full_reference);
    println!(
        "half scale: vs its reference {against_reference:.4}, vs full scale {against_full:.4}; the reference \
         itself moves {reference_moves:.4} between the scales"
    );
    // A quarter of the flux texels and receivers: close, not equal; the exact one bounce
    // itself moves 11 % between the two scales, its senders being a quarter as many. The GI
    // must move as the exact bounce does.
    bounds::assert_all([
        HALF_SCALE.check("half scale against its reference: block error", against_reference),
        HALF_SCALE_MOVE
            .check("half scale: the GI's move from full scale less the reference's", against_full - reference_moves),
    ]);
}
