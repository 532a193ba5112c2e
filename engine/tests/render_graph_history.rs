//! History pairs owned by the graph: last frame's `current` is this frame's `previous`; both
//! start from zeros after `reset_history` and after a resize, and a frame that does not write
//! a history leaves it worth no frames.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use engine::gpu::Gpu;
use engine::graph::{Buffer, BufferDesc, History, Image, PassContext, PassDecl, Read, RenderPass, Stage};
use engine::graph::{SizeRule, TextureDesc, Write};
use engine::headless::{read_buffer, HeadlessTarget, ImageKind};
use engine::plugin::{Plugin, PluginContext};
use engine::renderer::Renderer;
use engine::scene::Scene;
use engine::view_state::ViewState;
use engine::wgpu::{BufferUsages, TextureFormat};

/// Writes the frame's number into word 0 of its history buffer and last frame's words 0–2
/// into words 1–3: after frames 1, 2, 3 the buffer reads [3, 2, 1, 0].
struct Shift {
    frame: u32,
    buffer: History<Buffer>,
    image: History<Image>,
    hdr: engine::graph::Handle<Image>,
    /// `history_frames` of the buffer and the image, each frame.
    seen: Rc<RefCell<Vec<(u32, u32)>>>,
    /// Frames that run without this pass (it declares nothing).
    skip: Rc<Cell<bool>>,
}

struct ShiftIo {
    previous: Read<Buffer>,
    current: Write<Buffer>,
    image_previous: Read<Image>,
    _image: Write<Image>,
    // Written so that the pass leads to the output and is not culled.
    _hdr: Write<Image>,
}

impl RenderPass for Shift {
    type Io = Option<ShiftIo>;
    fn name(&self) -> &str {
        "shift"
    }
    fn declare(&self, d: &mut PassDecl<'_>) -> Option<ShiftIo> {
        if self.skip.get() {
            return None;
        }
        let usage = BufferUsages::COPY_SRC | BufferUsages::COPY_DST;
        let image = TextureDesc { size: SizeRule::ViewScaled(0.5), ..TextureDesc::target(TextureFormat::Rgba16Float) };
        Some(ShiftIo {
            previous: d.read(self.buffer.previous()),
            current: d.create(self.buffer.current(), BufferDesc { size: 16, usage }),
            image_previous: d.read(self.image.previous()),
            _image: d.create(self.image.current(), image),
            _hdr: d.write(self.hdr),
        })
    }
    fn run(&mut self, io: &Option<ShiftIo>, ctx: &mut PassContext<'_>) {
        let Some(io) = io else { return };
        self.frame += 1;
        ctx.write_buffer(&io.current, 0, &self.frame.to_le_bytes());
        ctx.encoder.copy_buffer_to_buffer(ctx.buffer(&io.previous), 0, ctx.buffer(&io.current), 4, 12);
        self.seen.borrow_mut().push((ctx.history_frames(&io.previous), ctx.history_frames(&io.image_previous)));
    }
}

struct ShiftPlugin {
    buffer: Rc<RefCell<Option<History<Buffer>>>>,
    seen: Rc<RefCell<Vec<(u32, u32)>>>,
    skip: Rc<Cell<bool>>,
}

impl Plugin for ShiftPlugin {
    fn name(&self) -> &str {
        "shift"
    }
    fn build(&mut self, ctx: &mut PluginContext<'_>) {
        let (buffer, image, hdr) =
            (ctx.history_buffer("shift.words"), ctx.history_image("shift.image"), ctx.core().hdr);
        *self.buffer.borrow_mut() = Some(buffer);
        let (seen, skip) = (self.seen.clone(), self.skip.clone());
        ctx.add_pass(Stage::Composite, Shift { frame: 0, buffer, image, hdr, seen, skip });
    }
}

#[test]
fn history_carries_last_frame_and_starts_from_zeros_after_a_reset_or_resize() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let (buffer, seen) = (Rc::new(RefCell::new(None)), Rc::new(RefCell::new(Vec::new())));
    let skip = Rc::new(Cell::new(false));
    let plugin = ShiftPlugin { buffer: buffer.clone(), seen: seen.clone(), skip: skip.clone() };
    let mut renderer = Renderer::new(&gpu, &Scene::default(), vec![Box::new(plugin)]).unwrap();
    let history = buffer.borrow().expect("built");
    let view = ViewState::default();
    let words = |renderer: &Renderer| -> [u32; 4] {
        // After a frame, what it wrote is the next frame's previous.
        let bytes = read_buffer(&gpu, renderer.graph().physical_buffer(history.previous()).unwrap());
        bytemuck::pod_read_unaligned(&bytes[..16])
    };
    let frame = |renderer: &mut Renderer, size: (u32, u32)| {
        let target = HeadlessTarget::new(&gpu, size.0, size.1, ImageKind::Display);
        target.render(&gpu, renderer, &view).unwrap();
    };
    for _ in 0..3 {
        frame(&mut renderer, (64, 48));
    }
    assert_eq!(words(&renderer), [3, 2, 1, 0]);
    assert_eq!(*seen.borrow(), [(0, 0), (1, 1), (2, 2)], "frames of history behind previous");

    renderer.reset_history();
    frame(&mut renderer, (64, 48));
    assert_eq!(words(&renderer), [4, 0, 0, 0], "a reset starts from zeros");
    frame(&mut renderer, (64, 48));
    assert_eq!(words(&renderer), [5, 4, 0, 0]);

    // A resize re-makes the view-sized image (its history starts again), not the buffer.
    frame(&mut renderer, (80, 60));
    assert_eq!(seen.borrow().last(), Some(&(2, 0)));
    assert_eq!(words(&renderer), [6, 5, 4, 0]);

    // A frame without the pass: its history is older than last frame, so it counts for none.
    skip.set(true);
    frame(&mut renderer, (80, 60));
    skip.set(false);
    frame(&mut renderer, (80, 60));
    assert_eq!(seen.borrow().last(), Some(&(0, 0)), "a frame that did not write a history breaks it");
    frame(&mut renderer, (80, 60));
    assert_eq!(seen.borrow().last(), Some(&(1, 1)));
}
