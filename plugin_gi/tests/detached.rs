//! The GI with the headlamp put down: reflection lights come from the lamp's own G-buffer.

mod common;

use common::*;
use plugin_gi::{readback, GiSettings};

const SQUARE: (u32, u32) = (96, 96);

bounds::tolerance! {
    /// The lamp put down at the camera against the lamp worn: reflected flux, any channel.
    FLUX: at_most 0.008, measured 0.0045
}
bounds::tolerance! {
    /// The put-down lamp's lights carry its G-buffer's flux: relative difference, any channel.
    CARRIED: at_most 4e-9, measured 2.11e-9
}
bounds::tolerance! {
    /// The lamp put down at the camera against the lamp worn: block error of the indirect light
    /// (the exact one bounce itself moves 2.0 % between the two samplings of its senders, 96²
    /// and 1024²).
    INDIRECT: at_most 0.008, measured 0.00518
}

/// A lamp detached exactly at the camera (same frustum: square view, same FOV) sees what the
/// attached lamp sees, sampled at 1024² instead of the view's resolution: the reflected flux
/// is the same integral, and the indirect light must agree.
#[test]
fn a_lamp_put_down_at_the_camera_reproduces_the_attached_lamp() {
    let gpu = gpu();
    let attached = cornell_view(4.0);
    let mut detached = attached.clone();
    detached.headlamp.detach_at(&attached.camera);

    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let a = render_linear(&gpu, &mut r, &attached, "indirect", SQUARE);
    let flux_a = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let lights_a = readback::lights(&gpu, &r.renderer).unwrap();
    let d = render_linear(&gpu, &mut r, &detached, "indirect", SQUARE);
    let flux_d = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let lights_d = readback::lights(&gpu, &r.renderer).unwrap();
    println!("flux attached {flux_a:?} ({} lights), detached {flux_d:?} ({} lights)", lights_a.len(), lights_d.len());

    for c in 0..3 {
        let rel = (flux_a[c] - flux_d[c]).abs() / flux_a[c];
        FLUX.assert(format!("channel {c}: reflected flux, detached against attached"), rel);
        let carried = readback::lights_flux(&lights_d)[c];
        CARRIED.assert(
            format!("channel {c}: the detached lights' flux against the G-buffer's"),
            (carried - flux_d[c]).abs() / flux_d[c],
        );
    }
    INDIRECT.assert("detached against attached: block error", block_error(&d, &a));
}

/// With the lamp detached and switched off there is no flux, hence no indirect light.
#[test]
fn a_detached_lamp_that_is_off_lights_nothing() {
    let gpu = gpu();
    let mut view = cornell_view(4.0);
    view.headlamp.detach_at(&view.camera.clone());
    view.headlamp.on = false;
    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let img = render_linear(&gpu, &mut r, &view, "indirect", SQUARE);
    assert!(img.pixels().all(|p| p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0));
}
