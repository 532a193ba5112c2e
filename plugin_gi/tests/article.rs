//! The article's method (`gi.method = article`): its distribution table's lights carry all of
//! the G-buffer's flux at every budget, in a constant number of calls; where a light volume
//! ends its light does not (the coarse light it refines carries it on); and it follows the
//! lamp when the lamp is put down.

mod common;

use common::*;
use plugin_gi::metrics::{block_error, energy};
use plugin_gi::{readback, GiSettings, Method};

const SIZE: (u32, u32) = (160, 120);

fn article(light_budget: u32) -> GiSettings {
    GiSettings { method: Method::Article, light_budget, ..unoccluded() }
}

/// Each lit texel's flux is in the fine tier's lights exactly once (a slot refined, or a block
/// spanning a fold drawn as its two sides, keeps all of it), whatever the budget; the calls
/// stay the same as the volumes drawn grow; and the same frame gives the same lights.
#[test]
fn the_tables_lights_carry_all_of_the_gbuffer_flux_at_every_budget() {
    let gpu = gpu();
    let (mut calls, mut drawn) = (Vec::new(), Vec::new());
    for budget in [64, 256, 1024, 4096] {
        let mut r = renderer(&gpu, &cornell_box(), article(budget));
        render_linear(&gpu, &mut r, &cornell_view(4.0), "final", (320, 240));
        let lights = readback::lights(&gpu, &r.renderer).expect("gi ran");
        let carried = readback::lights_flux(&lights);
        let total = readback::gbuffer_flux(&gpu, &r.renderer).expect("gi ran");
        for c in 0..3 {
            let rel = (carried[c] - total[c]).abs() / total[c];
            assert!(rel < 1e-4, "budget {budget}, channel {c}: lights carry {} W of {} W", carried[c], total[c]);
        }
        let volumes = readback::volume_stats(&gpu, &r.renderer).unwrap();
        let stats = plugin_gi::GiStats::of(&r.renderer);
        println!(
            "budget {budget}: {} fine lights, {} volumes drawn from {} slots, {} dispatches and {} draws",
            lights.len(),
            volumes.drawn,
            volumes.slots,
            stats.dispatches,
            stats.draws
        );
        assert!(volumes.slots <= budget + budget / 4 + 16, "budget {budget}: {} slots", volumes.slots);
        calls.push((stats.dispatches, stats.draws));
        drawn.push(volumes.drawn);
        render_linear(&gpu, &mut r, &cornell_view(4.0), "final", (320, 240));
        let again = readback::lights(&gpu, &r.renderer).expect("gi ran");
        assert!(again == lights, "budget {budget}: the lights differ between two frames of the same view");
    }
    assert!(drawn[3] > 10 * drawn[0], "the volumes drawn must range widely: {drawn:?}");
    assert!(calls.iter().all(|&c| c == calls[0]), "GI calls per frame by budget: {calls:?}");
}

/// A fine light's volume ends `volume_reach` sizes of its coarse light away; beyond it the
/// coarse light carries its flux. So the indirect light with the default volumes has the
/// energy of the same lights each drawn over every receiver (volume_reach 100, larger than the
/// box many times over), and nearly its picture; the article's own cutoff (its volumes ending
/// where a light's irradiance fell below a threshold) lost up to 16 % here.
#[test]
fn where_a_light_volume_ends_its_light_does_not() {
    let gpu = gpu();
    let view = cornell_view(4.0);
    let exact = GiSettings { article_interleave: 1, ..article(1024) };
    let mut everywhere = renderer(&gpu, &cornell_box(), GiSettings { volume_reach: 100.0, ..exact.clone() });
    let all = render_linear(&gpu, &mut everywhere, &view, "indirect", SIZE);
    for reach in [1.0, 2.5] {
        let mut r = renderer(&gpu, &cornell_box(), GiSettings { volume_reach: reach, ..exact.clone() });
        let ended = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
        let (gain, error) = (energy(&ended, &all), block_error(&ended, &all));
        println!("volumes of {reach} sizes: energy {:+.3} %, block error {:.2} %", 100.0 * gain, 100.0 * error);
        assert!(gain.abs() < 0.01, "reach {reach}: energy {:+.3} % of the lights drawn everywhere", 100.0 * gain);
        assert!(error < 0.03, "reach {reach}: {:.2} % from the lights drawn everywhere", 100.0 * error);
    }
}

/// A lamp put down at the camera (same frustum) gives what the attached lamp gives: the table
/// is made again for the lamp's own 1024² view and its distribution.
#[test]
fn a_lamp_put_down_at_the_camera_reproduces_the_attached_lamp() {
    let gpu = gpu();
    let attached = cornell_view(4.0);
    let mut detached = attached.clone();
    detached.headlamp.detach_at(&attached.camera);
    let square = (96, 96);
    let mut r = renderer(&gpu, &cornell_box(), article(1024));
    let a = render_linear(&gpu, &mut r, &attached, "indirect", square);
    let d = render_linear(&gpu, &mut r, &detached, "indirect", square);
    let flux = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
    let carried = readback::lights_flux(&readback::lights(&gpu, &r.renderer).unwrap());
    for c in 0..3 {
        assert!((carried[c] - flux[c]).abs() / flux[c] < 1e-4, "detached lights carry {} of {}", carried[c], flux[c]);
    }
    let (error, gain) = (block_error(&d, &a), energy(&d, &a));
    println!("detached vs attached: {:.2} %, energy {:+.2} %", 100.0 * error, 100.0 * gain);
    assert!(error <= 0.1 && gain.abs() <= 0.03, "detached differs from attached by {error:.4} ({gain:+.4})");
}
