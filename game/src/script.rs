//! Hand-written input scripts: a text file of timed inputs that becomes a replay without a
//! window, so tests and demos can be authored in an editor.
//!
//! One step per line: `TICKS ACTION...`, held for TICKS ticks (60 ticks = 1 s at the default
//! rate). `#` starts a comment. Actions may be combined on one line:
//!
//! | action          | meaning                                                           |
//! |-----------------|-------------------------------------------------------------------|
//! | `wait`          | nothing (stand still)                                             |
//! | `forward` `back`| walk forward / backward                                           |
//! | `left` `right`  | strafe                                                            |
//! | `sprint`        | hold sprint                                                       |
//! | `crouch`        | hold crouch                                                       |
//! | `jump`          | hold jump (jumps on landing while held)                           |
//! | `turn DEG`      | turn DEG degrees in all over the step, positive to the left       |
//! | `look DEG`      | pitch DEG degrees in all over the step, positive up               |
//! | `fire`          | hold the trigger (fires as fast as the gun allows)                |
//! | `reload`        | reload (on the step's first tick)                                 |
//! | `lamp toggle`   | switch the headlamp on/off (on the step's first tick)             |
//! | `lamp detach`   | set the lamp down / pick it up (on the step's first tick)         |
//! | `lamp throw`    | throw the lamp where you look (on the step's first tick)          |

use std::path::Path;

use crate::sim::command::{angle_units, buttons, TickCommand};

/// More ticks than this in one script is a typo: 5 hours at 60 Hz (the one table of limits
/// is `scene::limits`).
pub const MAX_TICKS: u64 = scene::limits::MAX_SCRIPT_TICKS;

/// Parses a script into one command per tick; errors name the file and line.
pub fn parse(text: &str, path: &Path) -> Result<Vec<TickCommand>, String> {
    parse_steps(text, path).map(|(commands, _)| commands)
}

/// Where a script's steps end: its line number (from 1) and the tick count after the step.
pub type StepEnd = (usize, usize);

/// [`parse`], also saying where each line's step ends.
pub fn parse_steps(text: &str, path: &Path) -> Result<(Vec<TickCommand>, Vec<StepEnd>), String> {
    let mut out = Vec::new();
    let mut ends = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let at = |msg: String| format!("{}:{}: {msg}", path.display(), n + 1);
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let mut words = line.split_whitespace();
        let count_word = words.next().expect("non-empty line");
        let ticks: u64 =
            count_word.parse().ok().filter(|&t| t > 0).ok_or_else(|| {
                at(format!("'{count_word}' is not a tick count (a whole number ≥ 1 starts every line)"))
            })?;
        if out.len() as u64 + ticks > MAX_TICKS {
            return Err(at(format!("the script runs past {MAX_TICKS} ticks")));
        }
        let step = Step::parse(words).map_err(at)?;
        let turn = spread(angle_units(step.turn_deg.to_radians()), ticks).map_err(at)?;
        let look = spread(angle_units(step.look_deg.to_radians()), ticks).map_err(at)?;
        for t in 0..ticks {
            let presses = if t == 0 { step.presses } else { 0 };
            out.push(TickCommand {
                forward: step.forward,
                strafe: step.strafe,
                turn: turn(t),
                look: look(t),
                buttons: step.held | presses,
            });
        }
        ends.push((n + 1, out.len()));
    }
    Ok((out, ends))
}

pub fn read(path: &Path) -> Result<Vec<TickCommand>, String> {
    read_steps(path).map(|(commands, _)| commands)
}

/// [`read`], also saying where each line's step ends.
pub fn read_steps(path: &Path) -> Result<(Vec<TickCommand>, Vec<StepEnd>), String> {
    let text = scene::limits::read_text(path, scene::limits::MAX_TEXT_BYTES)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    parse_steps(&text, path)
}

#[derive(Default)]
struct Step {
    forward: i8,
    strafe: i8,
    held: u8,
    presses: u8,
    turn_deg: f32,
    look_deg: f32,
}

const ACTIONS: &str = "wait, forward, back, left, right, sprint, crouch, jump, fire, reload, turn DEG, look DEG, \
                       lamp toggle, lamp detach, lamp throw";

impl Step {
    fn parse<'a>(mut words: impl Iterator<Item = &'a str>) -> Result<Self, String> {
        let mut s = Step::default();
        let mut any = false;
        while let Some(w) = words.next() {
            any = true;
            match w {
                "wait" => {}
                "forward" => s.forward = 127,
                "back" => s.forward = -127,
                "right" => s.strafe = 127,
                "left" => s.strafe = -127,
                "sprint" => s.held |= buttons::SPRINT,
                "crouch" => s.held |= buttons::CROUCH,
                "jump" => s.held |= buttons::JUMP,
                "fire" => s.held |= buttons::FIRE,
                "reload" => s.presses |= buttons::RELOAD,
                "turn" | "look" => {
                    let v = words.next().ok_or_else(|| format!("'{w}' needs a number of degrees"))?;
                    let deg: f32 = v
                        .parse()
                        .ok()
                        .filter(|d: &f32| d.is_finite())
                        .ok_or_else(|| format!("'{w} {v}': '{v}' is not a number of degrees"))?;
                    if w == "turn" {
                        s.turn_deg = deg;
                    } else {
                        s.look_deg = deg;
                    }
                }
                "lamp" => match words.next() {
                    Some("toggle") => s.presses |= buttons::LAMP_TOGGLE,
                    Some("detach") => s.presses |= buttons::LAMP_DETACH,
                    Some("throw") => s.presses |= buttons::LAMP_THROW,
                    other => {
                        return Err(format!(
                            "'lamp {}': expected lamp toggle, lamp detach or lamp throw",
                            other.unwrap_or("")
                        ))
                    }
                },
                _ => return Err(format!("unknown action '{w}' (known: {ACTIONS})")),
            }
        }
        if !any {
            return Err(format!("a tick count needs an action (known: {ACTIONS})"));
        }
        Ok(s)
    }
}

/// Splits `total` angle units over `ticks` whole-unit steps that add up to exactly the rounded
/// total, spreading the remainder evenly.
fn spread(total: f32, ticks: u64) -> Result<impl Fn(u64) -> i16, String> {
    let total = total.round() as i64;
    if total.unsigned_abs() / ticks > i16::MAX as u64 {
        return Err(format!("turning {total} angle units in {ticks} ticks is more than {} per tick", i16::MAX));
    }
    let ticks = ticks as i64;
    Ok(move |t: u64| {
        let t = t as i64;
        ((total * (t + 1)).div_euclid(ticks) - (total * t).div_euclid(ticks)) as i16
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(text: &str) -> Result<Vec<TickCommand>, String> {
        parse(text, Path::new("s.txt"))
    }

    #[test]
    fn steps_become_ticks() {
        let c = p("# a walk\n60 forward\n\n30 turn 15 # quarter of a right angle... ish\n1 lamp toggle\n2 left jump\n")
            .unwrap();
        assert_eq!(c.len(), 93);
        assert!(c[..60].iter().all(|c| c.forward == 127 && c.turn == 0 && c.buttons == 0));
        let turned: i32 = c[60..90].iter().map(|c| c.turn as i32).sum();
        assert_eq!(turned, (15.0f32 / 360.0 * 65536.0).round() as i32, "the total turn is exact");
        let first = c[60].turn;
        assert!(c[60..90].iter().all(|c| (c.turn - first).abs() <= 1), "and evenly spread");
        assert_eq!(c[90].buttons, buttons::LAMP_TOGGLE);
        assert_eq!((c[91].strafe, c[91].buttons, c[92].buttons), (-127, buttons::JUMP, buttons::JUMP));
    }

    #[test]
    fn presses_reach_one_tick_only() {
        let c = p("5 lamp detach forward").unwrap();
        assert_eq!(c[0].buttons, buttons::LAMP_DETACH);
        assert!(c[1..].iter().all(|c| c.buttons == 0 && c.forward == 127));
    }

    #[test]
    fn the_gun_and_the_lamp_throw_have_actions() {
        let c = p("3 fire reload lamp throw").unwrap();
        assert_eq!(c[0].buttons, buttons::FIRE | buttons::RELOAD | buttons::LAMP_THROW);
        assert!(c[1..].iter().all(|c| c.buttons == buttons::FIRE), "fire is held, the others pressed");
    }

    #[test]
    fn negative_turns_add_up_too() {
        let c = p("7 turn -100 look -10").unwrap();
        let sum: i32 = c.iter().map(|c| c.turn as i32).sum();
        assert_eq!(sum, (-100.0f32 / 360.0 * 65536.0).round() as i32);
    }

    #[test]
    fn mistakes_name_the_line() {
        for (text, needle) in [
            ("10 forwrd", "s.txt:1: unknown action 'forwrd'"),
            ("\n\nx forward", "s.txt:3: 'x' is not a tick count"),
            ("0 forward", "s.txt:1: '0' is not a tick count"),
            ("10", "needs an action"),
            ("10 turn", "'turn' needs a number"),
            ("10 turn left", "'left' is not a number"),
            ("10 lamp off", "expected lamp toggle, lamp detach or lamp throw"),
            ("1 turn 100000", "per tick"),
            ("99999999999 wait", "runs past"),
        ] {
            let e = p(text).unwrap_err();
            assert!(e.contains(needle), "{text:?} → {e}");
        }
    }
}
