//! What the GPU check is asked to run: the selection of shaders and passes, the adapter, the
//! workers, and how much of each pass's variant space (samples, shards, covering sets).

/// What to check.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct CheckOptions {
    /// Only this shader (`standard`, `deferred_shading`, `deferred_reflections`, `deferred_final`, or `kernels`
    /// for the compute kernels alone).
    pub shader: Option<String>,
    /// Only passes (or kernels) with this name.
    pub pass: Option<String>,
    /// The first adapter whose name contains this (case-insensitive); default: the first one.
    pub adapter: Option<String>,
    /// GPU workers, each with its own device (0: one per available core, at most 4).
    pub threads: usize,
    /// Check every n-th variant of the standard passes only (0 or 1: all of them). Keyword
    /// coverage is judged on the full space only.
    pub sample: usize,
    /// Only this shard of each standard pass's variants (variant i of a pass is in shard
    /// `i % N`); with `sample`, both apply. Keyword coverage is judged on the full space only.
    pub shard: Option<wgsl_variants::variants::Shard>,
    /// Check a t-wise covering set of each pass instead of its full space
    /// ([`wgsl_variants::Space::covering`]); `sample` and `shard` then apply to it (standard
    /// passes). The passes that are otherwise run whole (URP's lighting, shadow-caster and
    /// depth passes, the built-in deferred lighting) judge keyword coverage on the full space
    /// only.
    pub cover: Option<usize>,
    /// With `cover`, cover only passes whose space holds more than this many variants (as
    /// `validate --cover-above`). Without `cover`, passes past this many variants (default
    /// [`DEFAULT_COVER_ABOVE`]) get a [`DEFAULT_COVER_T`]-wise covering set.
    pub cover_above: Option<u64>,
    /// Check every variant of every selected pass, whatever its size (no covering set).
    pub full: bool,
    /// The bound on each wait for the GPU, for every worker's device (default
    /// [`crate::DEFAULT_TIMEOUT`]). A software adapter compiles a large variant at its first
    /// draw, so a busy machine may need more.
    pub timeout: Option<std::time::Duration>,
}

/// Passes with more variants than this are covered by default (URP's `UniversalGBuffer`).
pub const DEFAULT_COVER_ABOVE: u64 = 8192;

/// The covering strength of the default covering sets.
pub const DEFAULT_COVER_T: usize = 3;

impl CheckOptions {
    /// Whether the selection takes `shader/pass`.
    pub(crate) fn wants(&self, shader: &str, pass: &str) -> bool {
        self.shader.as_deref().is_none_or(|s| s == shader)
            && self.pass.as_deref().is_none_or(|p| p == pass)
    }

    /// The covering strength for a pass of `count` variants, or `None` for its full space.
    ///
    /// ```
    /// use wgsl_variants_gpu::check::CheckOptions;
    /// let mut o = CheckOptions::default();
    /// assert_eq!((o.cover_for(3072), o.cover_for(65536)), (None, Some(3)));
    /// o.full = true;
    /// assert_eq!(o.cover_for(65536), None);
    /// o.full = false;
    /// o.cover = Some(2);
    /// assert_eq!((o.cover_for(3072), o.cover_for(65536)), (Some(2), Some(2)));
    /// o.cover_above = Some(8192);
    /// assert_eq!(o.cover_for(3072), None);
    /// ```
    pub fn cover_for(&self, count: u64) -> Option<usize> {
        if self.full {
            return None;
        }
        match self.cover {
            Some(t) => self.cover_above.is_none_or(|n| count > n).then_some(t),
            None => {
                (count > self.cover_above.unwrap_or(DEFAULT_COVER_ABOVE)).then_some(DEFAULT_COVER_T)
            }
        }
    }

    /// Opens a device on the selected adapter with the selected timeout.
    pub(crate) fn context(&self) -> Result<crate::GpuContext, crate::GpuError> {
        let mut ctx = crate::GpuContext::new(self.adapter.as_deref())?;
        if let Some(timeout) = self.timeout {
            ctx.timeout = timeout;
        }
        Ok(ctx)
    }

    /// How many GPU workers to run: the `threads` field, or one per core (at most 4) for 0.
    pub(crate) fn threads(&self) -> usize {
        if self.threads > 0 {
            self.threads
        } else {
            std::thread::available_parallelism()
                .map_or(1, |n| n.get())
                .min(4)
        }
    }
}
