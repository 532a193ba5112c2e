//! Per-pass GPU timing with timestamp queries, for `headlamp bench` (opt-in, see
//! [`Renderer::set_timing`](crate::renderer::Renderer::set_timing)).
//!
//! The render graph writes a timestamp into the frame's command encoder before and after each
//! scheduled pass, resolves them into a buffer at the end of the frame and copies them into a
//! mappable one; [`GpuTimer::read`] maps it (blocking) and turns ticks into milliseconds with
//! the queue's timestamp period. Encoder-level timestamps need both `TIMESTAMP_QUERY` and
//! `TIMESTAMP_QUERY_INSIDE_ENCODERS` ([`Gpu::timestamps`]); without them there is no timer.

use crate::gpu::Gpu;

/// Two timestamps (start, end) per pass.
const PER_PASS: u32 = 2;

pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// How many passes one frame may time.
    capacity: u32,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
    /// The passes of the last frame whose timestamps were resolved, in execution order.
    recorded: Vec<String>,
}

impl GpuTimer {
    /// A timer for frames of up to `passes` passes, or None when the device cannot write
    /// timestamps inside command encoders.
    pub fn new(gpu: &Gpu, passes: u32) -> Option<Self> {
        if !gpu.timestamps {
            return None;
        }
        let capacity = passes.clamp(1, wgpu::QUERY_SET_MAX_QUERIES / PER_PASS);
        let count = capacity * PER_PASS;
        let bytes = u64::from(count) * u64::from(wgpu::QUERY_SIZE);
        let queries = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let buffer = |label, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let resolve =
            buffer("pass timestamps resolve", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
        let readback = buffer("pass timestamps readback", wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ);
        let period_ns = f64::from(gpu.queue.get_timestamp_period());
        Some(Self { queries, resolve, readback, capacity, period_ns, recorded: Vec::new() })
    }

    /// How many passes one frame may time.
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Records the start of the `index`-th pass of the frame.
    pub fn start(&self, encoder: &mut wgpu::CommandEncoder, index: usize) {
        encoder.write_timestamp(&self.queries, index as u32 * PER_PASS);
    }

    /// Records the end of the `index`-th pass of the frame.
    pub fn end(&self, encoder: &mut wgpu::CommandEncoder, index: usize) {
        encoder.write_timestamp(&self.queries, index as u32 * PER_PASS + 1);
    }

    /// Resolves the frame's timestamps (of `passes`, in the order they were timed) so that
    /// [`read`](Self::read) can fetch them once the frame has been submitted.
    pub fn finish(&mut self, encoder: &mut wgpu::CommandEncoder, passes: Vec<String>) {
        assert!(passes.len() as u32 <= self.capacity, "more passes than the timer was made for");
        let count = passes.len() as u32 * PER_PASS;
        if count > 0 {
            encoder.resolve_query_set(&self.queries, 0..count, &self.resolve, 0);
            let bytes = u64::from(count) * u64::from(wgpu::QUERY_SIZE);
            encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, bytes);
        }
        self.recorded = passes;
    }

    /// Each timed pass of the last finished frame and its GPU duration in milliseconds, in
    /// execution order; None before any frame was timed. Blocks until that frame is done.
    pub fn read(&self, gpu: &Gpu) -> Option<Vec<(String, f64)>> {
        if self.recorded.is_empty() {
            return None;
        }
        let bytes = u64::from(self.recorded.len() as u32 * PER_PASS) * u64::from(wgpu::QUERY_SIZE);
        let slice = self.readback.slice(..bytes);
        slice.map_async(wgpu::MapMode::Read, |r| r.expect("map timestamp buffer"));
        gpu.wait_idle();
        let ticks: Vec<u64> = {
            let mapped = slice.get_mapped_range().expect("timestamp buffer is mapped");
            mapped.chunks_exact(8).map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes"))).collect()
        };
        self.readback.unmap();
        let ms = |start: u64, end: u64| end.saturating_sub(start) as f64 * self.period_ns * 1e-6;
        Some(self.recorded.iter().zip(ticks.chunks_exact(2)).map(|(name, t)| (name.clone(), ms(t[0], t[1]))).collect())
    }
}
