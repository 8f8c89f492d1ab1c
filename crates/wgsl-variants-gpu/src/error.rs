//! The error type of the GPU harness.

use thiserror::Error;

/// Everything that can go wrong while driving the GPU harness.
///
/// wgpu reports most failures asynchronously through error scopes; the harness captures them
/// and turns them into one of these variants instead of letting wgpu's default handler panic.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter matched the request (or the machine has no usable adapter at all).
    #[error(
        "no GPU adapter found{}{}; install Mesa's lavapipe: apt-get install mesa-vulkan-drivers",
        .requested.as_ref().map(|r| format!(" matching {r:?}")).unwrap_or_default(),
        if .available.is_empty() {
            String::from(" (no adapters available)")
        } else {
            format!(" (available: {})", .available.join(", "))
        }
    )]
    NoAdapter {
        /// The adapter-name filter that was requested, if any.
        requested: Option<String>,
        /// Names of all adapters that were enumerated.
        available: Vec<String>,
    },
    /// The adapter refused to create a device.
    #[error("failed to create a GPU device: {0}")]
    RequestDevice(String),
    /// The adapter lacks a capability the harness needs (a downlevel adapter: WebGL2-class GL,
    /// such as llvmpipe's GL driver when no Vulkan driver is installed).
    #[error(
        "the adapter `{adapter}` cannot {what} (wgpu's downlevel flag {flag}), which the GPU check needs: install a Vulkan driver (on Debian, Mesa's lavapipe: `apt-get install mesa-vulkan-drivers`) or pick another adapter (--adapter NAME; WGPU_BACKEND=vulkan)"
    )]
    MissingCapability {
        /// The adapter's name and backend.
        adapter: String,
        /// What it cannot do, in words.
        what: &'static str,
        /// The wgpu flag.
        flag: &'static str,
    },
    /// The device was lost (driver reset, destroyed, ...).
    #[error("GPU device lost: {0}")]
    DeviceLost(String),
    /// A shader module or pipeline failed to compile or validate.
    #[error("pipeline `{label}` failed to compile: {message}")]
    PipelineCompile {
        /// Label of the pipeline (usually the variant name).
        label: String,
        /// The wgpu / naga diagnostic.
        message: String,
    },
    /// Any other wgpu validation (or out-of-memory / internal) error.
    #[error("GPU validation error in `{label}`: {message}")]
    Validation {
        /// Label of the operation that failed.
        label: String,
        /// The wgpu diagnostic.
        message: String,
    },
    /// Reading results back from the GPU failed.
    #[error("GPU readback failed in `{label}`: {message}")]
    Readback {
        /// Label of the operation that failed.
        label: String,
        /// What went wrong.
        message: String,
    },
    /// The GPU did not finish within the configured timeout.
    #[error("GPU work `{label}` did not finish within {seconds} s")]
    Timeout {
        /// Label of the operation that timed out.
        label: String,
        /// The timeout that expired, in seconds.
        seconds: f64,
    },
    /// The GPU check cannot run as asked.
    #[error("GPU check: {0}")]
    Check(Box<CheckError>),
}

/// Why the GPU check cannot run as asked.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CheckError {
    /// A shader, pass or keyword set the library does not have.
    #[error("{what}: {source}")]
    Lookup {
        /// What was looked up (`shader/pass`, a kernel).
        what: String,
        /// The lookup error.
        source: wgsl_variants::LookupError,
    },
    /// A pass's space past the check's budget.
    #[error("{what}: {source}")]
    Budget {
        /// `shader/pass`.
        what: String,
        /// The budget error.
        source: wgsl_variants::variants::BudgetError,
    },
    /// A pass's covering set could not be made.
    #[error(transparent)]
    Cover(#[from] wgsl_variants::covering::CoverError),
    /// A keyword set the CPU reference does not know.
    #[error("{variant}: the reference does not know this keyword set: {message}")]
    UnknownToReference {
        /// `shader/pass {KEYWORDS}`.
        variant: String,
        /// What the reference says.
        message: String,
    },
    /// The library of compute kernels does not load.
    #[error("the kernel library does not load:\n{}", .0.render(false))]
    KernelLibrary(Box<wgsl_variants::LoadError>),
    /// No pass or kernel matches the filters.
    #[error("nothing matches shader {:?} pass {:?}; the check knows {}", .shader.as_deref().unwrap_or("*"), .pass.as_deref().unwrap_or("*"), .known.join(", "))]
    NoMatch {
        /// The shader filter.
        shader: Option<String>,
        /// The pass filter.
        pass: Option<String>,
        /// Every `shader/pass` (and kernel) the check knows.
        known: Vec<String>,
    },
    /// Pictures are made of the standard passes only.
    #[error("pictures are made of standard/Deferred and standard/ForwardBase, not {0}")]
    NoPictures(String),
    /// There is no GPU worker to render on.
    #[error("no GPU worker to render on")]
    NoWorker,
    /// The deferred path's stencil holds at most four layers a light leaves out (the Unity
    /// Manual's Deferred Shading rendering path: the culling masks must keep 28 of the 32
    /// layers).
    #[error(
        "the lights' culling masks leave out {} layers ({}); the deferred path supports at most four",
        .layers.len(),
        .layers.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
    )]
    TooManyCulledLayers {
        /// Every layer some light leaves out, ascending.
        layers: Vec<u32>,
    },
}

impl From<CheckError> for GpuError {
    fn from(e: CheckError) -> GpuError {
        GpuError::Check(Box::new(e))
    }
}

impl CheckError {
    /// A lookup error about `what`.
    pub fn lookup(what: impl Into<String>, source: wgsl_variants::LookupError) -> GpuError {
        GpuError::from(CheckError::Lookup {
            what: what.into(),
            source,
        })
    }
}
