//! The UI painter draws egui's output over an already rendered frame (no window needed).

use engine::egui;
use engine::gpu::Gpu;
use engine::headless::{read_texture, HeadlessTarget, ImageKind};
use engine::ui::UiPainter;

const SIZE: [u32; 2] = [480, 240];
/// A high-DPI scale, so points and pixels differ and a mix-up shows.
const PIXELS_PER_POINT: f32 = 2.0;
const BLUE: [u8; 4] = [0, 0, 255, 255];
const RED: [u8; 4] = [255, 0, 0, 255];

fn pixel(bytes: &[u8], x: u32, y: u32) -> [u8; 4] {
    let i = ((y * SIZE[0] + x) * 4) as usize;
    bytes[i..i + 4].try_into().unwrap()
}

/// Fills the target with blue, standing in for the 3D frame.
fn clear_to_blue(gpu: &Gpu, view: &engine::wgpu::TextureView) {
    use engine::wgpu;
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("clear") });
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("clear"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::BLUE), store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    gpu.queue.submit([encoder.finish()]);
}

#[test]
fn paints_ui_over_the_frame() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let target = HeadlessTarget::new(&gpu, SIZE[0], SIZE[1], ImageKind::Display);
    clear_to_blue(&gpu, &target.view);

    let ctx = egui::Context::default();
    ctx.all_styles_mut(|s| s.animation_time = 0.0); // no fade-in: the window shows at once
    let mut painter = UiPainter::new(&gpu.device, target.texture.format());
    // A window is laid out invisibly in its first pass: prepare a few passes, paint once
    // (texture changes accumulate in between).
    for _ in 0..3 {
        let mut input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(SIZE[0] as f32, SIZE[1] as f32) / PIXELS_PER_POINT,
            )),
            ..Default::default()
        };
        input.viewports.entry(egui::ViewportId::ROOT).or_default().native_pixels_per_point = Some(PIXELS_PER_POINT);
        // A red rectangle from (10, 10) to (40, 30) points, i.e. (20, 20) to (80, 60) pixels,
        // and a window below it from (10, 50) points.
        let output = ctx.run_ui(input, |ui| {
            ui.painter().rect_filled(
                egui::Rect::from_min_max(egui::pos2(10.0, 10.0), egui::pos2(40.0, 30.0)),
                0.0,
                egui::Color32::RED,
            );
            // (Without its shadow, which would reach over the rectangle.)
            let frame = egui::Frame::window(ui.style()).shadow(egui::Shadow::NONE);
            egui::Window::new("w").frame(frame).fixed_pos(egui::pos2(10.0, 50.0)).show(ui.ctx(), |ui| ui.label("UI"));
        });
        assert_eq!(output.pixels_per_point, PIXELS_PER_POINT);
        painter.prepare(&ctx, output);
    }
    assert!(!painter.is_empty());
    painter.paint(&gpu, &target.view, SIZE);
    let bytes = read_texture(&gpu, &target.texture);

    // Inside the rectangle (1 px in from its anti-aliased edges): red.
    for y in 21..59 {
        for x in 21..79 {
            assert_eq!(pixel(&bytes, x, y), RED, "pixel ({x}, {y}) inside the rectangle");
        }
    }
    // Around the rectangle and beside the window: the frame as it was.
    for (x, y) in [(10, 40), (50, 70), (300, 50), (470, 10), (10, 200)] {
        assert_eq!(pixel(&bytes, x, y), BLUE, "pixel ({x}, {y}) outside the UI");
    }
    // The window (from (20, 100) pixels, as wide as the screen allows) covers the blue.
    let (xs, ys) = (30..450, 110..210);
    let area = xs.len() * ys.len();
    let covered =
        ys.flat_map(|y| xs.clone().map(move |x| (x, y))).filter(|&(x, y)| pixel(&bytes, x, y) != BLUE).count();
    assert_eq!(covered, area, "the window left blue pixels");
}
