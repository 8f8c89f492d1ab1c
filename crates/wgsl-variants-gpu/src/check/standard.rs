//! What a `standard` shader variant writes and the render job that draws it over the test
//! scene: shared by the standard passes' check, the G-buffers every deferred check starts
//! from, the pictures and the benches.

use super::compare::format_name;
use super::scene::TestScene;
use crate::{ColorTarget, RenderJob, TargetFormat};

/// The clear colours of the G-buffer targets RT0..RT4 (and of the forward target: RT0's):
/// values no lit pixel of the scene produces, so a discarded pixel that was written shows.
pub const CLEAR: [[f64; 4]; 5] = [
    [0.25, 0.5, 0.75, 0.125],
    [0.875, 0.625, 0.375, 0.25],
    [0.125, 0.25, 0.375, 0.0],
    [0.0625, 0.75, 0.5, 0.0],
    [0.375, 0.125, 0.625, 0.875],
];

/// What a standard pass's variant writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandardOutput {
    /// `ForwardBase` / `ForwardAdd`: one `Rgba8Unorm` colour.
    Forward,
    /// `Deferred`: the G-buffer.
    GBuffer {
        /// `UNITY_HDR_ON`: RT3 is `Rgba16Float` (else `Rgb10a2Unorm`).
        hdr: bool,
        /// `SHADOWS_SHADOWMASK`: RT4 (`Rgba8Unorm`, the baked occlusion) too.
        shadowmask: bool,
    },
}

impl StandardOutput {
    /// The G-buffer a `Deferred` variant with these keywords writes.
    pub fn gbuffer_of(keywords: &[&str]) -> StandardOutput {
        StandardOutput::GBuffer {
            hdr: keywords.contains(&"UNITY_HDR_ON"),
            shadowmask: keywords.contains(&"SHADOWS_SHADOWMASK"),
        }
    }

    /// The colour targets, named: RT0..RT3 (and RT4) of the G-buffer, or the forward colour.
    pub fn targets(self) -> Vec<(String, ColorTarget)> {
        let formats = match self {
            StandardOutput::Forward => {
                return vec![(
                    String::from("out Rgba8Unorm"),
                    ColorTarget::new(TargetFormat::Rgba8Unorm).with_clear(CLEAR[0]),
                )];
            }
            StandardOutput::GBuffer { hdr, shadowmask } => {
                let rt3 = if hdr {
                    TargetFormat::Rgba16Float
                } else {
                    TargetFormat::Rgb10a2Unorm
                };
                let mut formats = vec![
                    TargetFormat::Rgba8Unorm,
                    TargetFormat::Rgba8Unorm,
                    TargetFormat::Rgb10a2Unorm,
                    rt3,
                ];
                if shadowmask {
                    formats.push(TargetFormat::Rgba8Unorm);
                }
                formats
            }
        };
        formats
            .into_iter()
            .enumerate()
            .map(|(i, format)| {
                (
                    format!("RT{i} {}", format_name(format)),
                    ColorTarget::new(format).with_clear(CLEAR[i]),
                )
            })
            .collect()
    }
}

/// The render job of one variant's composed text.
pub fn standard_job(
    scene: &TestScene,
    label: &str,
    wgsl: &str,
    output: StandardOutput,
) -> RenderJob {
    let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
    job.width = scene.width;
    job.height = scene.height;
    job.targets = output.targets().into_iter().map(|(_, t)| t).collect();
    job.vertex_buffers = vec![scene.quad()];
    job.vertex_count = 6;
    job
}
