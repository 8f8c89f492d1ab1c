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
    /// The GPU check cannot run as asked (an unknown shader or pass, a keyword set the
    /// reference does not know, a kernel library that does not compose, ...).
    #[error("GPU check: {0}")]
    Check(String),
}
