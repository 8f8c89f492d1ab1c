//! GPU workers: one device each, so several cores compile and render variants at once, with
//! the resources their jobs bind uploaded to that device.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::{
    BoundResource, CheckError, GpuContext, GpuError, GpuResources, RenderJob, render_with,
};

/// One GPU worker: a context (its own device and queue) and the resources its jobs bind,
/// uploaded to that device.
///
/// Lavapipe compiles a pipeline's shaders when the first draw executes, on the queue's thread
/// of the device; one device per worker is what lets several cores compile at once.
#[derive(Debug)]
pub(crate) struct Worker<'c> {
    /// The worker's context.
    pub(crate) ctx: &'c GpuContext,
    /// Resources uploaded to `ctx`'s device.
    pub(crate) resources: GpuResources,
}

/// Renders `jobs` on `workers`, one thread per worker (wgpu error scopes are per thread, so
/// each job's errors stay its own). The first error stops the remaining jobs and is returned.
pub fn render_all(
    workers: &[Worker<'_>],
    jobs: &[RenderJob],
) -> Result<Vec<Vec<Vec<u8>>>, GpuError> {
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    type Slot = Option<Result<Vec<Vec<u8>>, GpuError>>;
    let results: Mutex<Vec<Slot>> = Mutex::new((0..jobs.len()).map(|_| None).collect());
    let work = |worker: &Worker<'_>| loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        if i >= jobs.len() || failed.load(Ordering::Relaxed) {
            break;
        }
        let out = render_with(worker.ctx, &jobs[i], &worker.resources);
        if out.is_err() {
            failed.store(true, Ordering::Relaxed);
        }
        results
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)[i] = Some(out);
    };
    std::thread::scope(|s| {
        for worker in workers.iter().skip(1) {
            s.spawn(move || work(worker));
        }
        if let Some(first) = workers.first() {
            work(first);
        }
    });
    let results = results
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut out = Vec::with_capacity(jobs.len());
    let mut first_error = None;
    for r in results {
        match r {
            Some(Ok(v)) => out.push(v),
            Some(Err(e)) => {
                first_error.get_or_insert(e);
            }
            None => {}
        }
    }
    match (first_error, out.len() == jobs.len()) {
        (Some(e), _) => Err(e),
        (None, true) => Ok(out),
        (None, false) => Err(GpuError::from(CheckError::NoWorker)),
    }
}

/// One worker per context (`ctx` first), each with `resources` uploaded to its device.
pub(crate) fn upload_workers<'c>(
    ctx: &'c GpuContext,
    contexts: &'c [GpuContext],
    resources: &[BoundResource],
    label: &str,
) -> Result<Vec<Worker<'c>>, GpuError> {
    std::iter::once(ctx)
        .chain(contexts)
        .map(|c| {
            Ok(Worker {
                ctx: c,
                resources: GpuResources::upload(c, label, resources)?,
            })
        })
        .collect()
}
