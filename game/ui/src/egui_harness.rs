//! Drives egui without a window, for tests of the screens here and of the game around them:
//! build the input of one pass, run it with `Context::run_ui`, find texts in what it drew,
//! and click on them.

use engine::egui;

/// The screen every pass gets, in points.
pub const SCREEN: egui::Vec2 = egui::vec2(800.0, 600.0);

/// One pass's input: the screen and `events`.
pub fn input(events: Vec<egui::Event>) -> egui::RawInput {
    egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, SCREEN)),
        events,
        ..Default::default()
    }
}

/// Every text drawn in a pass, with the rectangle it covers.
pub fn texts(output: &egui::FullOutput) -> Vec<(String, egui::Rect)> {
    fn walk(shape: &egui::Shape, out: &mut Vec<(String, egui::Rect)>) {
        match shape {
            egui::Shape::Text(t) => out.push((t.galley.text().to_owned(), t.visual_bounding_rect())),
            egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| walk(s, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for clipped in &output.shapes {
        walk(&clipped.shape, &mut out);
    }
    out
}

/// Where the text `wanted` was drawn (the first, if several).
pub fn find(texts: &[(String, egui::Rect)], wanted: &str) -> Option<egui::Rect> {
    texts.iter().find(|(t, _)| t == wanted).map(|(_, r)| *r)
}

/// A press and release of the primary button at `at`, as three passes see them.
pub fn click(at: egui::Pos2) -> [Vec<egui::Event>; 3] {
    click_with(egui::PointerButton::Primary, at)
}

/// A press and release of `button` at `at`, as three passes see them.
pub fn click_with(button: egui::PointerButton, at: egui::Pos2) -> [Vec<egui::Event>; 3] {
    let event = |pressed| egui::Event::PointerButton { pos: at, button, pressed, modifiers: egui::Modifiers::NONE };
    [vec![egui::Event::PointerMoved(at)], vec![event(true)], vec![event(false)]]
}

/// A key going down, as egui-winit reports it (logical and physical key alike).
pub fn key_down(key: egui::Key) -> egui::Event {
    egui::Event::Key { key, physical_key: Some(key), pressed: true, repeat: false, modifiers: egui::Modifiers::NONE }
}
