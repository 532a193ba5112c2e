//! The F3 performance overlay (a compact monospace table in the top-right corner) and the
//! smoothed frame-rate counter that feeds it.

use engine::egui::{self, Color32, RichText};

/// What the overlay shows this frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OverlayInfo {
    pub fps: f32,
    pub frame_ms: f32,
    /// Each render-graph pass and its GPU time, in execution order (`Renderer::last_pass_times`);
    /// empty when timing is off or unsupported.
    pub pass_times_ms: Vec<(String, f64)>,
    /// The reflection lights that lit an 8×8 tile of the indirect target last frame, on average,
    /// or with the article's method (`light_volumes`) the light volumes drawn.
    pub reflection_lights: u32,
    pub light_volumes: bool,
    /// Simulation ticks run this frame.
    pub ticks: u32,
    /// The 3D view's resolution relative to the window now.
    pub render_scale: f32,
    /// The frame rate dynamic resolution holds, when it is on.
    pub target_fps: Option<f32>,
}

/// Below the corner's first line, which `headlamp record`/`replay` use for their status.
const OFFSET: egui::Vec2 = egui::vec2(-8.0, 40.0);

pub fn show(ctx: &egui::Context, info: &OverlayInfo) {
    egui::Area::new(egui::Id::unique("performance overlay"))
        .order(egui::Order::Foreground)
        .anchor(egui::Align2::RIGHT_TOP, OFFSET)
        .interactable(false)
        .show(ctx, |ui| {
            egui::Frame::NONE
                .fill(Color32::from_black_alpha(170))
                .corner_radius(4.0)
                .inner_margin(egui::Margin::symmetric(8, 6))
                .show(ui, |ui| {
                    ui.label(RichText::new(table(info)).monospace().size(12.0).color(Color32::from_gray(225)))
                });
        });
}

/// The overlay's text: a name column and a right-aligned number column.
pub fn table(info: &OverlayInfo) -> String {
    let row = |name: &str, value: String| format!("{name:<13}{value:>13}\n");
    let mut out = row("fps", format!("{:.1}", info.fps));
    out += &row("frame ms", format!("{:.2}", info.frame_ms));
    out += &row("render scale", format!("{:.0} %", info.render_scale * 100.0));
    if let Some(fps) = info.target_fps {
        out += &row(" dynamic", format!("{fps:.0} fps"));
    }
    if info.pass_times_ms.is_empty() {
        out += &row("GPU ms", "off".into());
    } else {
        out += &row("GPU ms", String::new());
        for (pass, ms) in &info.pass_times_ms {
            out += &row(&format!(" {pass}"), format!("{ms:.3}"));
        }
        let total: f64 = info.pass_times_ms.iter().map(|(_, ms)| ms).sum();
        out += &row(" total", format!("{total:.3}"));
    }
    let unit = if info.light_volumes { " volumes" } else { "/tile" };
    out += &row("GI lights", format!("{}{unit}", info.reflection_lights));
    out += &row("ticks", info.ticks.to_string());
    out.pop(); // the last newline
    out
}

/// Frames per second and frame time, smoothed over about half a second so the numbers can
/// be read, yet follow a change within a second or two. Feed it every frame's `dt`.
#[derive(Clone, Debug, Default)]
pub struct FrameRate {
    /// Frames and seconds counted with exponential forgetting (time constant
    /// [`Self::SMOOTHING_S`]): their ratio is the frame rate over the recent past, so uneven
    /// frames average as frames per second, not as a mean of frame times weighted by length.
    frames: f32,
    seconds: f32,
}

impl FrameRate {
    /// The averaging time constant, seconds.
    pub const SMOOTHING_S: f32 = 0.5;

    pub fn new() -> Self {
        Self::default()
    }

    /// One frame of `dt` seconds.
    pub fn push(&mut self, dt: f32) {
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        let keep = (-dt / Self::SMOOTHING_S).exp();
        self.frames = self.frames * keep + 1.0;
        self.seconds = self.seconds * keep + dt;
    }

    /// 0 before the first frame.
    pub fn fps(&self) -> f32 {
        if self.seconds > 0.0 {
            self.frames / self.seconds
        } else {
            0.0
        }
    }

    /// The mean frame time, milliseconds; 0 before the first frame.
    pub fn frame_ms(&self) -> f32 {
        if self.frames > 0.0 {
            1000.0 * self.seconds / self.frames
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::egui_harness::{input, texts, SCREEN};

    #[test]
    fn frame_rate_settles_and_follows() {
        let mut rate = FrameRate::new();
        assert_eq!(rate.fps(), 0.0);
        rate.push(0.0);
        rate.push(f32::NAN);
        assert_eq!(rate.fps(), 0.0, "nonsense frame times are ignored");
        for _ in 0..120 {
            rate.push(1.0 / 60.0);
        }
        assert!((rate.fps() - 60.0).abs() < 0.01, "{}", rate.fps());
        assert!((rate.frame_ms() - 16.667).abs() < 0.01, "{}", rate.frame_ms());
        // Uneven frames average out.
        for i in 0..60 {
            rate.push(if i % 2 == 0 { 0.010 } else { 0.030 });
        }
        assert!((rate.frame_ms() - 20.0).abs() < 1.5, "{}", rate.frame_ms());
        // Two seconds at 30 fps: the counter says so.
        for _ in 0..60 {
            rate.push(1.0 / 30.0);
        }
        assert!((rate.fps() - 30.0).abs() < 1.0, "{}", rate.fps());
    }

    #[test]
    fn table_lists_every_pass_and_the_total() {
        let info = OverlayInfo {
            fps: 59.94,
            frame_ms: 16.68,
            pass_times_ms: vec![("gbuffer".into(), 1.25), ("gi_shade".into(), 3.5)],
            reflection_lights: 1234,
            light_volumes: false,
            ticks: 1,
            render_scale: 0.33,
            target_fps: Some(20.0),
        };
        let text = table(&info);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "fps                   59.9");
        assert_eq!(lines[1], "frame ms             16.68");
        assert!(lines.contains(&" gbuffer             1.250"), "{text}");
        assert!(lines.contains(&" gi_shade            3.500"), "{text}");
        assert!(lines.contains(&" total               4.750"), "{text}");
        assert!(lines.contains(&"GI lights        1234/tile"), "{text}");
        // The article's method counts the light volumes it drew.
        let volumes = table(&OverlayInfo { reflection_lights: 2345, light_volumes: true, ..info.clone() });
        assert!(volumes.lines().any(|l| l == "GI lights     2345 volumes"), "{volumes}");
        assert!(lines.contains(&"render scale          33 %"), "{text}");
        assert!(lines.contains(&" dynamic            20 fps"), "{text}");
        assert!(lines.iter().all(|l| l.chars().count() == lines[0].chars().count()), "aligned:\n{text}");
        assert!(table(&OverlayInfo::default()).contains("GPU ms                 off"));

        let ctx = egui::Context::default();
        let mut output = None;
        for _ in 0..3 {
            output = Some(ctx.run_ui(input(Vec::new()), |ui| show(ui.ctx(), &info)));
        }
        let shown = texts(&output.unwrap());
        let (_, rect) = shown.iter().find(|(t, _)| *t == text).expect("the table is drawn");
        assert!(rect.right() > SCREEN.x - 30.0 && rect.top() < 80.0, "top-right: {rect:?}");
    }
}
