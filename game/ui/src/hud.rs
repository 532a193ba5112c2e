//! The in-game HUD: crosshair, health, lamp battery, ammo, objective, hints and messages.
//! Everything sits on semi-transparent dark plates so it reads over a dark or a lamp-lit
//! scene, and nothing takes clicks (a click still reaches the game).

use engine::egui::{self, Align2, Color32, Pos2, Rect, RichText, Stroke, Vec2};

/// What the HUD shows this frame; the game fills it from its simulation.
#[derive(Clone, Debug, PartialEq)]
pub struct HudInfo {
    pub health: f32,
    pub max_health: f32,
    pub ammo_in_magazine: u32,
    pub magazine_size: u32,
    pub ammo_reserve: u32,
    pub reloading: bool,
    /// 0..=1.
    pub battery: f32,
    pub lamp_on: bool,
    pub lamp_attached: bool,
    pub enemies_left: u32,
    pub enemies_total: u32,
    pub objective: String,
    /// 0..=1: recent damage, shown as a red flash at the screen's edges.
    pub hurt: f32,
    /// What a key does here and now, e.g. "G — pick up the lamp".
    pub hint: Option<String>,
    /// Something that just happened, e.g. "Battery +50%".
    pub message: Option<String>,
    /// 0..=1: a shot just hit a crawler (a marker round the crosshair, fading).
    pub hit: f32,
    /// The crosshair's size (`Config::crosshair_scale`).
    pub crosshair_scale: f32,
}

impl Default for HudInfo {
    fn default() -> Self {
        Self {
            health: 100.0,
            max_health: 100.0,
            ammo_in_magazine: 12,
            magazine_size: 12,
            ammo_reserve: 48,
            reloading: false,
            battery: 1.0,
            lamp_on: true,
            lamp_attached: true,
            enemies_left: 0,
            enemies_total: 0,
            objective: String::new(),
            hurt: 0.0,
            hint: None,
            message: None,
            hit: 0.0,
            crosshair_scale: 1.0,
        }
    }
}

/// Below this battery charge the bar turns red and blinks.
pub const LOW_BATTERY: f32 = 0.2;

const MARGIN: f32 = 16.0;
const BAR_SIZE: Vec2 = egui::vec2(150.0, 12.0);
const CAPTION: Color32 = Color32::from_gray(170);
const TEXT: Color32 = Color32::from_gray(235);
const GREEN: Color32 = Color32::from_rgb(90, 200, 100);
const AMBER: Color32 = Color32::from_rgb(235, 180, 60);
const RED: Color32 = Color32::from_rgb(230, 60, 50);
const LAMP: Color32 = Color32::from_rgb(250, 225, 140);

pub fn show(ctx: &egui::Context, hud: &HudInfo) {
    let screen = ctx.content_rect();
    let painter = ctx.layer_painter(egui::LayerId::new(egui::Order::Background, egui::Id::unique("hud painter")));
    hurt_flash(&painter, screen, hud.hurt);
    crosshair(&painter, screen.center(), hud.crosshair_scale);
    hit_marker(&painter, screen.center(), hud.hit);
    area("hud vitals", Align2::LEFT_BOTTOM, egui::vec2(MARGIN, -MARGIN)).show(ctx, |ui| {
        plate().show(ui, |ui| {
            ui.horizontal_top(|ui| {
                health(ui, hud);
                ui.add_space(18.0);
                battery(ui, hud);
            })
        })
    });
    area("hud ammo", Align2::RIGHT_BOTTOM, egui::vec2(-MARGIN, -MARGIN))
        .show(ctx, |ui| plate().show(ui, |ui| ammo(ui, hud)));
    if !hud.objective.is_empty() || hud.enemies_total > 0 {
        area("hud objective", Align2::LEFT_TOP, egui::vec2(MARGIN, MARGIN))
            .show(ctx, |ui| plate().show(ui, |ui| objective(ui, hud)));
    }
    // The message sits above the hint, both centred above the bottom edge.
    if let Some(message) = &hud.message {
        area("hud message", Align2::CENTER_BOTTOM, egui::vec2(0.0, -130.0)).show(ctx, |ui| {
            plate().show(ui, |ui| ui.label(RichText::new(message).size(18.0).color(LAMP)));
        });
    }
    if let Some(hint) = &hud.hint {
        area("hud hint", Align2::CENTER_BOTTOM, egui::vec2(0.0, -90.0)).show(ctx, |ui| {
            plate().show(ui, |ui| ui.label(RichText::new(hint).size(16.0).color(TEXT)));
        });
    }
}

fn area(id: &str, anchor: Align2, offset: Vec2) -> egui::Area {
    egui::Area::new(egui::Id::unique(id)).order(egui::Order::Background).anchor(anchor, offset).interactable(false)
}

/// The dark, semi-transparent backplate under every HUD element.
fn plate() -> egui::Frame {
    egui::Frame::NONE
        .fill(Color32::from_black_alpha(150))
        .corner_radius(6.0)
        .inner_margin(egui::Margin::symmetric(10, 6))
}

fn caption(ui: &mut egui::Ui, text: &str, color: Color32) {
    ui.label(RichText::new(text).size(11.0).strong().color(color));
}

fn health(ui: &mut egui::Ui, hud: &HudInfo) {
    let fraction = if hud.max_health > 0.0 { hud.health / hud.max_health } else { 0.0 };
    let color = match fraction {
        f if f > 0.5 => GREEN,
        f if f > 0.25 => AMBER,
        _ => RED,
    };
    ui.vertical(|ui| {
        caption(ui, "HEALTH", CAPTION);
        ui.horizontal(|ui| {
            bar(ui, fraction, color);
            // Rounded up: any health left shows as at least 1.
            let shown = hud.health.max(0.0).ceil() as u32;
            ui.label(RichText::new(shown.to_string()).monospace().size(20.0).color(TEXT));
        });
    });
}

fn battery(ui: &mut egui::Ui, hud: &HudInfo) {
    let charge = hud.battery.clamp(0.0, 1.0);
    let low = charge < LOW_BATTERY;
    // Blinks at 2 Hz while low; the game redraws every frame, so no repaint request is needed.
    let blink_off = low && (ui.input(|i| i.time) * 2.0).fract() > 0.6;
    let color = match (low, blink_off) {
        (true, true) => RED.gamma_multiply(0.35),
        (true, false) => RED,
        _ => LAMP,
    };
    ui.vertical(|ui| {
        caption(ui, if low { "LAMP · LOW BATTERY" } else { "LAMP" }, if low { RED } else { CAPTION });
        ui.horizontal(|ui| {
            bar(ui, charge, color);
            let percent = format!("{:.0}%", charge * 100.0);
            ui.label(RichText::new(percent).monospace().size(20.0).color(if low { RED } else { TEXT }));
        });
        let state = match (hud.lamp_attached, hud.lamp_on) {
            (true, true) => None,
            (true, false) => Some("lamp off"),
            (false, true) => Some("lamp set down"),
            (false, false) => Some("lamp set down · off"),
        };
        if let Some(state) = state {
            ui.label(RichText::new(state).size(13.0).color(CAPTION));
        }
    });
}

fn ammo(ui: &mut egui::Ui, hud: &HudInfo) {
    // Left-aligned: a right-aligned layout would stretch the area to the screen's width.
    ui.vertical(|ui| {
        caption(ui, "AMMO", CAPTION);
        let empty = hud.ammo_in_magazine == 0;
        let text = format!("{} / {}", hud.ammo_in_magazine, hud.ammo_reserve);
        // Never wrapped: in its narrow corner area egui broke the count onto two lines.
        let count = RichText::new(text).monospace().size(26.0).color(if empty { RED } else { TEXT });
        ui.add(egui::Label::new(count).extend());
        if hud.reloading {
            ui.label(RichText::new("Reloading…").size(14.0).color(AMBER));
        }
    });
}

fn objective(ui: &mut egui::Ui, hud: &HudInfo) {
    if !hud.objective.is_empty() {
        ui.label(RichText::new(&hud.objective).size(16.0).color(TEXT));
    }
    if hud.enemies_total > 0 {
        let text = format!("Enemies left: {} / {}", hud.enemies_left, hud.enemies_total);
        ui.label(RichText::new(text).size(14.0).color(CAPTION));
    }
}

/// A bar filled to `fraction` (clamped to 0..=1) over a faint track.
fn bar(ui: &mut egui::Ui, fraction: f32, color: Color32) {
    let (rect, _) = ui.allocate_exact_size(BAR_SIZE, egui::Sense::hover());
    let painter = ui.painter();
    painter.rect_filled(rect, 3.0, Color32::from_white_alpha(25));
    let filled = Rect::from_min_size(rect.min, egui::vec2(rect.width() * fraction.clamp(0.0, 1.0), rect.height()));
    painter.rect_filled(filled, 3.0, color);
    painter.rect_stroke(rect, 3.0, Stroke::new(1.0, Color32::from_white_alpha(60)), egui::StrokeKind::Inside);
}

/// A small cross with a gap, white over a dark outline so it shows on bright and dark walls.
fn crosshair(painter: &egui::Painter, centre: Pos2, scale: f32) {
    let (gap, length) = (4.0 * scale, 7.0 * scale);
    let arms = [egui::vec2(1.0, 0.0), egui::vec2(-1.0, 0.0), egui::vec2(0.0, 1.0), egui::vec2(0.0, -1.0)];
    for (width, color) in [(3.5, Color32::from_black_alpha(170)), (1.5, Color32::from_white_alpha(230))] {
        for dir in arms {
            painter.line_segment(
                [centre + dir * gap, centre + dir * (gap + length)],
                Stroke::new(width * scale.max(1.0), color),
            );
        }
    }
}

/// Four short diagonals round the crosshair: the shot landed.
fn hit_marker(painter: &egui::Painter, centre: Pos2, hit: f32) {
    let hit = hit.clamp(0.0, 1.0);
    if hit <= 0.0 {
        return;
    }
    let color = Color32::from_rgba_unmultiplied(255, 235, 200, (hit * 255.0) as u8);
    for (dx, dy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        let dir = egui::vec2(dx, dy) * std::f32::consts::FRAC_1_SQRT_2;
        painter.line_segment([centre + dir * 9.0, centre + dir * 17.0], Stroke::new(2.0, color));
    }
}

/// Red at the screen's edges fading to nothing a fifth of the way in, as strong as `hurt`.
fn hurt_flash(painter: &egui::Painter, screen: Rect, hurt: f32) {
    let hurt = hurt.clamp(0.0, 1.0);
    if hurt <= 0.0 {
        return;
    }
    let edge = Color32::from_rgba_unmultiplied(210, 10, 10, (hurt * 170.0) as u8);
    let inner = screen.shrink(screen.size().min_elem() * 0.2);
    let mut mesh = egui::Mesh::default();
    for corner in [screen.left_top(), screen.right_top(), screen.right_bottom(), screen.left_bottom()] {
        mesh.colored_vertex(corner, edge);
    }
    for corner in [inner.left_top(), inner.right_top(), inner.right_bottom(), inner.left_bottom()] {
        mesh.colored_vertex(corner, Color32::TRANSPARENT);
    }
    // One band per side: outer edge i..j to inner edge i+4..j+4.
    for i in 0..4 {
        let j = (i + 1) % 4;
        mesh.add_triangle(i, j, j + 4);
        mesh.add_triangle(i, j + 4, i + 4);
    }
    painter.add(egui::Shape::mesh(mesh));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::egui_harness::{input, texts, SCREEN};

    fn shown(hud: &HudInfo) -> (Vec<String>, egui::FullOutput) {
        let ctx = egui::Context::default();
        let mut output = None;
        // Areas size themselves over their first passes.
        for _ in 0..3 {
            output = Some(ctx.run_ui(input(Vec::new()), |ui| show(ui.ctx(), hud)));
        }
        let output = output.unwrap();
        (texts(&output).into_iter().map(|(t, _)| t).collect(), output)
    }

    #[test]
    fn the_crosshair_grows_with_its_scale() {
        // How far the crosshair's lines reach from the screen's centre.
        let reach = |scale: f32| {
            let (_, output) = shown(&HudInfo { crosshair_scale: scale, ..HudInfo::default() });
            let centre = egui::pos2(SCREEN.x / 2.0, SCREEN.y / 2.0);
            output
                .shapes
                .iter()
                .filter_map(|c| match &c.shape {
                    egui::Shape::LineSegment { points, .. } => {
                        Some(points.iter().map(|p| p.distance(centre)).fold(0.0, f32::max))
                    }
                    _ => None,
                })
                .filter(|d| *d < 100.0)
                .fold(0.0, f32::max)
        };
        assert!((reach(1.0) - 11.0).abs() < 0.5, "{}", reach(1.0));
        assert!((reach(2.5) - 27.5).abs() < 0.5, "{}", reach(2.5));
    }

    #[test]
    fn shows_ammo_health_battery_and_objective() {
        let hud = HudInfo {
            health: 74.2,
            ammo_in_magazine: 7,
            ammo_reserve: 36,
            reloading: true,
            battery: 0.62,
            enemies_left: 2,
            enemies_total: 3,
            objective: "Clear the cellar — or reach the exit".into(),
            hint: Some("G — pick up the lamp".into()),
            message: Some("Battery +50%".into()),
            ..HudInfo::default()
        };
        let (texts, output) = shown(&hud);
        for expected in [
            "7 / 36",
            "Reloading…",
            "75",
            "62%",
            "Clear the cellar — or reach the exit",
            "Enemies left: 2 / 3",
            "G — pick up the lamp",
            "Battery +50%",
        ] {
            assert!(texts.iter().any(|t| t == expected), "'{expected}' in {texts:?}");
        }
        assert!(!texts.iter().any(|t| t.starts_with("lamp ")), "the lamp is on and carried: {texts:?}");
        // Where things are: ammo bottom-right, objective top-left.
        let all = crate::egui_harness::texts(&output);
        let at = |t: &str| crate::egui_harness::find(&all, t).unwrap().center();
        assert!(at("7 / 36").x > SCREEN.x * 0.75 && at("7 / 36").y > SCREEN.y * 0.75);
        assert!(at("Enemies left: 2 / 3").x < SCREEN.x * 0.25 && at("Enemies left: 2 / 3").y < SCREEN.y * 0.25);
        assert!(at("75").x < SCREEN.x * 0.5 && at("75").y > SCREEN.y * 0.75);
    }

    #[test]
    fn lamp_state_and_low_battery_are_spelled_out() {
        let (texts, _) = shown(&HudInfo { battery: 0.1, lamp_on: false, ..HudInfo::default() });
        assert!(texts.iter().any(|t| t == "lamp off"), "{texts:?}");
        assert!(texts.iter().any(|t| t == "LAMP · LOW BATTERY"), "{texts:?}");
        let (texts, _) = shown(&HudInfo { lamp_attached: false, ..HudInfo::default() });
        assert!(texts.iter().any(|t| t == "lamp set down"), "{texts:?}");
        let (texts, _) = shown(&HudInfo::default());
        assert!(!texts.iter().any(|t| t.contains("Reloading") || t.contains("Enemies")), "{texts:?}");
    }

    #[test]
    fn takes_no_clicks() {
        let ctx = egui::Context::default();
        let hud = HudInfo { hint: Some("hint".into()), objective: "goal".into(), ..HudInfo::default() };
        for _ in 0..3 {
            let _ =
                ctx.run_ui(input(vec![egui::Event::PointerMoved(egui::pos2(30.0, 580.0))]), |ui| show(ui.ctx(), &hud));
        }
        assert!(!ctx.egui_wants_pointer_input(), "the pointer over the health plate is the game's");
    }

    #[test]
    fn hurt_paints_a_red_edge() {
        let count_meshes = |hurt| {
            let (_, output) = shown(&HudInfo { hurt, ..HudInfo::default() });
            output.shapes.iter().filter(|c| matches!(&c.shape, egui::Shape::Mesh(m) if m.vertices.len() == 8)).count()
        };
        assert_eq!(count_meshes(0.0), 0);
        assert_eq!(count_meshes(0.8), 1);
    }
}
