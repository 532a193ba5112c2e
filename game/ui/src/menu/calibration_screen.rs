//! The brightness screen a first start opens (Game Accessibility Guidelines: let players set
//! brightness against a reference): squares of dark scene radiance drawn through the game's own
//! tonemap at the chosen brightness, over black; the player raises the brightness until the
//! dimmest is only just visible.

use engine::egui::{self, Color32, RichText};

use super::widgets::{big_button, heading, panel};
use crate::config::Config;

/// Tonemap inputs of the squares at brightness 0, as fractions of a white wall 4 m from the
/// lamp (which the shipped levels' exposures show mid-grey: about 0.19 into the tonemap).
const WALL_AT_4M: f32 = 0.19;
const SQUARES: [f32; 4] = [1.0 / 64.0, 1.0 / 16.0, 1.0 / 4.0, 1.0];
const SIZE: f32 = 72.0;

/// What the present pass shows for a tonemap input `x` (radiance × exposure): Narkowicz's ACES
/// fit, then sRGB encoding, as `shaders/common.wgsl` and `shaders/present.wgsl` do.
pub fn displayed(x: f32) -> u8 {
    let x = x.max(0.0);
    let c = ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

/// Draws the screen; true when Done is clicked (the config then says it was calibrated).
pub(super) fn show(ctx: &egui::Context, config: &mut Config) -> bool {
    let mut done = false;
    panel(ctx, "brightness", |ui| {
        heading(ui, "Set the brightness");
        ui.label("Headlamp's levels are dark. Raise the brightness until the dimmest square");
        ui.label("below is only just visible against the black.");
        ui.add_space(12.0);
        egui::Frame::NONE.fill(Color32::BLACK).inner_margin(egui::Margin::same(16)).show(ui, |ui| {
            ui.horizontal(|ui| {
                for f in SQUARES {
                    let v = displayed(WALL_AT_4M * f * config.exposure_scale());
                    let (rect, _) = ui.allocate_exact_size(egui::vec2(SIZE, SIZE), egui::Sense::hover());
                    ui.painter().rect_filled(rect, 2.0, Color32::from_gray(v));
                }
            });
        });
        ui.add_space(12.0);
        let slider = egui::Slider::new(&mut config.brightness, Config::BRIGHTNESS_RANGE)
            .step_by(0.1)
            .fixed_decimals(1)
            .suffix(" stops")
            .text("Brightness");
        ui.add(slider);
        ui.label(RichText::new("Settings > Video changes it later.").weak());
        ui.add_space(12.0);
        if big_button(ui, "Done") {
            config.calibrated = true;
            done = true;
        }
    });
    done
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_squares_go_through_the_games_tonemap() {
        assert_eq!(displayed(0.0), 0);
        assert_eq!(displayed(100.0), 255, "the tonemap saturates");
        // A white wall 4 m away shows mid-grey, as the shipped levels' exposures intend.
        assert!((135..=155).contains(&displayed(WALL_AT_4M)), "{}", displayed(WALL_AT_4M));
        // At brightness 0 the dimmest square is just above black; two stops up, clearly grey.
        let dimmest = WALL_AT_4M * SQUARES[0];
        assert!((1..=6).contains(&displayed(dimmest)), "{}", displayed(dimmest));
        assert!(displayed(dimmest * 4.0) > 3 * displayed(dimmest));
    }
}
