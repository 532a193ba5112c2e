//! What the renderer sees of the simulation: the two latest tick states blended by the clock's
//! fraction, so motion is smooth at any frame rate while the simulation stays at its fixed tick.

use engine::camera::yaw_pitch_rotation;
use engine::frame::ViewState;

use crate::sim::command::radians;
use crate::sim::WorldState;

/// Blends yaw the short way round.
fn yaw_between(a: u16, b: u16, t: f32) -> f32 {
    a as f32 + (b.wrapping_sub(a) as i16) as f32 * t
}

/// Writes the camera and lamp of the state between `prev` (t = 0) and `cur` (t = 1) into `view`.
/// `extra_turn` (angle units) is mouse motion not yet in any tick: adding it keeps mouse look
/// immediate in a live game (0 when replaying).
pub fn apply(view: &mut ViewState, prev: &WorldState, cur: &WorldState, t: f32, extra_turn: (f32, f32)) {
    let (p, c) = (&prev.player, &cur.player);
    view.camera.position = p.eye().lerp(c.eye(), t);
    let yaw = yaw_between(p.yaw, c.yaw, t) + extra_turn.0;
    let pitch = (p.pitch as f32 + (c.pitch - p.pitch) as f32 * t + extra_turn.1)
        .clamp(-(crate::sim::player::MAX_PITCH as f32), crate::sim::player::MAX_PITCH as f32);
    view.camera.rotation = yaw_pitch_rotation(radians(yaw), radians(pitch));
    let lamp = &cur.lamp;
    view.headlamp.on = lamp.on;
    view.headlamp.attached = lamp.attached;
    if !lamp.attached {
        view.headlamp.position = lamp.position;
        view.headlamp.rotation = yaw_pitch_rotation(radians(lamp.yaw as f32), radians(lamp.pitch as f32));
    }
}

/// The view exactly at one tick (snapshots, tests).
pub fn at(view: &mut ViewState, state: &WorldState) {
    apply(view, state, state, 1.0, (0.0, 0.0));
}
