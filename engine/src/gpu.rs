//! The GPU context: one instance/adapter/device/queue, shared by the window and headless paths.

use std::fmt;
use std::sync::{Arc, Mutex};

/// wgpu's errors span lines (a source chain); ours are one.
fn one_line(e: &impl fmt::Display) -> String {
    e.to_string().split(['\n', '\r']).map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join(" ")
}

/// Installed by `.ci/run`; printed whenever no adapter is found so a test failure says what to do.
pub const LAVAPIPE_HINT: &str = "install Mesa's software Vulkan driver (lavapipe): \
`sudo apt-get install mesa-vulkan-drivers libvulkan1` (Debian/Ubuntu), then retry";

/// The Vulkan driver name (`VkPhysicalDeviceDriverProperties::driverName`, wgpu's
/// `AdapterInfo::driver`) of Mesa's software rasteriser, lavapipe.
pub const LAVAPIPE_DRIVER: &str = "llvmpipe";

/// Which of `adapters` is lavapipe: the first Vulkan adapter whose driver is
/// [`LAVAPIPE_DRIVER`]. Any other adapter is refused, however capable, with the list of what
/// was found: pictures and GI figures compared with goldens made on lavapipe would meet another
/// rasteriser's rounding there.
pub fn choose_lavapipe(adapters: &[wgpu::AdapterInfo]) -> Result<usize, GpuError> {
    adapters
        .iter()
        .position(|a| a.backend == wgpu::Backend::Vulkan && a.driver.eq_ignore_ascii_case(LAVAPIPE_DRIVER))
        .ok_or_else(|| {
            let found: Vec<String> =
                adapters.iter().map(|a| format!("{} ({:?}, driver {})", a.name, a.backend, a.driver)).collect();
            let found = if found.is_empty() { "none".to_string() } else { found.join(", ") };
            GpuError::NoAdapter(format!(
                "goldens and GI figures are compared on lavapipe (Vulkan driver {LAVAPIPE_DRIVER}); found {found}"
            ))
        })
}

pub enum GpuError {
    NoAdapter(String),
    Device(String),
    /// Work on the device failed (out of memory, a size past its limits, a validation error).
    Failed(String),
}

impl fmt::Display for GpuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GpuError::NoAdapter(why) => write!(f, "no GPU adapter found ({why}); {LAVAPIPE_HINT}"),
            GpuError::Device(why) => write!(f, "could not open the GPU device: {why}"),
            GpuError::Failed(why) => write!(f, "the GPU failed {why}"),
        }
    }
}

/// As [`Display`](fmt::Display): a test's `.unwrap()` then prints the install advice.
impl fmt::Debug for GpuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for GpuError {}

pub struct Gpu {
    /// GPU errors raised outside an error scope (see [`Gpu::checked`]), oldest first: wgpu's
    /// default is to panic on them; here the frame loop turns them into an error instead.
    uncaptured: Arc<Mutex<Vec<String>>>,
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Whether the device can write GPU timestamps (used by `bench`).
    pub timestamps: bool,
}

impl Gpu {
    /// A device with no window. `WGPU_ADAPTER_NAME` / `WGPU_BACKEND` pick a specific adapter.
    pub fn headless() -> Result<Gpu, GpuError> {
        Self::headless_without(wgpu::Features::empty())
    }

    /// A device on lavapipe ([`choose_lavapipe`]) whatever else the machine has and whatever
    /// the environment says: for the tests and commands that compare pictures or GI figures
    /// with what was measured on it. Fails with install advice where it is missing.
    pub fn lavapipe() -> Result<Gpu, GpuError> {
        let vulkan = wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        };
        let instance = wgpu::Instance::new(vulkan);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        let infos: Vec<wgpu::AdapterInfo> = adapters.iter().map(wgpu::Adapter::get_info).collect();
        let adapter = adapters.swap_remove(choose_lavapipe(&infos)?);
        Self::open(instance, adapter, wgpu::Features::empty())
    }

    /// [`Gpu::headless`] without `features` even where the adapter has them: for tests of what
    /// a device that lacks them gets.
    pub fn headless_without(features: wgpu::Features) -> Result<Gpu, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(Self::pick_adapter(&instance, None))?;
        Self::open(instance, adapter, features)
    }

    /// A device able to present to `surface` (created from `instance`).
    pub fn for_surface(instance: wgpu::Instance, surface: &wgpu::Surface<'_>) -> Result<Gpu, GpuError> {
        let adapter = pollster::block_on(Self::pick_adapter(&instance, Some(surface)))?;
        Self::open(instance, adapter, wgpu::Features::empty())
    }

    async fn pick_adapter(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<wgpu::Adapter, GpuError> {
        if let Ok(name) = std::env::var("WGPU_ADAPTER_NAME") {
            let wanted = name.to_lowercase();
            for adapter in instance.enumerate_adapters(wgpu::Backends::all()).await {
                if adapter.get_info().name.to_lowercase().contains(&wanted)
                    && surface.is_none_or(|s| adapter.is_surface_supported(s))
                {
                    return Ok(adapter);
                }
            }
            return Err(GpuError::NoAdapter(format!("no adapter named like WGPU_ADAPTER_NAME={name}")));
        }
        instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: surface,
                apply_limit_buckets: false,
            })
            .await
            .map_err(|e| GpuError::NoAdapter(e.to_string()))
    }

    fn open(instance: wgpu::Instance, adapter: wgpu::Adapter, without: wgpu::Features) -> Result<Gpu, GpuError> {
        let timing = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
        // Blending into f32 targets lets plugins accumulate many small contributions exactly;
        // subgroup operations let a compute pass's lanes share work (see `subgroup_size`).
        let wanted = timing | wgpu::Features::FLOAT32_BLENDABLE | wgpu::Features::SUBGROUP;
        let features = adapter.features() & (wanted - without);
        let info = adapter.get_info();
        log::info!("GPU adapter: {} ({:?}, {:?}), features {:?}", info.name, info.backend, info.device_type, features);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("headlamp"),
            required_features: features,
            // The G-buffer needs more colour bytes per sample than WebGPU's baseline; every
            // Vulkan/Metal/D3D12 adapter offers it, so take what the adapter has.
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        let uncaptured = Arc::new(Mutex::new(Vec::new()));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            let message = one_line(&e);
            log::error!("GPU: {message}");
            if let Ok(mut errors) = sink.lock() {
                errors.push(message);
            }
        }));
        Ok(Gpu { uncaptured, instance, adapter, device, queue, timestamps: features.contains(timing) })
    }

    /// Runs `f` with the device's errors caught (out of memory, validation, internal): a GPU
    /// error in it becomes an `Err` saying what was being done, never wgpu's panic.
    pub fn checked<T>(&self, doing: &str, f: impl FnOnce() -> T) -> Result<T, GpuError> {
        let scopes = [wgpu::ErrorFilter::OutOfMemory, wgpu::ErrorFilter::Validation, wgpu::ErrorFilter::Internal]
            .map(|filter| self.device.push_error_scope(filter));
        let value = f();
        // Popped innermost first; running out of memory is reported before the invalid
        // resources it leaves behind.
        let mut caught: Vec<Option<wgpu::Error>> =
            scopes.into_iter().rev().map(|s| pollster::block_on(s.pop())).collect();
        caught.reverse();
        match caught.into_iter().flatten().next() {
            None => Ok(value),
            Some(e) => Err(GpuError::Failed(format!("{doing}: {}", one_line(&e)))),
        }
    }

    /// The first GPU error raised outside [`Gpu::checked`] since the last call, if any.
    pub fn take_uncaptured(&self) -> Option<String> {
        let mut errors = self.uncaptured.lock().ok()?;
        let first = errors.first().cloned();
        errors.clear();
        first
    }

    pub fn adapter_name(&self) -> String {
        self.adapter.get_info().name
    }

    /// The number of lanes of every subgroup of a compute shader (lavapipe: 8 on a CPU with
    /// 256-bit vectors; NVIDIA: 32), when the device has subgroup operations and its subgroups
    /// are all of one size; None otherwise.
    pub fn subgroup_size(&self) -> Option<u32> {
        let info = self.adapter.get_info();
        let one_size = info.subgroup_min_size == info.subgroup_max_size;
        (self.device.features().contains(wgpu::Features::SUBGROUP) && one_size).then_some(info.subgroup_min_size)
    }

    /// Whether render targets of 32-bit float formats can be blended into.
    pub fn float32_blendable(&self) -> bool {
        self.device.features().contains(wgpu::Features::FLOAT32_BLENDABLE)
    }

    /// Blocks until all submitted work is done.
    pub fn wait_idle(&self) {
        let _ = self.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adapter(name: &str, driver: &str, device_type: wgpu::DeviceType, backend: wgpu::Backend) -> wgpu::AdapterInfo {
        wgpu::AdapterInfo { name: name.into(), driver: driver.into(), ..wgpu::AdapterInfo::new(device_type, backend) }
    }

    #[test]
    fn lavapipe_is_chosen_by_its_driver_and_any_other_adapter_is_refused() {
        use wgpu::{Backend, DeviceType};
        let nvidia = adapter("NVIDIA H100", "NVIDIA", DeviceType::DiscreteGpu, Backend::Vulkan);
        let lavapipe = adapter("llvmpipe (LLVM 15.0.6, 256 bits)", "llvmpipe", DeviceType::Cpu, Backend::Vulkan);
        // Another CPU adapter is not lavapipe, nor is an adapter merely named like it.
        let swiftshader = adapter("SwiftShader Device", "SwiftShader driver", DeviceType::Cpu, Backend::Vulkan);
        let named_like =
            adapter("llvmpipe", "Intel open-source Mesa driver", DeviceType::IntegratedGpu, Backend::Vulkan);
        let on_gl = adapter("llvmpipe (LLVM 15.0.6, 256 bits)", "llvmpipe", DeviceType::Cpu, Backend::Gl);
        assert_eq!(choose_lavapipe(&[nvidia.clone(), lavapipe.clone()]).unwrap(), 1);
        assert_eq!(choose_lavapipe(&[lavapipe]).unwrap(), 0);
        let refused = [nvidia, swiftshader, named_like, on_gl];
        let e = choose_lavapipe(&refused).unwrap_err().to_string();
        assert!(e.contains("NVIDIA H100 (Vulkan, driver NVIDIA)") && e.contains("SwiftShader"), "{e}");
        assert!(e.contains("mesa-vulkan-drivers"), "the error says how to install lavapipe: {e}");
        let e = choose_lavapipe(&[]).unwrap_err().to_string();
        assert!(e.contains("found none") && e.contains("mesa-vulkan-drivers"), "{e}");
    }
}
