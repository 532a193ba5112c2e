//! The state hash a replay stores per tick: 64-bit FNV-1a over every field's exact bits, in
//! declaration order, so any difference at all — a float's last bit — shows.

use glam::Vec3;
use physics::CharacterBody;

use super::WorldState;

struct StateHash(scene::Fnv1a);

impl StateHash {
    fn bytes(&mut self, b: &[u8]) {
        self.0.write(b);
    }
    fn f32(&mut self, v: f32) {
        self.bytes(&v.to_bits().to_le_bytes());
    }
    fn vec3(&mut self, v: Vec3) {
        v.to_array().iter().for_each(|&c| self.f32(c));
    }
    fn flags(&mut self, flags: &[bool]) {
        flags.iter().for_each(|&f| self.bytes(&[f as u8]));
    }
    fn body(&mut self, b: &CharacterBody) {
        self.vec3(b.position);
        self.vec3(b.velocity);
        self.flags(&[b.grounded, b.crouching]);
    }
}

// The method is written here, beside the hashing it is, so that the simulation's module
// does not import its own hash back.
impl WorldState {
    /// 64-bit FNV-1a over every field's exact bits, in declaration order.
    pub fn hash(&self) -> u64 {
        let s = self;
        let mut h = StateHash(scene::Fnv1a::default());
        h.bytes(&s.tick.to_le_bytes());

        let p = &s.player;
        h.body(&p.body);
        h.bytes(&p.yaw.to_le_bytes());
        h.bytes(&p.pitch.to_le_bytes());
        h.f32(p.eye_height);
        h.f32(p.health);
        h.bytes(&[p.hurt_ticks]);
        h.f32(p.to_next_step);

        let l = &s.lamp;
        h.flags(&[l.on, l.attached]);
        h.vec3(l.position);
        h.bytes(&l.yaw.to_le_bytes());
        h.bytes(&l.pitch.to_le_bytes());
        h.vec3(l.velocity);
        h.flags(&[l.resting]);
        h.f32(l.battery);
        h.f32(l.flicker);
        h.bytes(&[l.flicker_ticks]);

        let w = &s.weapon;
        h.bytes(&w.magazine.to_le_bytes());
        h.bytes(&w.reserve.to_le_bytes());
        h.bytes(&[w.cooldown, w.reloading, w.flash, w.click]);

        h.bytes(&(s.enemies.len() as u32).to_le_bytes());
        for e in &s.enemies {
            h.body(&e.body);
            h.f32(e.yaw);
            h.f32(e.health);
            h.bytes(&[e.mind as u8]);
            h.bytes(&e.timer.to_le_bytes());
            h.vec3(e.target);
            h.bytes(&e.waypoint.to_le_bytes());
            h.bytes(&[e.flinch]);
            h.f32(e.walked);
        }
        h.bytes(&(s.pickups.len() as u32).to_le_bytes());
        for p in &s.pickups {
            h.flags(&[p.taken]);
        }
        h.bytes(&(s.impacts.len() as u32).to_le_bytes());
        for i in &s.impacts {
            h.vec3(i.position);
            h.vec3(i.normal);
            h.bytes(&i.tick.to_le_bytes());
            h.flags(&[i.on_enemy]);
        }
        h.bytes(&[s.outcome as u8]);
        h.bytes(&s.rng.state().to_le_bytes());
        h.0.finish()
    }
}
