//! One tick of player input, quantised to exactly what the simulation consumes: this is what a
//! replay stores, so playing live and replaying run the same numbers.

/// Yaw and pitch are whole units of 1/65536 of a turn (Doom's angle units): integers add up
/// exactly, so a replay turns the player to the same bit-exact heading.
pub const ANGLE_UNITS_PER_TURN: f32 = 65536.0;

/// Buttons, as bits of [`TickCommand::buttons`]. Held buttons (jump, crouch, sprint, fire) are
/// set on every tick they are down; the others are presses, set on one tick only.
pub mod buttons {
    pub const JUMP: u8 = 1 << 0;
    pub const CROUCH: u8 = 1 << 1;
    pub const SPRINT: u8 = 1 << 2;
    /// Switch the headlamp on or off.
    pub const LAMP_TOGGLE: u8 = 1 << 3;
    /// Set the lamp down in front of you, or pick it back up when it is within reach.
    pub const LAMP_DETACH: u8 = 1 << 4;
    /// Fire the weapon (held: it fires again as soon as it can).
    pub const FIRE: u8 = 1 << 5;
    /// Reload the weapon.
    pub const RELOAD: u8 = 1 << 6;
    /// Throw the lamp where you look.
    pub const LAMP_THROW: u8 = 1 << 7;
    pub const ALL: u8 = JUMP | CROUCH | SPRINT | LAMP_TOGGLE | LAMP_DETACH | FIRE | RELOAD | LAMP_THROW;
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TickCommand {
    /// Forward (+) / back (−) as a fraction of full speed, ×127.
    pub forward: i8,
    /// Right (+) / left (−), ×127.
    pub strafe: i8,
    /// Yaw change, angle units; positive turns left (counter-clockwise seen from above).
    pub turn: i16,
    /// Pitch change, angle units; positive looks up.
    pub look: i16,
    pub buttons: u8,
}

impl TickCommand {
    /// Bytes per command in a replay.
    pub const SIZE: usize = 7;

    pub fn held(&self, button: u8) -> bool {
        self.buttons & button != 0
    }

    pub fn encode(&self) -> [u8; Self::SIZE] {
        let [t0, t1] = self.turn.to_le_bytes();
        let [l0, l1] = self.look.to_le_bytes();
        [self.forward as u8, self.strafe as u8, t0, t1, l0, l1, self.buttons]
    }

    /// Reads a command back. Every button bit has a meaning now, so a wider command (a new
    /// `command_size` in the replay header) is how more buttons would arrive.
    pub fn decode(bytes: &[u8]) -> Result<Self, String> {
        let b: &[u8; Self::SIZE] =
            bytes.try_into().map_err(|_| format!("a command is {} bytes, not {}", Self::SIZE, bytes.len()))?;
        Ok(Self {
            forward: b[0] as i8,
            strafe: b[1] as i8,
            turn: i16::from_le_bytes([b[2], b[3]]),
            look: i16::from_le_bytes([b[4], b[5]]),
            buttons: b[6],
        })
    }
}

/// Radians → angle units, fractional (scripts and mouse input round them).
pub fn angle_units(radians: f32) -> f32 {
    radians * ANGLE_UNITS_PER_TURN / std::f32::consts::TAU
}

/// Angle units → radians.
pub fn radians(units: f32) -> f32 {
    units * (std::f32::consts::TAU / ANGLE_UNITS_PER_TURN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_round_trip_through_bytes() {
        let c = TickCommand { forward: -127, strafe: 64, turn: -12345, look: 300, buttons: buttons::ALL };
        assert_eq!(TickCommand::decode(&c.encode()), Ok(c));
        assert!(TickCommand::decode(&[0; 6]).is_err());
    }
}
