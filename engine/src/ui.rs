//! In-game UI with egui, drawn over the finished frame.
//!
//! [`UiLayer`] is what the window loop uses: egui's context, its winit glue (events, cursor,
//! IME) and a [`UiPainter`]. The painter needs no window, so it can draw into any texture,
//! e.g. an offscreen one in a test. The engine stays game-agnostic: what the UI shows is the
//! app's business (`WindowApp::ui`).

use winit::event::{ElementState, WindowEvent};
use winit::window::Window;

use crate::gpu::Gpu;

/// Draws egui's output over a texture that already holds the rendered frame.
pub struct UiPainter {
    renderer: egui_wgpu::Renderer,
    /// Texture changes not yet uploaded (several passes may run between two paints).
    textures: egui::TexturesDelta,
    primitives: Vec<egui::ClippedPrimitive>,
    /// The scale the primitives were tessellated at; painting must use the same.
    pixels_per_point: f32,
}

impl UiPainter {
    /// A painter for targets of `target_format` (sRGB or not; egui-wgpu encodes accordingly).
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        Self {
            renderer: egui_wgpu::Renderer::new(device, target_format, egui_wgpu::RendererOptions::default()),
            textures: egui::TexturesDelta::default(),
            primitives: Vec::new(),
            pixels_per_point: 1.0,
        }
    }

    /// Takes one finished egui pass (`Context::run_ui`/`run_pass`): tessellates its shapes for
    /// the next [`Self::paint`] and queues its texture changes. Returns what the platform has to
    /// apply (cursor, clipboard, IME).
    pub fn prepare(&mut self, ctx: &egui::Context, output: egui::FullOutput) -> egui::PlatformOutput {
        self.textures.append(output.textures_delta);
        self.pixels_per_point = output.pixels_per_point;
        self.primitives = ctx.tessellate(output.shapes, output.pixels_per_point);
        output.platform_output
    }

    /// Whether the last prepared pass drew anything.
    pub fn is_empty(&self) -> bool {
        self.primitives.is_empty()
    }

    /// Draws the prepared UI over `target` (its contents are kept: `LoadOp::Load`) and submits
    /// the work. `size_in_pixels` is the target's size.
    pub fn paint(&mut self, gpu: &Gpu, target: &wgpu::TextureView, size_in_pixels: [u32; 2]) {
        for (id, deltas) in &self.textures.set {
            for delta in deltas {
                self.renderer.update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor { size_in_pixels, pixels_per_point: self.pixels_per_point };
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("ui") });
        let mut commands =
            self.renderer.update_buffers(&gpu.device, &gpu.queue, &mut encoder, &self.primitives, &screen);
        if !self.primitives.is_empty() {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("ui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            self.renderer.render(&mut pass.forget_lifetime(), &self.primitives, &screen);
        }
        commands.push(encoder.finish());
        gpu.queue.submit(commands);
        for id in &self.textures.free {
            self.renderer.free_texture(id);
        }
        self.textures.clear();
    }
}

impl Drop for UiPainter {
    fn drop(&mut self) {
        // Unpainted texture changes die with the renderer (egui asserts they were handled).
        self.textures.clear();
    }
}

/// egui over a window: feeds it the window's events, runs the app's UI code once a frame and
/// paints the result over the rendered frame.
///
/// While the mouse is captured for mouse look ([`Self::set_captured`]) the UI gets no pointer
/// or key presses (releases still arrive, so nothing stays held) and the cursor stays hidden.
pub struct UiLayer {
    ctx: egui::Context,
    state: egui_winit::State,
    painter: UiPainter,
    captured: bool,
    /// Where the pointer is (points), and whether it moved since egui last ran: egui judges a
    /// click by the pointer position of its last frame, which may be a long way off at a low
    /// frame rate.
    pointer: Option<egui::Pos2>,
    pointer_moved: bool,
}

impl UiLayer {
    pub fn new(gpu: &Gpu, window: &Window, surface_format: wgpu::TextureFormat) -> Self {
        let ctx = egui::Context::default();
        let state = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            window.theme(),
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        Self {
            ctx,
            state,
            painter: UiPainter::new(&gpu.device, surface_format),
            captured: false,
            pointer: None,
            pointer_moved: false,
        }
    }

    pub fn context(&self) -> &egui::Context {
        &self.ctx
    }

    /// The mouse is (or no longer is) captured for mouse look. Capturing makes the UI forget
    /// the pointer and any keyboard focus, so nothing reacts to the hidden cursor.
    pub fn set_captured(&mut self, captured: bool) {
        if captured && !self.captured {
            self.state.egui_input_mut().events.push(egui::Event::PointerGone);
            self.ctx.memory_mut(|m| m.stop_text_input());
        }
        self.captured = captured;
    }

    /// Feeds one window event to the UI. Returns true when the UI consumed it, i.e. the game
    /// should not act on it: a click or wheel over a UI window or during a UI drag, or a key
    /// pressed while a text field has the keyboard. (A focused slider does not take the
    /// keyboard away from the game, unlike egui's own default.)
    pub fn on_window_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        match event {
            WindowEvent::CursorMoved { position, .. } if !self.captured => {
                let ppp = egui_winit::pixels_per_point(&self.ctx, window);
                self.pointer = Some(egui::pos2(position.x as f32, position.y as f32) / ppp);
                self.pointer_moved = true;
            }
            WindowEvent::CursorLeft { .. } => self.pointer = None,
            _ => {}
        }
        match event {
            WindowEvent::CursorMoved { .. }
            | WindowEvent::CursorEntered { .. }
            | WindowEvent::MouseWheel { .. }
            | WindowEvent::Touch(_)
            | WindowEvent::PinchGesture { .. }
            | WindowEvent::Ime(_)
                if self.captured =>
            {
                false
            }
            WindowEvent::MouseInput { state: ElementState::Pressed, .. } if self.captured => false,
            WindowEvent::MouseInput { .. } if self.captured => {
                // A release (of the click that captured the mouse): let egui see it so the
                // button is not left down, then forget the pointer again.
                let _ = self.state.on_window_event(window, event);
                self.state.egui_input_mut().events.push(egui::Event::PointerGone);
                false
            }
            WindowEvent::MouseInput { state: ElementState::Pressed, .. } if self.pointer_moved => {
                // egui's answer is for where the pointer was last frame: ask it what lies
                // under the pointer now (a window or popup; the screen's background is not UI).
                let _ = self.state.on_window_event(window, event);
                let over_ui = self
                    .pointer
                    .and_then(|p| self.ctx.layer_id_at(p))
                    .is_some_and(|layer| layer.order != egui::Order::Background);
                over_ui || self.ctx.egui_is_using_pointer()
            }
            WindowEvent::KeyboardInput { event: key, .. } => {
                let pressed = key.state == ElementState::Pressed;
                if self.captured && pressed {
                    return false;
                }
                let typing = self.ctx.text_edit_focused();
                let _ = self.state.on_window_event(window, event);
                pressed && typing
            }
            _ => self.state.on_window_event(window, event).consumed,
        }
    }

    /// A key pressed and released for the UI alone (a gamepad moving through a menu, see
    /// [`crate::gamepad::menu_key`]); nothing while the mouse is captured for mouse look.
    pub fn tap_key(&mut self, key: egui::Key, modifiers: egui::Modifiers) {
        if self.captured {
            return;
        }
        let events = &mut self.state.egui_input_mut().events;
        for pressed in [true, false] {
            events.push(egui::Event::Key { key, physical_key: None, pressed, repeat: false, modifiers });
        }
    }

    /// Runs one UI pass (`run_ui` may be called more than once if egui asks for it) and
    /// prepares its output for [`Self::paint`].
    pub fn frame(&mut self, window: &Window, mut run_ui: impl FnMut(&egui::Context)) {
        let input = self.state.take_egui_input(window);
        self.pointer_moved = false;
        let output = self.ctx.run_pass(input, |ctx| run_ui(ctx));
        let mut platform = self.painter.prepare(&self.ctx, output);
        if self.captured {
            platform.cursor_icon = egui::CursorIcon::None;
        }
        self.state.handle_platform_output(window, platform);
    }

    /// Draws the last frame's UI over `target` (kept as rendered: `LoadOp::Load`).
    pub fn paint(&mut self, gpu: &Gpu, target: &wgpu::TextureView, size_in_pixels: [u32; 2]) {
        self.painter.paint(gpu, target, size_in_pixels);
    }
}
