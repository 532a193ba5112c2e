//! What every menu screen is drawn with: the centred panel, the heading, the wide button.

use engine::egui::{self, Color32, RichText};

const BUTTON_WIDTH: f32 = 240.0;

/// A screen's centred panel. `id` keeps each screen's size apart (areas remember theirs).
pub(super) fn panel<R>(ctx: &egui::Context, id: &str, add_contents: impl FnOnce(&mut egui::Ui) -> R) -> R {
    egui::Area::new(egui::Id::unique(id))
        .order(egui::Order::Foreground)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            egui::Frame::NONE
                .fill(Color32::from_rgba_unmultiplied(16, 16, 20, 240))
                .stroke(egui::Stroke::new(1.0, Color32::from_gray(70)))
                .corner_radius(10.0)
                .inner_margin(egui::Margin::same(24))
                .show(ui, |ui| ui.vertical_centered(add_contents).inner)
                .inner
        })
        .inner
}

pub(super) fn heading(ui: &mut egui::Ui, text: &str) {
    ui.label(RichText::new(text).size(32.0).strong().color(Color32::from_gray(240)));
    ui.add_space(16.0);
}

/// A wide menu button; true when clicked.
pub(super) fn big_button(ui: &mut egui::Ui, text: &str) -> bool {
    let button = egui::Button::new(RichText::new(text).size(20.0));
    ui.add_sized(egui::vec2(BUTTON_WIDTH, 40.0), button).clicked()
}
