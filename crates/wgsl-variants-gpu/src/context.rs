//! The headless wgpu context: instance, adapter, device and queue, plus error bookkeeping.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use super::error::GpuError;

/// Default bound on every wait for the GPU ([`GpuContext::timeout`]).
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(30);

/// Errors recorded by the uncaptured-error handler and the device-lost callback.
#[derive(Debug, Default)]
struct ErrorLog {
    /// Messages of errors that no error scope captured, oldest first.
    uncaptured: Vec<String>,
    /// Reason the device was lost, if it was.
    lost: Option<String>,
}

/// Locks the error log, recovering from poisoning (the log is plain data).
fn lock(log: &Mutex<ErrorLog>) -> MutexGuard<'_, ErrorLog> {
    log.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A headless GPU context (no surface): one adapter, one device and its queue.
///
/// Create it once and reuse it for every job; creating a device is far more expensive than
/// creating pipelines. The context is `Send + Sync`, so jobs may be driven from several threads
/// (error scopes are per-thread in wgpu, which is what the harness relies on).
pub struct GpuContext {
    /// The wgpu instance the adapter came from.
    pub instance: wgpu::Instance,
    /// The selected adapter.
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
    /// Upper bound for every wait on the GPU (submission completion, buffer mapping).
    pub timeout: Duration,
    /// Information about `adapter`, queried once.
    info: wgpu::AdapterInfo,
    /// Shared with the uncaptured-error handler and the device-lost callback.
    log: Arc<Mutex<ErrorLog>>,
}

impl std::fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.info.name)
            .field("backend", &self.info.backend)
            .field("device_type", &self.info.device_type)
            .field("timeout", &self.timeout)
            .finish_non_exhaustive()
    }
}

impl GpuContext {
    /// Optional features requested when the adapter has them: URP's G-buffer renders into
    /// `Rg11b10Ufloat` (`RG11B10UFLOAT_RENDERABLE`) and, without accurate normals,
    /// `Rgba8Snorm` (renderable only as an adapter-specific format feature); the frame bench
    /// times each pass with timestamp queries (`TIMESTAMP_QUERY`; without it, it says so and
    /// times the frame by the wall clock); the deferred frame marks the light culling mask's
    /// layers in a `Depth32FloatStencil8` buffer (`DEPTH32FLOAT_STENCIL8`).
    pub const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::RG11B10UFLOAT_RENDERABLE
        .union(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
        .union(wgpu::Features::TIMESTAMP_QUERY)
        .union(wgpu::Features::DEPTH32FLOAT_STENCIL8);

    /// Creates a headless context.
    ///
    /// Backends come from `WGPU_BACKEND` (see [`wgpu::Backends::from_env`]); without it the
    /// primary backends (Vulkan, Metal, DX12) are tried first and then all backends (incl. GL).
    /// Instance flags honour the `WGPU_*` flag variables ([`wgpu::InstanceFlags::with_env`]).
    /// Adapters of every device type are considered, including CPU adapters such as Mesa's
    /// lavapipe. With `adapter_filter`, the first adapter whose name contains the filter
    /// (case-insensitively) is used; without it, the first enumerated adapter.
    ///
    /// The device gets the WebGPU default limits, lowered to what the adapter supports (except
    /// colour-attachment bytes per sample: the adapter's own, for URP's G-buffer), and
    /// only the optional features of [`GpuContext::OPTIONAL_FEATURES`] the adapter has. An uncaptured-error handler and a device-lost callback are installed
    /// that record instead of panicking; see [`GpuContext::take_error`].
    pub fn new(adapter_filter: Option<&str>) -> Result<Self, GpuError> {
        let needle = adapter_filter.map(str::to_lowercase);
        let matches = |adapter: &wgpu::Adapter| match &needle {
            Some(n) => adapter.get_info().name.to_lowercase().contains(n.as_str()),
            None => true,
        };
        // Without WGPU_BACKEND, try the primary backends (Vulkan, Metal, DX12) first and
        // only then all of them: initialising the GL backend headless is slow and noisy.
        let attempts = match wgpu::Backends::from_env() {
            Some(backends) => vec![backends],
            None => vec![wgpu::Backends::PRIMARY, wgpu::Backends::all()],
        };
        let mut available = Vec::new();
        let mut found = None;
        for backends in attempts {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            desc.flags = wgpu::InstanceFlags::from_env_or_default();
            let instance = wgpu::Instance::new(desc);
            let adapters = pollster::block_on(instance.enumerate_adapters(backends));
            available = adapters.iter().map(describe).collect();
            if let Some(adapter) = adapters.into_iter().find(|a| matches(a)) {
                found = Some((instance, adapter));
                break;
            }
        }
        let (instance, adapter) = found.ok_or_else(|| GpuError::NoAdapter {
            requested: adapter_filter.map(str::to_owned),
            available,
        })?;
        let info = adapter.get_info();
        // Shadow maps, depth pre-passes and G-buffer depth are read back to compare them with
        // the reference: a GL adapter without depth copies fails later with a raw validation
        // dump, so say so first, with the fix.
        check_downlevel(
            adapter.get_downlevel_capabilities().flags,
            &format!("{} ({:?})", info.name, info.backend),
        )?;

        let mut limits = wgpu::Limits::default().or_worse_values_from(&adapter.limits());
        // URP's G-buffer with its optional targets needs up to 48 bytes per sample (WebGPU's
        // default is 32, which the four base targets already fill): take what the adapter has.
        limits.max_color_attachment_bytes_per_sample = adapter
            .limits()
            .max_color_attachment_bytes_per_sample
            .max(limits.max_color_attachment_bytes_per_sample);
        let device_desc = wgpu::DeviceDescriptor {
            label: Some("wgsl-variants harness device"),
            required_features: adapter.features() & Self::OPTIONAL_FEATURES,
            required_limits: limits,
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&device_desc))
            .map_err(|e| GpuError::RequestDevice(e.to_string()))?;

        let log = Arc::new(Mutex::new(ErrorLog::default()));
        let handler_log = Arc::clone(&log);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            lock(&handler_log).uncaptured.push(error.to_string());
        }));
        let lost_log = Arc::clone(&log);
        device.set_device_lost_callback(move |reason, message| {
            lock(&lost_log).lost = Some(format!("{reason:?}: {message}"));
        });

        Ok(Self {
            instance,
            adapter,
            device,
            queue,
            timeout: DEFAULT_TIMEOUT,
            info,
            log,
        })
    }

    /// Name of the selected adapter, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)` for lavapipe.
    pub fn adapter_name(&self) -> &str {
        &self.info.name
    }

    /// Whether the device can time passes with timestamp queries (the adapter has
    /// `TIMESTAMP_QUERY`, requested by [`GpuContext::OPTIONAL_FEATURES`]).
    pub fn has_timestamps(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// Full information about the selected adapter.
    pub fn adapter_info(&self) -> &wgpu::AdapterInfo {
        &self.info
    }

    /// Takes the oldest error that escaped all error scopes, if any.
    ///
    /// A lost device takes precedence and is reported as [`GpuError::DeviceLost`] (and stays
    /// recorded: a lost device does not come back). Other errors come back as
    /// [`GpuError::Validation`] labelled `uncaptured` and are removed from the log.
    pub fn take_error(&self) -> Option<GpuError> {
        let mut log = lock(&self.log);
        if let Some(reason) = &log.lost {
            return Some(GpuError::DeviceLost(reason.clone()));
        }
        if log.uncaptured.is_empty() {
            None
        } else {
            let message = log.uncaptured.remove(0);
            Some(GpuError::Validation {
                label: String::from("uncaptured"),
                message,
            })
        }
    }

    /// Returns [`GpuError::DeviceLost`] if the device-lost callback has fired.
    pub fn check_device(&self) -> Result<(), GpuError> {
        match &lock(&self.log).lost {
            Some(reason) => Err(GpuError::DeviceLost(reason.clone())),
            None => Ok(()),
        }
    }

    /// Waits for all submitted work (and pending map callbacks) with [`GpuContext::timeout`]
    /// as the bound; returns [`GpuError::Timeout`] naming `label` when it expires.
    pub fn wait(&self, label: &str) -> Result<(), GpuError> {
        self.check_device()?;
        let poll = wgpu::PollType::Wait {
            submission_index: None,
            timeout: Some(self.timeout),
        };
        match self.device.poll(poll) {
            Ok(_) => self.check_device(),
            Err(wgpu::PollError::Timeout) => {
                self.check_device()?;
                Err(GpuError::Timeout {
                    label: label.to_owned(),
                    seconds: self.timeout.as_secs_f64(),
                })
            }
            Err(e) => Err(GpuError::Validation {
                label: label.to_owned(),
                message: e.to_string(),
            }),
        }
    }

    /// Runs `f` inside error scopes for validation, out-of-memory and internal errors and
    /// returns its result together with the first error captured, if any.
    ///
    /// Error scopes are per-thread, so `f` must do its wgpu calls on the calling thread.
    pub fn capture<T>(&self, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        // Scopes must be popped in reverse order of pushing.
        let validation = pollster::block_on(validation.pop());
        let internal = pollster::block_on(internal.pop());
        let oom = pollster::block_on(oom.pop());
        (value, validation.or(internal).or(oom))
    }

    /// Like [`GpuContext::capture`], but turns a captured error into [`GpuError::Validation`]
    /// labelled `label`.
    pub fn scoped<T>(&self, label: &str, f: impl FnOnce() -> T) -> Result<T, GpuError> {
        match self.capture(f) {
            (value, None) => Ok(value),
            (_, Some(error)) => Err(GpuError::Validation {
                label: label.to_owned(),
                message: error_message(&error),
            }),
        }
    }
}

/// `name (backend, device type)` of an adapter, for error messages.
fn describe(adapter: &wgpu::Adapter) -> String {
    let info = adapter.get_info();
    format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
}

/// Renders a wgpu error with its whole source chain (the naga diagnostics live there).
pub fn error_message(error: &wgpu::Error) -> String {
    let mut message = error.to_string();
    let mut source = std::error::Error::source(error);
    while let Some(s) = source {
        let text = s.to_string();
        if !message.contains(&text) {
            message.push_str("\n  caused by: ");
            message.push_str(&text);
        }
        source = s.source();
    }
    message
}
/// The downlevel capabilities the harness needs of `adapter` (named in the error).
fn check_downlevel(flags: wgpu::DownlevelFlags, adapter: &str) -> Result<(), GpuError> {
    if !flags.contains(wgpu::DownlevelFlags::DEPTH_TEXTURE_AND_BUFFER_COPIES) {
        return Err(GpuError::MissingCapability {
            adapter: adapter.to_owned(),
            what: "copy depth textures to buffers",
            flag: "DEPTH_TEXTURE_AND_BUFFER_COPIES",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A WebGL2-class adapter (GL llvmpipe when no Vulkan driver is installed) lacks depth
    /// copies: refused up front, naming the flag and the fix, instead of a validation dump.
    #[test]
    fn an_adapter_without_depth_copies_is_refused_with_the_fix() {
        let gl =
            wgpu::DownlevelFlags::all() - wgpu::DownlevelFlags::DEPTH_TEXTURE_AND_BUFFER_COPIES;
        let err = check_downlevel(gl, "llvmpipe (Gl)")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("`llvmpipe (Gl)`")
                && err.contains("DEPTH_TEXTURE_AND_BUFFER_COPIES")
                && err.contains("mesa-vulkan-drivers"),
            "{err}"
        );
        assert!(check_downlevel(wgpu::DownlevelFlags::all(), "lavapipe (Vulkan)").is_ok());
    }
}
