use super::*;
use crate::sim::level_entities::EnemySpawn;

fn crawler() -> Enemy {
    let spawn = EnemySpawn { name: String::new(), position: Vec3::ZERO, yaw: 0.0, route: Vec::new() };
    Enemy::spawn(&spawn)
}

/// `e` in `mind` for `timer` ticks, and the tick before it.
fn in_mind(mind: Mind, timer: u16) -> (Enemy, Enemy) {
    let mut cur = crawler();
    cur.mind = mind;
    cur.timer = timer;
    let mut prev = cur;
    prev.timer = timer.saturating_sub(1);
    (prev, cur)
}

fn posed(mind: Mind, timer: u16) -> Pose {
    let (prev, cur) = in_mind(mind, timer);
    pose(&prev, &cur, 1.0, 100.0, 0)
}

fn world_points(p: &Pose) -> Vec<Vec3> {
    let local = p.spine.iter().map(|s| s.0).chain([p.neck, p.head]).chain(p.limbs.iter().flatten().copied());
    local.map(|v| p.to_world.transform_point3(v)).collect()
}

#[test]
fn a_still_crawler_keeps_its_feet_planted_whatever_the_tick() {
    let e = crawler();
    let feet = |clock: f32| pose(&e, &e, 0.5, clock, 0).limbs.map(|l| l[2]);
    let at = feet(10.0);
    for clock in [11.0, 47.5, 300.0] {
        let moved = feet(clock).iter().zip(&at).map(|(a, b)| (*a - *b).length()).fold(0.0, f32::max);
        assert!(moved < 1e-5, "no walk cycle standing still (clock {clock}): moved {moved} m");
    }
    for (foot, shape) in at.iter().zip(&LIMBS) {
        assert!(foot.y.abs() < 1e-3 && (foot.z - shape.rest.z).abs() < 1e-3, "on the ground at rest: {foot}");
    }
}

#[test]
fn a_walking_crawler_cycles_its_legs_with_the_ground_covered() {
    let mut e = crawler();
    e.body.velocity = Vec3::new(0.0, 0.0, -enemy::PATROL_SPEED);
    let at = |walked: f32| {
        let mut cur = e;
        cur.walked = walked;
        pose(&cur, &cur, 1.0, 0.0, 0).limbs.map(|l| l[2])
    };
    // A quarter of the gait apart: every foot has moved; half a gait on, the diagonal pairs have
    // swapped (left hind where the right hind was, along the way).
    let (a, b, c) = (at(0.0), at(0.25 * GAIT), at(0.5 * GAIT));
    for i in 0..4 {
        assert!((a[i] - b[i]).length() > 0.1, "foot {i} moves: {} → {}", a[i], b[i]);
    }
    assert!((a[0].z - c[1].z).abs() < 1e-3 && (a[1].z - c[0].z).abs() < 1e-3, "a trot");
    // Some foot is in the air mid-step, and the same distance walked gives the same pose.
    assert!(b.iter().any(|f| f.y > 0.1), "a foot lifted: {b:?}");
    assert_eq!(at(0.25 * GAIT), b);
    // Blending across the wrap of the gait goes the short way, not back through the cycle.
    let (mut prev, mut cur) = (e, e);
    prev.walked = GAIT - 0.02;
    cur.walked = 0.02;
    assert!((walk_phase(&prev, &cur, 0.5) - TAU).abs() < 1e-4);
}

#[test]
fn the_strike_is_drawn_back_through_the_windup_and_reaches_out_at_its_end() {
    let hand = |timer: u16| {
        let p = posed(Mind::Attack, timer);
        p.to_world.transform_point3(p.limbs[STRIKE_LIMB][2])
    };
    let (start, drawn, struck) = (hand(0), hand(enemy::WINDUP / 2), hand(enemy::WINDUP));
    let rest = posed(Mind::Chase, 5).limbs[STRIKE_LIMB][2];
    assert!((start - rest).length() < 0.05, "starts from the ground: {start} vs {rest}");
    assert!(drawn.y > 1.2 && drawn.z > start.z, "drawn up and back mid-windup: {drawn}");
    // Facing −Z: the claw is out in front by about the reach the simulation strikes at.
    assert!(-struck.z > enemy::REACH * 0.8 && struck.y > 0.5, "reaching out as it lands: {struck}");
    let head = |timer: u16| posed(Mind::Attack, timer).head;
    assert!(head(enemy::WINDUP).z < head(0).z - 0.15, "the head lunges with it");
    let recovered = hand(enemy::WINDUP + enemy::RECOVER);
    assert!((recovered - start).length() < 0.05, "back down after the recovery: {recovered}");
}

#[test]
fn an_alerted_crawler_rears_up_then_comes_down_to_move_in() {
    let head_y = |mind, timer| posed(mind, timer).to_world.transform_point3(posed(mind, timer).head).y;
    let standing = head_y(Mind::Patrol, 0);
    assert!(head_y(Mind::Alert, enemy::NOTICE_TICKS / 2) > standing + 0.15, "reared up");
    assert!((head_y(Mind::Alert, enemy::NOTICE_TICKS) - standing).abs() < 0.02, "down again as it moves in");
    let claws = posed(Mind::Alert, enemy::NOTICE_TICKS / 2).limbs.map(|l| l[2].y);
    assert!(claws[2] > 0.5 && claws[3] > 0.5, "forelimbs raised: {claws:?}");
}

#[test]
fn a_hit_jerks_the_head_back() {
    let (prev, mut cur) = in_mind(Mind::Chase, 30);
    let calm = pose(&prev, &cur, 1.0, 0.0, 0).head;
    cur.flinch = 12;
    let mut before = prev;
    before.flinch = 12;
    let hit = pose(&before, &cur, 1.0, 0.0, 0).head;
    assert!(hit.z > calm.z + 0.1, "thrown back: {hit} vs {calm}");
}

#[test]
fn a_dead_crawler_falls_and_lies_low() {
    let standing = world_points(&posed(Mind::Dead, 0));
    assert!(standing.iter().any(|p| p.y > 1.1), "it starts upright");
    let falling = posed(Mind::Dead, 10);
    assert!(falling.fallen > 0.0 && falling.fallen < 1.0);
    for timer in [20, 400, u16::MAX] {
        let lying = posed(Mind::Dead, timer);
        assert_eq!(lying.fallen, 1.0);
        for p in world_points(&lying) {
            assert!(p.y < 0.75 && p.y > -0.05, "lying on the floor after {timer} ticks: {p}");
        }
    }
}

#[test]
fn the_body_turns_with_the_crawler_and_its_head_leads_the_turn() {
    let (mut prev, mut cur) = in_mind(Mind::Patrol, 3);
    prev.yaw = 0.0;
    cur.yaw = 0.05;
    let p = pose(&prev, &cur, 1.0, 0.0, 0);
    let facing = p.to_world.transform_vector3(Vec3::NEG_Z);
    assert!((facing - Vec3::new(-0.05f32.sin(), 0.0, -0.05f32.cos())).length() < 1e-4);
    let gaze = p.gaze();
    // Turning left (positive yaw): the head looks further left than the body faces.
    assert!(facing.cross(gaze).y > 0.05, "head leads: {gaze} vs {facing}");
    // Blended the short way round across ±π.
    prev.yaw = 3.1;
    cur.yaw = -3.1;
    let mid = pose(&prev, &cur, 0.5, 0.0, 0).to_world.transform_vector3(Vec3::NEG_Z);
    assert!((mid - Vec3::Z).length() < 0.05, "{mid}");
}

fn beam_at_eye(eye: Vec3) -> LampLight {
    LampLight {
        position: Vec3::new(0.0, 1.3, -5.0),
        direction: (eye - Vec3::new(0.0, 1.3, -5.0)).normalize(),
        intensity: Vec3::splat(40.0),
        cos_inner: 20f32.to_radians().cos(),
        cos_outer: 30f32.to_radians().cos(),
        viewer: Vec3::new(0.0, 1.3, -5.0),
    }
}

#[test]
fn eyes_shine_back_as_squarely_as_the_beam_falls_on_them() {
    let eye = Vec3::new(0.0, 1.3, 0.0);
    let lamp = beam_at_eye(eye);
    let looking = Vec3::NEG_Z;
    let full = eyeshine(eye, looking, &lamp);
    // E = I / d², returned as R_A·E, tinted.
    let expected = 40.0 / 25.0 * RETROREFLECTION;
    assert!((full.x - expected).abs() < 1e-3 * expected, "{full} vs {expected}");
    // Twice as far: a quarter.
    let mut far = lamp;
    far.position.z = -10.0;
    far.viewer = far.position;
    assert!((eyeshine(eye, looking, &far).x - expected / 4.0).abs() < 1e-3 * expected);
    // Looking 60° away: half (cosine); looking away: none.
    let aside = Vec3::new(-(60f32.to_radians().sin()), 0.0, -(60f32.to_radians().cos()));
    assert!((eyeshine(eye, aside, &lamp).x - expected * 0.5).abs() < 1e-3 * expected);
    assert_eq!(eyeshine(eye, Vec3::Z, &lamp), Vec3::ZERO);
    // Outside the beam's cone, and with the lamp off: none.
    let mut aimed_off = lamp;
    aimed_off.direction = Vec3::new(1.0, 0.0, 1.0).normalize();
    assert_eq!(eyeshine(eye, looking, &aimed_off), Vec3::ZERO);
    assert_eq!(eyeshine(eye, looking, &LampLight::OFF), Vec3::ZERO);
    // A lamp set down, seen from the side: the light goes back to the lamp, not to the player.
    let mut set_down = lamp;
    set_down.viewer = Vec3::new(4.0, 1.3, -3.0);
    assert_eq!(eyeshine(eye, looking, &set_down), Vec3::ZERO);
}

#[test]
fn instances_show_eyeshine_alive_and_dull_eyes_dead() {
    let meshes = CrawlerMeshes::fake(0);
    let eye_glow = |mind, lamp: &LampLight| {
        let (prev, cur) = in_mind(mind, 2);
        let mut out = Vec::new();
        meshes.instances(&mut out, (&prev, &cur), 1.0, 0.0, 0, lamp);
        let eyes: Vec<f32> =
            out.iter().filter(|i| i.transform.x_axis.truncate().length() < 0.05).map(|i| i.emissive[0]).collect();
        assert_eq!(eyes.len(), 2, "two eyes");
        eyes[0]
    };
    let eye = posed(Mind::Patrol, 2).eyes()[0];
    let lit = beam_at_eye(eye);
    assert!(eye_glow(Mind::Patrol, &lit) > 10.0 * eye_glow(Mind::Patrol, &LampLight::OFF));
    assert_eq!(eye_glow(Mind::Dead, &lit), 0.0);
}
