//! The window loop (winit `ApplicationHandler`): owns the surface, the GPU and the UI layer,
//! turns events into [`Input`], and asks the app for a frame. Resizes, minimising to 0×0 and
//! lost or outdated surfaces are handled here so no app has to.
//!
//! The mouse: by default a click captures it (mouse look), Esc or losing focus releases it; an
//! app can take over with [`WindowApp::capture_wanted`]. While it is released, events go to
//! the UI first; a click or key the UI consumed (a click on a UI window, typing into a text
//! field) neither captures the mouse nor reaches [`Input`] — except Esc, which always reaches
//! it (apps open and close their menus with it).

use std::sync::Arc;
use std::time::Instant;

use anyhow::Context;
use winit::application::ApplicationHandler;
use winit::event::{DeviceEvent, DeviceId, ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{CursorGrabMode, Window, WindowId};

use crate::gamepad::Gamepads;
use crate::gpu::Gpu;
use crate::input::{Input, MouseButton};
use crate::ui::UiLayer;

/// What a windowed program provides.
pub trait WindowApp {
    /// The window and GPU exist; `format` is the surface's.
    fn init(&mut self, gpu: &Gpu, format: wgpu::TextureFormat) -> anyhow::Result<()>;
    /// Advances the program by `dt` seconds of wall time.
    fn update(&mut self, input: &Input, dt: f32);
    /// Polled after every `update`: true releases a captured mouse once (e.g. a menu was just
    /// opened and should be usable at once).
    fn release_mouse_requested(&mut self) -> bool {
        false
    }
    /// Polled each frame after `update`: Some(true) grabs the mouse (raw look), Some(false)
    /// frees it and a click no longer grabs it, None keeps today's behaviour (a click grabs,
    /// Esc frees). Losing focus always frees it; Some(true) grabs again once focus is back.
    fn capture_wanted(&self) -> Option<bool> {
        None
    }
    /// Polled each frame: whether presentation waits for vertical blank (AutoVsync vs
    /// AutoNoVsync, which falls back from Immediate to Mailbox to Fifo); a change reconfigures
    /// the surface.
    fn vsync(&self) -> bool {
        true
    }
    /// Builds this frame's UI with egui (after `update`, before `render`); the loop paints it
    /// over what `render` drew. The default shows nothing.
    fn ui(&mut self, _ctx: &egui::Context) {}
    /// Draws into the surface texture.
    fn render(&mut self, gpu: &Gpu, target: &wgpu::Texture, view: &wgpu::TextureView) -> anyhow::Result<()>;
    /// Every raw window event, before the engine's and the UI's own handling.
    fn window_event(&mut self, _window: &Window, _event: &WindowEvent) {}
    fn wants_exit(&self) -> bool {
        false
    }
}

/// Opens a window and runs `app` until it closes; returns the first error the app reported.
/// The app is borrowed, so what it holds (a recording, say) outlives the window either way.
pub fn run<A: WindowApp>(title: &str, app: &mut A) -> anyhow::Result<()> {
    let event_loop = EventLoop::new().context("could not open a window (is a display available?)")?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut runner = Runner {
        app,
        title: title.to_owned(),
        state: None,
        input: Input::default(),
        last: Instant::now(),
        error: None,
        capture: None,
        focused: true,
        pads: Gamepads::start(),
    };
    event_loop.run_app(&mut runner).context("window event loop failed")?;
    match runner.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct WindowState {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    gpu: Gpu,
    ui: UiLayer,
    /// What `config.present_mode` was chosen for.
    vsync: bool,
    /// The format the UI is drawn in: the surface's without sRGB encoding where the adapter can
    /// view the surface that way (egui blends in gamma space), else the surface's own.
    ui_format: wgpu::TextureFormat,
}

struct Runner<'a, A: WindowApp> {
    app: &'a mut A,
    title: String,
    state: Option<WindowState>,
    input: Input,
    last: Instant,
    error: Option<anyhow::Error>,
    /// The app's last [`WindowApp::capture_wanted`].
    capture: Option<bool>,
    focused: bool,
    pads: Gamepads,
}

impl<A: WindowApp> Runner<'_, A> {
    fn create(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let attrs = Window::default_attributes()
            .with_title(&self.title)
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 720.0));
        let window = Arc::new(event_loop.create_window(attrs).context("could not create the window")?);
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let surface =
            instance.create_surface(window.clone()).context("could not create a drawing surface for the window")?;
        let gpu = Gpu::for_surface(instance, &surface)?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.adapter, size.width.max(1), size.height.max(1))
            .context("the GPU cannot present to this window")?;
        // Prefer an sRGB format so the present pass's output is encoded by the hardware.
        let caps = surface.get_capabilities(&gpu.adapter);
        if let Some(&srgb) = caps.formats.iter().find(|f| f.is_srgb()) {
            config.format = srgb;
        }
        let vsync = self.app.vsync();
        config.present_mode = present_mode(vsync);
        let mut ui_format = config.format;
        let surface_views = gpu.adapter.get_downlevel_capabilities().flags;
        if config.format.is_srgb() && surface_views.contains(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS) {
            ui_format = config.format.remove_srgb_suffix();
            config.view_formats.push(ui_format);
        }
        surface.configure(&gpu.device, &config);
        self.app.init(&gpu, config.format)?;
        let ui = UiLayer::new(&gpu, &window, ui_format);
        self.state = Some(WindowState { window, surface, config, gpu, ui, vsync, ui_format });
        Ok(())
    }

    fn set_captured(&mut self, captured: bool) {
        let Some(state) = &mut self.state else { return };
        log::debug!("mouse {}", if captured { "captured" } else { "released" });
        state.ui.set_captured(captured);
        if captured {
            let grabbed = state
                .window
                .set_cursor_grab(CursorGrabMode::Locked)
                .or_else(|_| state.window.set_cursor_grab(CursorGrabMode::Confined));
            if grabbed.is_err() {
                log::warn!("could not grab the mouse cursor");
            }
        } else {
            let _ = state.window.set_cursor_grab(CursorGrabMode::None);
        }
        state.window.set_cursor_visible(!captured);
        self.input.captured = captured;
    }

    fn frame(&mut self) -> anyhow::Result<()> {
        let now = Instant::now();
        let dt = (now - self.last).as_secs_f32().min(0.25);
        self.last = now;
        self.poll_pads();
        self.app.update(&self.input, dt);
        if self.app.release_mouse_requested() && self.input.captured {
            self.set_captured(false);
        }
        self.capture = self.app.capture_wanted();
        if let Some(captured) = capture_change(self.capture, self.focused, self.input.captured) {
            self.set_captured(captured);
        }
        self.input.end_frame();

        let vsync = self.app.vsync();
        let Some(state) = &mut self.state else { return Ok(()) };
        if vsync != state.vsync {
            state.vsync = vsync;
            state.config.present_mode = present_mode(vsync);
            if state.config.width > 0 && state.config.height > 0 {
                state.surface.configure(&state.gpu.device, &state.config);
            }
        }
        if state.config.width == 0 || state.config.height == 0 {
            return Ok(()); // minimised: nothing to draw into
        }
        let (texture, suboptimal) = match state.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => (t, false),
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => (t, true),
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(()),
            wgpu::CurrentSurfaceTexture::Outdated => {
                state.surface.configure(&state.gpu.device, &state.config);
                return Ok(());
            }
            wgpu::CurrentSurfaceTexture::Lost => {
                state.surface = state
                    .gpu
                    .instance
                    .create_surface(state.window.clone())
                    .context("could not recreate the lost surface")?;
                state.surface.configure(&state.gpu.device, &state.config);
                return Ok(());
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                log::warn!("surface texture validation error; skipping a frame");
                return Ok(());
            }
        };
        let view = texture.texture.create_view(&wgpu::TextureViewDescriptor::default());
        state.ui.frame(&state.window, |ctx| self.app.ui(ctx));
        self.app.render(&state.gpu, &texture.texture, &view)?;
        let ui_view = texture
            .texture
            .create_view(&wgpu::TextureViewDescriptor { format: Some(state.ui_format), ..Default::default() });
        state.ui.paint(&state.gpu, &ui_view, [texture.texture.width(), texture.texture.height()]);
        state.window.pre_present_notify();
        state.gpu.queue.present(texture);
        if suboptimal {
            state.surface.configure(&state.gpu.device, &state.config);
        }
        // A GPU error is wgpu's panic by default; here it ends the loop as the app's errors do.
        if let Some(e) = state.gpu.take_uncaptured() {
            anyhow::bail!("the GPU failed drawing a frame: {e}");
        }
        Ok(())
    }

    /// Gamepad events since the last frame into [`Input::pad`]; while the UI has the screen
    /// (mouse not captured) the buttons that move through menus also reach it as keys.
    fn poll_pads(&mut self) {
        for event in self.pads.poll() {
            let before = self.input.pad.pressed_buttons().len();
            self.input.pad.apply(event);
            let Some(state) = &mut self.state else { continue };
            for &button in &self.input.pad.pressed_buttons()[before..] {
                if let Some((key, modifiers)) = crate::gamepad::menu_key(button) {
                    state.ui.tap_key(key, modifiers);
                }
            }
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }
}

/// The capture an app's [`WindowApp::capture_wanted`] asks for, when it differs from the
/// current one. A window without focus never holds the mouse.
fn capture_change(wanted: Option<bool>, focused: bool, captured: bool) -> Option<bool> {
    let target = wanted? && focused;
    (target != captured).then_some(target)
}

fn present_mode(vsync: bool) -> wgpu::PresentMode {
    if vsync {
        wgpu::PresentMode::AutoVsync
    } else {
        wgpu::PresentMode::AutoNoVsync
    }
}

impl<A: WindowApp> ApplicationHandler for Runner<'_, A> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_none() {
            if let Err(e) = self.create(event_loop) {
                self.fail(event_loop, e);
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let mut ui_consumed = false;
        if let Some(state) = &mut self.state {
            self.app.window_event(&state.window, &event);
            ui_consumed = state.ui.on_window_event(&state.window, &event);
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(state) = &mut self.state {
                    state.config.width = size.width;
                    state.config.height = size.height;
                    if size.width > 0 && size.height > 0 {
                        state.surface.configure(&state.gpu.device, &state.config);
                    }
                }
            }
            WindowEvent::Focused(focused) => {
                log::debug!("focused: {focused}");
                self.focused = focused;
                if !focused {
                    self.input.release_all();
                    self.set_captured(false);
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    let down = event.state == ElementState::Pressed;
                    let escape = code == KeyCode::Escape;
                    if down && ui_consumed && !escape {
                        return; // typed into the UI
                    }
                    // Only the default mode frees the mouse itself; an app that chose says so.
                    if escape && down && self.input.captured && self.capture.is_none() {
                        self.set_captured(false);
                    }
                    self.input.key_event(code, down, event.repeat);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let down = state == ElementState::Pressed;
                // A click in the window means it has the user: some X setups without a window
                // manager never report focus until the pointer is grabbed.
                self.focused |= down;
                if down && ui_consumed {
                    return; // a click on the UI
                }
                if down && button == MouseButton::Left && !self.input.captured && self.capture.is_none() {
                    self.set_captured(true);
                } else {
                    self.input.mouse_button(button, down);
                }
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame() {
                    self.fail(event_loop, e);
                }
                if self.app.wants_exit() {
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn device_event(&mut self, _event_loop: &ActiveEventLoop, _id: DeviceId, event: DeviceEvent) {
        if let DeviceEvent::MouseMotion { delta } = event {
            if self.input.captured {
                self.input.mouse_delta += glam::Vec2::new(delta.0 as f32, delta.1 as f32);
            }
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(state) = &self.state {
            state.window.request_redraw();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_app_that_chooses_gets_its_capture_while_focused_and_none_leaves_it_alone() {
        assert_eq!(capture_change(None, true, false), None);
        assert_eq!(capture_change(None, true, true), None);
        assert_eq!(capture_change(Some(true), true, false), Some(true));
        assert_eq!(capture_change(Some(true), true, true), None);
        assert_eq!(capture_change(Some(true), false, false), None, "no grab without focus");
        assert_eq!(capture_change(Some(true), false, true), Some(false));
        assert_eq!(capture_change(Some(false), true, true), Some(false));
        assert_eq!(capture_change(Some(false), true, false), None);
        assert_eq!(present_mode(true), wgpu::PresentMode::AutoVsync);
        assert_eq!(present_mode(false), wgpu::PresentMode::AutoNoVsync);
    }
}
