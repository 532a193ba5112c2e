//! The crawler: a slow, pale thing that lives in the dark. It patrols its route, notices the
//! player by sight (far further when the headlamp shines), by the lamp's beam falling on it, or
//! by gunshots; it turns, closes in and strikes. A lamp lying elsewhere draws it away: it goes
//! to look at the light.

use glam::Vec3;
use physics::{CharacterBody, CharacterConfig, CharacterController, CharacterMove, LevelCollision};

use super::level_entities::EnemySpawn;
use super::nav_grid::NavGrid;

pub const MAX_HEALTH: f32 = 100.0;
pub const PATROL_SPEED: f32 = 1.4;
pub const CHASE_SPEED: f32 = 3.3;
/// Turning speed, rad/s.
pub const TURN_RATE: f32 = 4.0;
/// Sight range with the player's headlamp on and attached (the player is a beacon), and
/// without it (a shape in the dark), m.
pub const SIGHT_LIT: f32 = 20.0;
pub const SIGHT_DARK: f32 = 5.0;
/// Half-angle of the field of view, as the cosine (70°).
pub const SIGHT_COS: f32 = 0.342;
/// Heard (felt) at this distance whatever the light, m.
pub const SENSE_RANGE: f32 = 2.0;
/// A gunshot is heard this far in the open, and this far through walls, m.
pub const HEARING: f32 = 24.0;
pub const HEARING_THROUGH_WALLS: f32 = 9.0;
/// Ticks between noticing and moving in: the crawler turns and rears up first.
pub const NOTICE_TICKS: u16 = 24;
/// Attack: starts within REACH (horizontal, m), lands after WINDUP ticks if the player is
/// still within HIT_RANGE, then waits RECOVER ticks.
pub const REACH: f32 = 1.3;
pub const HIT_RANGE: f32 = 1.9;
pub const WINDUP: u16 = 24;
pub const RECOVER: u16 = 40;
pub const DAMAGE: f32 = 18.0;
/// Having lost the player, it searches the last place it saw them for this long.
pub const SEARCH_TICKS: u16 = 240;
/// Close enough to a waypoint or target, m.
const ARRIVED: f32 = 0.5;
/// Ground covered by one full cycle of a crawler's legs, m: [`Enemy::walked`] is kept modulo
/// this, so the walk cycle it drives stays exact however long the game.
pub const GAIT: f32 = 1.2;
/// Ticks between a crawler's breaths: slow while it wanders, quick while it hunts.
pub const BREATH_CALM: u32 = 150;
pub const BREATH_HUNTING: u32 = 70;
/// Each crawler's breaths are offset by this many ticks times its index, so a pack does not
/// breathe in unison.
pub const BREATH_STAGGER: u32 = 37;

/// A crawler's body.
pub fn body_config() -> CharacterConfig {
    CharacterConfig { radius: 0.35, height: 1.5, crouch_height: 1.5, jump_speed: 0.0, ..Default::default() }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mind {
    /// Walking its route (or guarding its spot).
    Patrol,
    /// Noticed something; turning to it.
    Alert,
    /// Going for the player (or for what it last saw).
    Chase,
    /// Mid-strike.
    Attack,
    /// Looking around where it last saw the player, or where a light is.
    Search,
    Dead,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enemy {
    pub body: CharacterBody,
    /// Facing, radians (0 faces −Z, positive turns left).
    pub yaw: f32,
    pub health: f32,
    pub mind: Mind,
    /// Ticks in the current state of mind.
    pub timer: u16,
    /// Where it is heading in Chase/Search.
    pub target: Vec3,
    /// Index into its route.
    pub waypoint: u16,
    /// Ticks left of the flinch shown after a hit.
    pub flinch: u8,
    /// Ground covered so far (horizontally, as moved, walls included), m, modulo [`GAIT`]: the
    /// phase of the walk cycle, so a replay's legs move exactly as they did.
    pub walked: f32,
}

/// What the enemy perceives this tick, gathered by the simulation.
pub struct Senses {
    pub player_feet: Vec3,
    pub player_eye: Vec3,
    pub player_alive: bool,
    /// The player's lamp is on and on their head.
    pub player_lit: bool,
    /// The lamp's beam falls on this enemy from a lamp lying at this position.
    pub lamp_seen_at: Option<Vec3>,
    /// The lamp's beam, on the player's head, falls on this enemy.
    pub in_player_beam: bool,
    /// A gunshot this tick, heard here.
    pub gunshot: bool,
    /// Away from the other crawlers pressing on this one (zero when none is within
    /// [`CROWD_RADIUS`]), as a fraction of walking speed.
    pub crowd: Vec3,
}

/// Crawlers closer than this (m, between centres) push apart, so a pack does not melt into one
/// body.
pub const CROWD_RADIUS: f32 = 0.8;

/// The push away from `others` (alive crawlers' feet) on a crawler at `feet`: for each one
/// nearer than [`CROWD_RADIUS`], the unit direction away from it scaled by how deep it presses.
pub fn crowd_push(feet: Vec3, others: impl Iterator<Item = Vec3>) -> Vec3 {
    others.fold(Vec3::ZERO, |push, other| {
        let away = horizontal(feet - other);
        let d = away.length();
        if !(1e-4..CROWD_RADIUS).contains(&d) {
            return push;
        }
        push + away / d * (1.0 - d / CROWD_RADIUS)
    })
}

/// What an enemy did this tick that the world must apply.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Deed {
    Nothing,
    Struck(f32),
}

impl Enemy {
    pub fn spawn(s: &EnemySpawn) -> Self {
        Self {
            body: CharacterBody::standing_at(s.position),
            yaw: s.yaw,
            health: MAX_HEALTH,
            mind: Mind::Patrol,
            timer: 0,
            target: s.position,
            waypoint: 0,
            flinch: 0,
            walked: 0.0,
        }
    }

    pub fn alive(&self) -> bool {
        self.mind != Mind::Dead
    }

    /// Whether crawler `index` (its place in the level's list) draws a breath on `tick`: each
    /// its own beat, offset by its index so a pack does not breathe in unison.
    pub fn breathes(&self, tick: u32, index: usize) -> bool {
        let period = match self.mind {
            Mind::Dead => return false,
            Mind::Patrol | Mind::Search => BREATH_CALM,
            Mind::Alert | Mind::Chase | Mind::Attack => BREATH_HUNTING,
        };
        (tick + index as u32 * BREATH_STAGGER).is_multiple_of(period)
    }

    /// Eye height of a crawler, m above its feet.
    pub fn eye(&self) -> Vec3 {
        self.body.position + Vec3::Y * 1.3
    }

    /// The capsule segment bullets test against (with [`body_config`]'s radius).
    pub fn hit_segment(&self) -> (Vec3, Vec3) {
        let r = body_config().radius;
        (self.body.position + Vec3::Y * r, self.body.position + Vec3::Y * (body_config().height - r))
    }

    fn facing(&self) -> Vec3 {
        Vec3::new(-libm::sinf(self.yaw), 0.0, -libm::cosf(self.yaw))
    }

    /// A hit: damage, and it knows where the shot came from.
    pub fn shot(&mut self, damage: f32, from: Vec3) {
        if !self.alive() {
            return;
        }
        self.health -= damage;
        self.flinch = 12;
        if self.health <= 0.0 {
            self.health = 0.0;
            self.mind = Mind::Dead;
            self.timer = 0;
            return;
        }
        self.target = from;
        if matches!(self.mind, Mind::Patrol | Mind::Search) {
            self.set_mind(Mind::Alert);
        }
    }

    /// A tick passes: the flinch fades and the time in this state of mind runs (for a body, the
    /// time since it fell, which its drawn fall follows).
    pub fn age(&mut self) {
        self.flinch = self.flinch.saturating_sub(1);
        self.timer = self.timer.saturating_add(1);
    }

    fn set_mind(&mut self, mind: Mind) {
        self.mind = mind;
        self.timer = 0;
    }

    /// Whether it sees the player this tick.
    fn sees_player(&self, s: &Senses, level: &LevelCollision) -> bool {
        if !s.player_alive {
            return false;
        }
        let to = s.player_eye - self.eye();
        let d = to.length();
        if d < SENSE_RANGE {
            return true;
        }
        let range = if s.player_lit { SIGHT_LIT } else { SIGHT_DARK };
        let in_view =
            to.x * self.facing().x + to.z * self.facing().z >= SIGHT_COS * libm::sqrtf(to.x * to.x + to.z * to.z);
        (d < range && in_view || s.in_player_beam) && clear_line(level, self.eye(), s.player_eye)
    }

    /// One tick of thinking and moving.
    pub fn step(
        &mut self,
        s: &Senses,
        route: &[Vec3],
        level: &LevelCollision,
        nav: &NavGrid,
        controller: &CharacterController,
        dt: f32,
    ) -> Deed {
        self.age();
        if self.mind == Mind::Dead {
            return Deed::Nothing;
        }
        let sees = self.sees_player(s, level);
        if sees {
            self.target = s.player_feet;
        }
        let mut deed = Deed::Nothing;
        let mut goal = None;
        let mut speed = 0.0;
        match self.mind {
            Mind::Patrol | Mind::Search => {
                if sees || s.gunshot {
                    self.target = s.player_feet;
                    self.set_mind(Mind::Alert);
                } else if let Some(lamp) = s.lamp_seen_at {
                    // A light where there was none: go and look.
                    self.target = lamp;
                    if self.mind == Mind::Patrol {
                        self.set_mind(Mind::Search);
                    }
                }
            }
            _ => {}
        }
        match self.mind {
            Mind::Patrol => {
                if let Some(&point) = route.get(self.waypoint as usize) {
                    if horizontal(point - self.body.position).length() < ARRIVED {
                        self.waypoint = ((self.waypoint as usize + 1) % route.len()) as u16;
                    }
                    goal = Some(route[self.waypoint as usize]);
                    speed = PATROL_SPEED;
                }
            }
            Mind::Alert => {
                self.turn_towards(self.target, dt);
                if self.timer >= NOTICE_TICKS {
                    self.set_mind(Mind::Chase);
                }
            }
            Mind::Chase => {
                let near = horizontal(s.player_feet - self.body.position).length();
                if sees && near < REACH {
                    self.set_mind(Mind::Attack);
                } else if !sees && horizontal(self.target - self.body.position).length() < ARRIVED {
                    self.set_mind(Mind::Search);
                } else {
                    goal = Some(self.target);
                    speed = CHASE_SPEED;
                }
            }
            Mind::Attack => {
                self.turn_towards(s.player_feet, dt);
                if self.timer == WINDUP {
                    let near = horizontal(s.player_feet - self.body.position).length();
                    if s.player_alive && near < HIT_RANGE && (s.player_feet.y - self.body.position.y).abs() < 1.5 {
                        deed = Deed::Struck(DAMAGE);
                    }
                } else if self.timer >= WINDUP + RECOVER {
                    self.set_mind(Mind::Chase);
                }
            }
            Mind::Search => {
                if horizontal(self.target - self.body.position).length() > ARRIVED && self.timer < SEARCH_TICKS {
                    goal = Some(self.target);
                    speed = PATROL_SPEED;
                } else if self.timer >= SEARCH_TICKS {
                    self.set_mind(Mind::Patrol);
                } else {
                    // Look around.
                    self.yaw += 1.5 * dt;
                }
            }
            Mind::Dead => {}
        }
        let mut wish = Vec3::ZERO;
        if let Some(mut goal) = goal {
            // Out of sight, the way there goes round walls: the grid's next step.
            let lift = Vec3::Y * 0.8;
            if !clear_line(level, self.body.position + lift, goal + lift) {
                goal = nav.next_step(self.body.position, goal).unwrap_or(goal);
            }
            let to = horizontal(goal - self.body.position);
            let len = to.length();
            if len > 1e-3 {
                let way = open_direction(level, self.body.position, to / len, len, self.facing());
                self.turn_towards(self.body.position + way, dt);
                // Walk where it faces, so it turns before it strides off.
                let along = way.dot(self.facing()).max(0.0);
                wish = self.facing() * speed * along;
            }
        }
        if s.crowd != Vec3::ZERO {
            wish += s.crowd * PATROL_SPEED;
        }
        let mv = CharacterMove { wish_velocity: wish, jump: false, crouch: false };
        let before = self.body.position;
        controller.step(level, &mut self.body, &mv, dt);
        self.walked += horizontal(self.body.position - before).length();
        if self.walked >= GAIT {
            self.walked -= GAIT * libm::floorf(self.walked / GAIT);
        }
        deed
    }

    fn turn_towards(&mut self, point: Vec3, dt: f32) {
        let to = point - self.body.position;
        if to.x * to.x + to.z * to.z < 1e-6 {
            return;
        }
        let wanted = libm::atan2f(-to.x, -to.z);
        let mut delta = wanted - self.yaw;
        // Wrap into (−π, π].
        delta -= std::f32::consts::TAU * libm::floorf((delta + std::f32::consts::PI) / std::f32::consts::TAU);
        let max = TURN_RATE * dt;
        self.yaw += delta.clamp(-max, max);
        self.yaw -= std::f32::consts::TAU * libm::floorf((self.yaw + std::f32::consts::PI) / std::f32::consts::TAU);
    }
}

/// How far ahead a crawler looks for something in its way, m.
const LOOK_AHEAD: f32 = 1.2;

/// The direction to walk towards a goal `distance` away along unit `dir`: straight if the way
/// is clear for [`LOOK_AHEAD`] (or up to the goal), else the smallest turn either side, in 20°
/// steps, that is — a crawler feels its way round a crate instead of pushing into it. Of the
/// two sides it tries the one it already faces first, so it does not dither between them. The
/// body's width is probed with three parallel rays at knee and chest height.
fn open_direction(level: &LevelCollision, feet: Vec3, dir: Vec3, distance: f32, facing: Vec3) -> Vec3 {
    let reach = LOOK_AHEAD.min(distance);
    let radius = body_config().radius;
    let clear = |d: Vec3| {
        let side = Vec3::new(-d.z, 0.0, d.x) * radius;
        [0.4, 1.1].iter().all(|&h| {
            [-1.0, 0.0, 1.0].iter().all(|&k| {
                let origin = feet + Vec3::Y * h + side * k;
                level.cast_ray(origin, d, reach + radius).is_none()
            })
        })
    };
    if clear(dir) {
        return dir;
    }
    // Positive angles turn from +X towards −Z (counter-clockwise seen from above).
    let first = if dir.x * facing.z - dir.z * facing.x < 0.0 { 1.0 } else { -1.0 };
    for step in 1..=6 {
        for sign in [first, -first] {
            let angle = sign * step as f32 * 20f32.to_radians();
            let (s, c) = (libm::sinf(angle), libm::cosf(angle));
            let turned = Vec3::new(dir.x * c + dir.z * s, 0.0, -dir.x * s + dir.z * c);
            if clear(turned) {
                return turned;
            }
        }
    }
    dir
}

fn horizontal(v: Vec3) -> Vec3 {
    Vec3::new(v.x, 0.0, v.z)
}

/// Nothing of the level between `a` and `b`.
pub fn clear_line(level: &LevelCollision, a: Vec3, b: Vec3) -> bool {
    let d = b - a;
    let len = d.length();
    len < 1e-4 || level.cast_ray(a, d / len, len).is_none()
}
