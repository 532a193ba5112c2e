//! The deterministic game simulation: a fixed tick consumes one [`TickCommand`] and advances
//! the world. It reads no clock (the tick length is fixed), draws randomness only from its
//! seeded [`Rng`], and iterates only in fixed orders (the level file's), so the same commands
//! from the same start give the same [`WorldState`] bit for bit; [`WorldState::hash`] proves
//! it tick by tick.

pub mod command;
pub mod enemy;
mod hash;
pub mod lamp;
pub mod level_entities;
pub mod nav_grid;
pub mod pickup;
pub mod player;
pub mod rng;
pub mod weapon;

use std::sync::Arc;

use glam::Vec3;
use physics::{CharacterConfig, CharacterController, LevelCollision};
use scene::Level;

pub use command::TickCommand;
pub use enemy::Enemy;
pub use lamp::Lamp;
pub use level_entities::{LevelEntities, PickupKind};
pub use pickup::Pickup;
pub use player::Player;
pub use rng::Rng;
pub use weapon::{Impact, Weapon};

/// How the level is going.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    Playing,
    Won,
    Lost,
}

impl Outcome {
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Playing => "playing",
            Outcome::Won => "won",
            Outcome::Lost => "lost",
        }
    }
}

/// Everything that changes from tick to tick. The level's geometry and placements are not
/// here: they are fixed, and the replay header pins them by content hash.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldState {
    /// Ticks simulated so far.
    pub tick: u32,
    pub player: Player,
    pub lamp: Lamp,
    pub weapon: Weapon,
    /// In the level file's order.
    pub enemies: Vec<Enemy>,
    pub pickups: Vec<Pickup>,
    /// The latest shot marks, oldest first.
    pub impacts: Vec<Impact>,
    pub outcome: Outcome,
    pub rng: Rng,
}

impl WorldState {
    pub fn enemies_left(&self) -> usize {
        self.enemies.iter().filter(|e| e.alive()).count()
    }
}

/// Something that happened in a tick, for the HUD and sound to react to. Not part of the
/// state: the state alone decides what happens next. Everything that makes a sound is here,
/// so the same replay gives the same list, tick by tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    Fired,
    /// The trigger fell on an empty gun with nothing left to load.
    DryFire,
    ReloadStarted,
    Reloaded,
    /// A shot hit the level (`enemy` None) or crawler `enemy` (its index), at `at`.
    Hit {
        enemy: Option<u16>,
        at: Vec3,
    },
    /// Crawler `enemy` died.
    EnemyDown {
        enemy: u16,
    },
    Picked(PickupKind),
    PlayerHurt,
    /// The player's feet: a step in this gait, leaving the ground, or landing at `speed` m/s.
    Footstep(player::Gait),
    Jumped,
    Landed {
        speed: f32,
    },
    LampPickedUp,
    /// The lamp left the head: set down (false) or thrown (true).
    LampLetGo {
        thrown: bool,
    },
    /// The lamp came to rest at `at` after falling or flying at `speed` m/s.
    LampLanded {
        at: Vec3,
        speed: f32,
    },
    /// The lamp went on or off (pressed, or the battery ran out or was refilled).
    LampSwitched {
        on: bool,
    },
    /// Once a second while the lit lamp's battery is low.
    LowBattery,
    /// Crawler `enemy` (its index) has noticed the player (seen, heard, or lit by the beam);
    /// `in_sight`: a clear line from the player's eyes to it.
    Noticed {
        enemy: u16,
        in_sight: bool,
    },
    /// Crawler `enemy` drew a breath (alive, now and then: see [`Enemy::breathes`]).
    Breath {
        enemy: u16,
    },
    /// Crawler `enemy` rears up to strike.
    Strike {
        enemy: u16,
    },
    /// The level is won, by reaching the exit (`exit`) or putting every crawler down.
    Won {
        exit: bool,
    },
    /// The player died.
    Died,
}

impl Event {
    /// Whether the light changes at once, so that what the renderer kept from earlier frames
    /// (its history) says nothing of the next: the lamp leaving the head or coming back.
    pub fn cuts_the_light(&self) -> bool {
        matches!(self, Event::LampPickedUp | Event::LampLetGo { .. })
    }
}

/// A level's fixed gameplay data: its collision geometry and what it places.
pub struct LevelWorld {
    pub collision: LevelCollision,
    pub entities: LevelEntities,
    /// Where crawlers can walk.
    pub nav: nav_grid::NavGrid,
}

impl LevelWorld {
    pub fn new(collision: LevelCollision, entities: LevelEntities) -> Self {
        let body = enemy::body_config();
        // Only crawlers walk the grid: a level without them (any bare scene file) skips it.
        let nav = if entities.enemies.is_empty() {
            nav_grid::NavGrid::empty()
        } else {
            nav_grid::NavGrid::build(&collision, body.radius, body.height)
        };
        Self { collision, entities, nav }
    }
}

/// Builds a level's [`LevelWorld`] once; every simulation of the level shares it.
pub fn level_world(level: &Level) -> anyhow::Result<Arc<LevelWorld>> {
    let collision = LevelCollision::from_scene(&level.scene)
        .map_err(|e| anyhow::anyhow!("{}: cannot build collision geometry: {e}", level.scene_path.display()))?;
    let entities = LevelEntities::read(level)?;
    Ok(Arc::new(LevelWorld::new(collision, entities)))
}

/// The exit is reached within its radius and this far above or below the feet, m.
pub const EXIT_HEIGHT: f32 = 2.0;

/// Where the player starts: feet, yaw and pitch (radians). The level's spawn, or for a bare
/// scene file the feet below the first view's eye.
pub fn start_pose(level: &Level) -> (Vec3, f32, f32) {
    match &level.spawn {
        Some(s) => (s.position, s.yaw, s.pitch),
        None => {
            let camera = engine::start_view::initial_camera(level, &Default::default());
            let f = camera.forward();
            (camera.position - Vec3::Y * scene::DEFAULT_EYE_HEIGHT, (-f.x).atan2(-f.z), f.y.clamp(-1.0, 1.0).asin())
        }
    }
}

/// The world and the fixed things it is simulated against.
pub struct Simulation {
    pub state: WorldState,
    world: Arc<LevelWorld>,
    controller: CharacterController,
    enemy_controller: CharacterController,
    tick_rate: u32,
    /// What happened in the latest tick.
    pub events: Vec<Event>,
}

/// The lamp's beam, for what the enemies notice: a cone this wide (cosine of the half-angle)
/// and this long.
const BEAM_COS: f32 = 0.85;
const BEAM_RANGE: f32 = 16.0;

impl Simulation {
    /// The level as it starts: the player at the spawn (or, for a bare scene file, below the
    /// first view's eye), lamp on and attached, everything the level places where it says.
    pub fn new(level: &Level, world: Arc<LevelWorld>, tick_rate: u32, seed: u64) -> Self {
        let (feet, yaw, pitch) = start_pose(level);
        let units = |radians: f32| command::angle_units(radians).round() as i64;
        let yaw = units(yaw).rem_euclid(65536) as u16;
        let pitch = units(pitch).clamp(-(player::MAX_PITCH as i64), player::MAX_PITCH as i64) as i16;
        Self::at(feet, yaw, pitch, world, tick_rate, seed)
    }

    /// The world with the player standing at `feet`, heading `yaw`, pitch `pitch` (angle units).
    pub fn at(feet: Vec3, yaw: u16, pitch: i16, world: Arc<LevelWorld>, tick_rate: u32, seed: u64) -> Self {
        let config = CharacterConfig::default();
        let state = WorldState {
            tick: 0,
            player: Player::spawn(feet, yaw, pitch, &config),
            lamp: Lamp::new(),
            weapon: Weapon::new(),
            enemies: world.entities.enemies.iter().map(Enemy::spawn).collect(),
            pickups: world.entities.pickups.iter().map(Pickup::spawn).collect(),
            impacts: Vec::new(),
            outcome: Outcome::Playing,
            rng: Rng::new(seed),
        };
        Self {
            state,
            world,
            controller: CharacterController::new(config),
            enemy_controller: CharacterController::new(enemy::body_config()),
            tick_rate,
            events: Vec::new(),
        }
    }

    pub fn tick_rate(&self) -> u32 {
        self.tick_rate
    }

    /// The level data this simulation runs on, to start another one on it.
    pub fn world(&self) -> Arc<LevelWorld> {
        self.world.clone()
    }

    pub fn entities(&self) -> &LevelEntities {
        &self.world.entities
    }

    /// Advances one tick. Once the level is won or lost only the tick count moves, and the
    /// bodies' clocks, so the crawler that ended it still finishes falling.
    pub fn step(&mut self, cmd: &TickCommand) {
        self.events.clear();
        let dt = 1.0 / self.tick_rate as f32;
        if self.state.outcome == Outcome::Playing {
            self.play(cmd, dt);
        } else {
            self.state.enemies.iter_mut().filter(|e| !e.alive()).for_each(Enemy::age);
        }
        self.state.tick += 1;
    }

    fn play(&mut self, cmd: &TickCommand, dt: f32) {
        let level = &self.world.collision;
        let s = &mut self.state;
        let mv = s.player.steer(cmd);
        let body_before = s.player.body;
        self.controller.step(level, &mut s.player.body, &mv, dt);
        s.player.settle_eye(&self.controller.config, dt);
        s.player.hurt_ticks = s.player.hurt_ticks.saturating_sub(1);
        match s.player.footfall(&body_before, dt) {
            Some(player::Footfall::Step(gait)) => self.events.push(Event::Footstep(gait)),
            Some(player::Footfall::Jumped) => self.events.push(Event::Jumped),
            Some(player::Footfall::Landed(speed)) => self.events.push(Event::Landed { speed }),
            None => {}
        }

        let lamp_before = s.lamp;
        s.lamp.step(cmd, &s.player, level, &mut s.rng, self.world.entities.rules.battery_seconds, dt);
        if s.lamp.attached && !lamp_before.attached {
            self.events.push(Event::LampPickedUp);
        } else if !s.lamp.attached && lamp_before.attached {
            self.events.push(Event::LampLetGo { thrown: !cmd.held(command::buttons::LAMP_DETACH) });
        }
        if !s.lamp.attached && s.lamp.resting && !lamp_before.resting {
            self.events.push(Event::LampLanded { at: s.lamp.position, speed: lamp_before.velocity.length() });
        }
        if s.lamp.on && s.lamp.battery < lamp::LOW_BATTERY && s.tick.is_multiple_of(self.tick_rate) {
            self.events.push(Event::LowBattery);
        }

        let gunshot = match s.weapon.step(cmd) {
            weapon::WeaponAction::Shot => true,
            weapon::WeaponAction::DryClick => {
                self.events.push(Event::DryFire);
                false
            }
            weapon::WeaponAction::ReloadStarted => {
                self.events.push(Event::ReloadStarted);
                false
            }
            weapon::WeaponAction::Reloaded => {
                self.events.push(Event::Reloaded);
                false
            }
            weapon::WeaponAction::Nothing => false,
        };
        if gunshot {
            self.events.push(Event::Fired);
            self.shoot();
        }
        self.move_enemies(gunshot, dt);
        self.collect_pickups();

        let s = &mut self.state;
        // A battery picked up can light a dead lamp again: compared after the pickups.
        if s.lamp.on != lamp_before.on {
            self.events.push(Event::LampSwitched { on: s.lamp.on });
        }
        let exit_reached = self.world.entities.exit.is_some_and(|exit| {
            let d = exit.position - s.player.body.position;
            d.x * d.x + d.z * d.z <= exit.radius * exit.radius && d.y.abs() < EXIT_HEIGHT
        });
        s.outcome = if !s.player.alive() {
            Outcome::Lost
        } else if exit_reached || (!s.enemies.is_empty() && s.enemies_left() == 0) {
            Outcome::Won
        } else {
            Outcome::Playing
        };
        match s.outcome {
            Outcome::Won => self.events.push(Event::Won { exit: exit_reached }),
            Outcome::Lost => self.events.push(Event::Died),
            Outcome::Playing => {}
        }
    }

    /// A hitscan shot from the eye along the view: the nearest of the level and the enemies.
    fn shoot(&mut self) {
        let s = &mut self.state;
        let (eye, dir) = (s.player.eye(), s.player.aim());
        let wall = self.world.collision.cast_ray(eye, dir, weapon::RANGE);
        let mut nearest = wall.map_or(weapon::RANGE, |h| h.distance);
        let mut struck = None;
        for (i, e) in s.enemies.iter().enumerate() {
            if !e.alive() {
                continue;
            }
            let (a, b) = e.hit_segment();
            if let Some(t) = weapon::ray_capsule(eye, dir, a, b, enemy::body_config().radius, nearest) {
                nearest = t;
                struck = Some(i);
            }
        }
        let impact = match (struck, wall) {
            (Some(i), _) => {
                let e = &mut s.enemies[i];
                e.shot(weapon::DAMAGE, s.player.body.position);
                let (enemy, at) = (i as u16, eye + dir * nearest);
                self.events.push(Event::Hit { enemy: Some(enemy), at });
                if !e.alive() {
                    self.events.push(Event::EnemyDown { enemy });
                }
                Impact { position: at, normal: -dir, tick: s.tick, on_enemy: true }
            }
            (None, Some(hit)) => {
                self.events.push(Event::Hit { enemy: None, at: hit.point });
                Impact { position: hit.point, normal: hit.normal, tick: s.tick, on_enemy: false }
            }
            (None, None) => return,
        };
        if s.impacts.len() == weapon::MAX_IMPACTS {
            s.impacts.remove(0);
        }
        s.impacts.push(impact);
    }

    fn move_enemies(&mut self, gunshot: bool, dt: f32) {
        let level = &self.world.collision;
        let s = &mut self.state;
        let lamp_on = s.lamp.brightness() > 0.0;
        let (lamp_pos, lamp_dir) = if s.lamp.attached {
            (s.player.eye(), s.player.aim())
        } else {
            (s.lamp.position, player::aim(s.lamp.yaw, s.lamp.pitch))
        };
        // Where every crawler stands as the tick begins: each is pushed off the others' spots.
        let standing: Vec<Option<Vec3>> = s.enemies.iter().map(|e| e.alive().then_some(e.body.position)).collect();
        for (i, (e, spawn)) in s.enemies.iter_mut().zip(&self.world.entities.enemies).enumerate() {
            let chest = e.body.position + Vec3::Y * 0.8;
            let to = chest - lamp_pos;
            let d = to.length();
            let in_beam = lamp_on
                && d < BEAM_RANGE
                && to.dot(lamp_dir) >= BEAM_COS * d
                && enemy::clear_line(level, lamp_pos, chest);
            let far = (s.player.eye() - e.eye()).length();
            let heard = gunshot
                && (far < enemy::HEARING_THROUGH_WALLS
                    || far < enemy::HEARING && enemy::clear_line(level, s.player.eye(), e.eye()));
            let senses = enemy::Senses {
                player_feet: s.player.body.position,
                player_eye: s.player.eye(),
                player_alive: s.player.alive(),
                player_lit: lamp_on && s.lamp.attached,
                lamp_seen_at: (in_beam && !s.lamp.attached).then_some(s.lamp.position),
                in_player_beam: in_beam && s.lamp.attached,
                gunshot: heard,
                crowd: if e.alive() {
                    let others = standing.iter().enumerate().filter(|&(j, _)| j != i);
                    enemy::crowd_push(e.body.position, others.filter_map(|(_, p)| *p))
                } else {
                    Vec3::ZERO
                },
            };
            let mind_before = e.mind;
            let calm = matches!(e.mind, enemy::Mind::Patrol | enemy::Mind::Search);
            if let enemy::Deed::Struck(damage) =
                e.step(&senses, &spawn.route, level, &self.world.nav, &self.enemy_controller, dt)
            {
                s.player.hurt(damage);
                self.events.push(Event::PlayerHurt);
            }
            let index = i as u16;
            if calm && e.mind == enemy::Mind::Alert {
                let in_sight = enemy::clear_line(level, s.player.eye(), e.eye());
                self.events.push(Event::Noticed { enemy: index, in_sight });
            }
            if e.mind == enemy::Mind::Attack && mind_before != enemy::Mind::Attack {
                self.events.push(Event::Strike { enemy: index });
            }
            if e.breathes(s.tick, i) {
                self.events.push(Event::Breath { enemy: index });
            }
        }
    }

    /// Walking over a pickup takes it, when it is of use (a full lamp leaves a battery).
    fn collect_pickups(&mut self) {
        let s = &mut self.state;
        for p in s.pickups.iter_mut() {
            if !p.within_grab(s.player.body.position) {
                continue;
            }
            let used = match p.kind {
                PickupKind::Battery if s.lamp.battery < lamp::FULL => {
                    let was_empty = s.lamp.battery == 0.0;
                    s.lamp.battery = (s.lamp.battery + p.amount).min(1.0);
                    // A lamp that died of an empty battery comes back on with the new one.
                    s.lamp.on |= was_empty;
                    true
                }
                PickupKind::Ammo => s.weapon.add_ammo(p.amount.round() as u16),
                PickupKind::Health if s.player.health < player::MAX_HEALTH => {
                    s.player.health = (s.player.health + p.amount).min(player::MAX_HEALTH);
                    true
                }
                _ => false,
            };
            if used {
                p.taken = true;
                self.events.push(Event::Picked(p.kind));
            }
        }
    }
}

#[cfg(test)]
mod tests;
