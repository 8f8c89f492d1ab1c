//! GPU time per render pass, from wgpu timestamp queries (`Features::TIMESTAMP_QUERY`): each
//! pass writes a timestamp where it begins and one where it ends, the query set is resolved
//! into a buffer in the same submission, and the ticks are read back after it completes and
//! scaled by [`wgpu::Queue::get_timestamp_period`] (nanoseconds per tick).
//!
//! An adapter without timestamp queries gets no [`PassTimer`] (`None`): the caller says so
//! and falls back to wall-clock time, never a silent zero.

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::readback::map_buffers;

/// One pass's interval on the GPU's clock, in nanoseconds from the first pass's start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassSpan {
    /// When the pass began.
    pub start_ns: f64,
    /// When it ended.
    pub end_ns: f64,
}

impl PassSpan {
    /// The pass's GPU time in milliseconds.
    pub fn ms(&self) -> f64 {
        (self.end_ns - self.start_ns) * 1e-6
    }
}

/// Timestamp queries for `passes` render passes of one submission.
#[derive(Debug)]
pub(crate) struct PassTimer {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    passes: u32,
}

impl PassTimer {
    /// A timer for `passes` passes, or `None` when the device was created without
    /// `TIMESTAMP_QUERY` (the adapter lacks it; see `GpuContext::OPTIONAL_FEATURES`).
    pub(crate) fn new(ctx: &GpuContext, label: &str, passes: usize) -> Option<PassTimer> {
        if !ctx
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
            || passes == 0
        {
            return None;
        }
        let passes = u32::try_from(passes).ok()?;
        let count = passes * 2;
        let size = u64::from(count) * wgpu::QUERY_SIZE as u64;
        let buffer = |usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(PassTimer {
            set: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some(label),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer(wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ),
            passes,
        })
    }

    /// The timestamp writes of pass `pass` (its begin and end queries).
    pub(crate) fn writes(&self, pass: usize) -> wgpu::RenderPassTimestampWrites<'_> {
        let first = pass as u32 * 2;
        wgpu::RenderPassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(first),
            end_of_pass_write_index: Some(first + 1),
        }
    }

    /// Records the resolve of every query into a mappable buffer, after the passes.
    pub(crate) fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..self.passes * 2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, self.resolve.size());
    }

    /// Reads the resolved ticks (the submission holding [`PassTimer::resolve`] must have been
    /// made) and returns each pass's span in nanoseconds from the first pass's start.
    pub(crate) fn read(&self, ctx: &GpuContext, label: &str) -> Result<Vec<PassSpan>, GpuError> {
        let bytes = map_buffers(ctx, label, &[&self.read])?.remove(0);
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        let period = f64::from(ctx.queue.get_timestamp_period());
        let origin = ticks.first().copied().unwrap_or(0);
        // Ticks before the origin would be a clock gone backwards: kept signed, so a check
        // sees it instead of a wrapped huge value.
        let ns = |t: u64| (t as i128 - origin as i128) as f64 * period;
        Ok(ticks
            .chunks_exact(2)
            .map(|p| PassSpan {
                start_ns: ns(p[0]),
                end_ns: ns(p[1]),
            })
            .collect())
    }
}
