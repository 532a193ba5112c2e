//! The player's gun: a hitscan pistol with a magazine, a reserve and a reload, whose shot lights
//! the room for a few ticks (the muzzle flash) and leaves a mark where it hits.

use glam::Vec3;

use super::command::{buttons, TickCommand};

pub const MAGAZINE: u16 = 12;
pub const START_RESERVE: u16 = 24;
pub const MAX_RESERVE: u16 = 120;
/// Ticks between shots while the trigger is held (6⅔ shots a second at 60 Hz).
pub const FIRE_INTERVAL: u8 = 9;
pub const RELOAD_TICKS: u8 = 84;
/// Ticks the muzzle flash lights the room.
pub const FLASH_TICKS: u8 = 3;
pub const DAMAGE: f32 = 34.0;
pub const RANGE: f32 = 80.0;
/// Impact marks kept; the oldest goes first.
pub const MAX_IMPACTS: usize = 24;
/// Ticks between dry clicks while the trigger is held on an empty gun with nothing to load.
pub const DRY_INTERVAL: u8 = 20;

/// What the gun did in a tick, for the simulation to act on and the sound to play.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WeaponAction {
    Nothing,
    /// A round left the barrel.
    Shot,
    /// The trigger fell on an empty chamber with nothing left to load.
    DryClick,
    ReloadStarted,
    /// The reload finished: the magazine is full (or holds what the reserve had).
    Reloaded,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weapon {
    pub magazine: u16,
    pub reserve: u16,
    /// Ticks until the next shot may leave.
    pub cooldown: u8,
    /// Ticks left of a reload in progress (0 = not reloading).
    pub reloading: u8,
    /// Ticks left of the muzzle flash.
    pub flash: u8,
    /// Ticks until a trigger held on an empty gun clicks again. Apart from `cooldown`, which
    /// only a shot sets, so the gun in hand kicks at a shot and never at a click.
    pub click: u8,
}

/// Where a shot hit: a wall (or floor, prop…) or an enemy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Impact {
    pub position: Vec3,
    pub normal: Vec3,
    pub tick: u32,
    pub on_enemy: bool,
}

impl Weapon {
    pub fn new() -> Self {
        Self { magazine: MAGAZINE, reserve: START_RESERVE, cooldown: 0, reloading: 0, flash: 0, click: 0 }
    }

    /// Advances timers and handles the trigger and reload.
    pub fn step(&mut self, cmd: &TickCommand) -> WeaponAction {
        self.cooldown = self.cooldown.saturating_sub(1);
        self.flash = self.flash.saturating_sub(1);
        self.click = self.click.saturating_sub(1);
        if self.reloading > 0 {
            self.reloading -= 1;
            if self.reloading == 0 {
                let moved = (MAGAZINE - self.magazine).min(self.reserve);
                self.magazine += moved;
                self.reserve -= moved;
                return WeaponAction::Reloaded;
            }
            return WeaponAction::Nothing;
        }
        let wants_reload = cmd.held(buttons::RELOAD) || (cmd.held(buttons::FIRE) && self.magazine == 0);
        if wants_reload && self.magazine < MAGAZINE && self.reserve > 0 {
            self.reloading = RELOAD_TICKS;
            return WeaponAction::ReloadStarted;
        }
        if cmd.held(buttons::FIRE) && self.cooldown == 0 {
            if self.magazine == 0 {
                // Nothing to fire or load: a click, repeated while the trigger is held.
                if self.click > 0 {
                    return WeaponAction::Nothing;
                }
                self.click = DRY_INTERVAL;
                return WeaponAction::DryClick;
            }
            self.magazine -= 1;
            self.cooldown = FIRE_INTERVAL;
            self.flash = FLASH_TICKS;
            return WeaponAction::Shot;
        }
        WeaponAction::Nothing
    }

    /// Adds rounds to the reserve; false when it is already full.
    pub fn add_ammo(&mut self, rounds: u16) -> bool {
        if self.reserve >= MAX_RESERVE {
            return false;
        }
        self.reserve = (self.reserve + rounds).min(MAX_RESERVE);
        true
    }
}

impl Default for Weapon {
    fn default() -> Self {
        Self::new()
    }
}

/// Distance along a ray (unit `dir`) to a capsule around the segment `a`–`b`, if it hits within
/// `max`. A capsule is a cylinder and two end spheres: the nearest entry into any of the three.
pub fn ray_capsule(origin: Vec3, dir: Vec3, a: Vec3, b: Vec3, radius: f32, max: f32) -> Option<f32> {
    let r2 = radius * radius;
    let sphere = |c: Vec3| {
        let oc = origin - c;
        let qb = dir.dot(oc);
        let h = qb * qb - (oc.dot(oc) - r2);
        (h >= 0.0).then(|| -qb - h.sqrt())
    };
    // The cylinder: solve in the plane across the axis, keep hits between the end planes.
    let axis = (b - a).normalize();
    let length = (b - a).length();
    let oa = origin - a;
    let d_perp = dir - axis * dir.dot(axis);
    let o_perp = oa - axis * oa.dot(axis);
    let qa = d_perp.dot(d_perp);
    let cylinder = if qa > 1e-12 {
        let qb = d_perp.dot(o_perp);
        let h = qb * qb - qa * (o_perp.dot(o_perp) - r2);
        (h >= 0.0).then(|| (-qb - h.sqrt()) / qa).filter(|t| (0.0..=length).contains(&(oa + dir * *t).dot(axis)))
    } else {
        None
    };
    [cylinder, sphere(a), sphere(b)].into_iter().flatten().filter(|t| (0.0..=max).contains(t)).reduce(f32::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fire() -> TickCommand {
        TickCommand { buttons: buttons::FIRE, ..Default::default() }
    }

    #[test]
    fn holding_the_trigger_fires_at_its_rate_until_empty_then_reloads() {
        let mut w = Weapon::new();
        // 12 shots 9 ticks apart take 100 ticks; then the empty gun starts reloading.
        assert_eq!((0..120).filter(|_| w.step(&fire()) == WeaponAction::Shot).count(), 12);
        assert_eq!(w.magazine, 0);
        assert!(w.reloading > 0, "an empty magazine reloads when the trigger is pulled");
        let done: Vec<WeaponAction> = (0..RELOAD_TICKS).map(|_| w.step(&TickCommand::default())).collect();
        assert_eq!((w.magazine, w.reserve), (12, 12));
        assert_eq!(done.iter().filter(|a| **a == WeaponAction::Reloaded).count(), 1, "the reload's end says so, once");
    }

    #[test]
    fn an_empty_gun_with_no_reserve_clicks_at_its_own_rate() {
        let mut w = Weapon { magazine: 0, reserve: 0, ..Weapon::new() };
        let actions: Vec<WeaponAction> = (0..60).map(|_| w.step(&fire())).collect();
        let clicks: Vec<usize> = (0..60).filter(|&i| actions[i] == WeaponAction::DryClick).collect();
        assert_eq!(clicks, vec![0, DRY_INTERVAL as usize, 2 * DRY_INTERVAL as usize]);
        assert!(actions.iter().all(|a| matches!(a, WeaponAction::DryClick | WeaponAction::Nothing)));
        assert_eq!(w.flash, 0, "a click lights nothing");
        assert_eq!(w.cooldown, 0, "a click is no shot: the gun in hand does not kick");
    }

    #[test]
    fn reload_tops_up_from_the_reserve_and_no_shot_leaves_meanwhile() {
        let mut w = Weapon::new();
        assert_eq!(w.step(&fire()), WeaponAction::Shot);
        assert_eq!(w.flash, FLASH_TICKS);
        let reload = TickCommand { buttons: buttons::RELOAD, ..Default::default() };
        assert_eq!(w.step(&reload), WeaponAction::ReloadStarted);
        assert!((0..RELOAD_TICKS).all(|_| w.step(&fire()) != WeaponAction::Shot), "no shot during a reload");
        assert_eq!((w.magazine, w.reserve), (12, 23));
        let mut full = Weapon::new();
        assert_eq!(full.step(&reload), WeaponAction::Nothing);
        assert_eq!(full.reloading, 0, "a full magazine does not reload");
        w.reserve = MAX_RESERVE - 5;
        assert!(w.add_ammo(24));
        assert_eq!(w.reserve, MAX_RESERVE);
        assert!(!w.add_ammo(24));
    }

    #[test]
    fn rays_hit_capsules_on_the_body_and_the_caps() {
        let (a, b) = (Vec3::new(0.0, 0.5, -5.0), Vec3::new(0.0, 1.5, -5.0));
        let hit = |o: Vec3, d: Vec3| ray_capsule(o, d.normalize(), a, b, 0.4, 100.0);
        assert!((hit(Vec3::new(0.0, 1.0, 0.0), -Vec3::Z).unwrap() - 4.6).abs() < 1e-4, "the body");
        assert!((hit(Vec3::new(0.0, 10.0, -5.0), -Vec3::Y).unwrap() - 8.1).abs() < 1e-4, "the top cap");
        assert!(hit(Vec3::new(0.5, 1.0, 0.0), -Vec3::Z).is_none(), "beside it");
        assert!(hit(Vec3::new(0.0, 1.0, 0.0), Vec3::Z).is_none(), "behind the ray");
        assert!(ray_capsule(Vec3::new(0.0, 1.0, 0.0), -Vec3::Z, a, b, 0.4, 3.0).is_none(), "beyond max");
    }
}
