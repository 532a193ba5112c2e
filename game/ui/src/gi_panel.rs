//! The GI settings: their sliders ([`sliders`], also on the Settings screen) and the F1
//! panel around them, built from [`GiSettings::FIELDS`] so a new setting gets its slider
//! without touching this file.

use engine::egui;
use plugin_gi::{FieldInfo, GiSettings};

/// The panel's window title.
pub const TITLE: &str = "Global illumination";
/// The always-on hint in the top-left corner.
pub const HINT: &str = "F1: settings · Esc: release mouse";

/// Fields whose range spans orders of magnitude get a logarithmic slider.
const LOGARITHMIC: &[&str] = &["split_ratio"];

/// The panel's contents: an on/off checkbox, a slider per numeric field, a checkbox per
/// switch or a radio button per choice (hover text: the field's help) and a reset button. Returns whether anything changed.
pub fn sliders(ui: &mut egui::Ui, s: &mut GiSettings) -> bool {
    let before = s.clone();
    ui.checkbox(&mut s.enabled, "enabled").on_hover_text(GiSettings::ENABLED_HELP);
    for field in GiSettings::FIELDS {
        if field.is_switch() {
            let mut on = slider_value(s, field, None) == 1.0;
            if ui.checkbox(&mut on, field.name).on_hover_text(field.help).changed() {
                slider_value(s, field, Some(f64::from(u8::from(on))));
            }
            continue;
        }
        if !field.choices.is_empty() {
            let current = slider_value(s, field, None).round() as usize;
            ui.horizontal(|ui| {
                for (i, name) in field.choices.iter().enumerate() {
                    if ui.radio(current == i, *name).on_hover_text(field.help).clicked() {
                        slider_value(s, field, Some(i as f64));
                    }
                }
                ui.label(field.name);
            });
            continue;
        }
        let slider = egui::Slider::from_get_set(field.min..=field.max, |v| slider_value(s, field, v))
            .text(field.name)
            .logarithmic(LOGARITHMIC.contains(&field.name));
        let slider = if field.integer { slider.integer() } else { slider };
        ui.add(slider).on_hover_text(field.help);
    }
    if ui.button("Reset to defaults").clicked() {
        *s = GiSettings::default();
    }
    *s != before
}

/// A slider's access to a field: `None` reads it, `Some(v)` sets it first (clamped to the
/// field's range and rounded for whole-number fields, by [`GiSettings::set_number`]).
pub fn slider_value(s: &mut GiSettings, field: &FieldInfo, v: Option<f64>) -> f64 {
    if let Some(v) = v {
        s.set_number(field.name, v);
    }
    s.get(field.name).expect("every entry of GiSettings::FIELDS has a value")
}

/// The hint in the top-left corner; it takes no clicks, so clicking it still captures the mouse.
pub fn hint(ctx: &egui::Context) {
    egui::Area::new(egui::Id::unique("headlamp hint"))
        .fixed_pos(egui::pos2(8.0, 8.0))
        .order(egui::Order::Background)
        .interactable(false)
        .show(ctx, |ui| {
            egui::Frame::NONE
                .fill(egui::Color32::from_black_alpha(150))
                .corner_radius(4.0)
                .inner_margin(egui::Margin::symmetric(6, 3))
                .show(ui, |ui| ui.label(egui::RichText::new(HINT).color(egui::Color32::from_gray(220))));
        });
}

/// The panel as a window; `open` is cleared by its close button. Returns whether a setting changed.
pub fn window(ctx: &egui::Context, open: &mut bool, s: &mut GiSettings) -> bool {
    let mut changed = false;
    egui::Window::new(TITLE)
        .open(open)
        .default_pos(egui::pos2(8.0, 40.0))
        .resizable(false)
        .show(ctx, |ui| changed = sliders(ui, s));
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::egui_harness::{click, input, texts};

    /// Runs one pass of the panel inside a window, as `headlamp play` shows it.
    fn pass(ctx: &egui::Context, s: &mut GiSettings, events: Vec<egui::Event>) -> (bool, egui::FullOutput) {
        let mut changed = false;
        let mut open = true;
        let mut output = ctx.run_ui(input(events), |ui| changed = window(ui.ctx(), &mut open, s));
        output.textures_delta.clear(); // nothing paints here
        (changed, output)
    }

    #[test]
    fn builds_a_slider_per_field() {
        let ctx = egui::Context::default();
        let mut s = GiSettings::default();
        let mut output = None;
        // A window sizes itself over its first passes.
        for _ in 0..3 {
            let (changed, out) = pass(&ctx, &mut s, Vec::new());
            assert!(!changed, "showing the panel must not change anything");
            output = Some(out);
        }
        assert_eq!(s, GiSettings::default());
        let texts = texts(&output.unwrap());
        let shown: Vec<&str> = texts.iter().map(|(t, _)| t.as_str()).collect();
        for label in
            [TITLE, "enabled", "Reset to defaults"].into_iter().chain(GiSettings::FIELDS.iter().map(|f| f.name))
        {
            assert_eq!(shown.iter().filter(|&&t| t == label).count(), 1, "'{label}' once in {shown:?}");
        }
        // Each slider shows its value beside its name, e.g. merge_normal_deg's 25.
        assert!(shown.contains(&"25"), "merge_normal_deg's value in {shown:?}");
    }

    #[test]
    fn slider_values_are_clamped_and_rounded() {
        // Real-valued fields are f32: compare at f32 precision.
        let f32_eq = |a: f64, b: f64| (a as f32) == (b as f32);
        let mut s = GiSettings::default();
        for field in GiSettings::FIELDS {
            let high = slider_value(&mut s, field, Some(field.max * 10.0 + 1.0));
            assert!(f32_eq(high, field.max), "{} set above its range gave {high}", field.name);
            let low = slider_value(&mut s, field, Some(field.min - 1.0));
            assert!(f32_eq(low, field.min), "{} set below its range gave {low}", field.name);
            assert_eq!(slider_value(&mut s, field, None), low, "{} reads back", field.name);
            assert_eq!(s.get(field.name), Some(low));
        }
        let bounces = GiSettings::FIELDS.iter().find(|f| f.name == "bounces").unwrap();
        assert_eq!(slider_value(&mut s, bounces, Some(2.6)), 3.0);
    }

    #[test]
    fn reset_button_restores_the_defaults() {
        let ctx = egui::Context::default();
        let mut s = GiSettings { enabled: false, split_ratio: 0.1, bounces: 3, ..GiSettings::default() };
        let mut output = None;
        for _ in 0..3 {
            output = Some(pass(&ctx, &mut s, Vec::new()).1);
        }
        let (_, rect) = texts(&output.unwrap()).into_iter().find(|(t, _)| t == "Reset to defaults").unwrap();
        let [moved, pressed, released] = click(rect.center());
        pass(&ctx, &mut s, moved);
        pass(&ctx, &mut s, pressed);
        let (changed, _) = pass(&ctx, &mut s, released);
        assert!(changed, "clicking the button reports a change");
        assert_eq!(s, GiSettings::default());
    }
}
