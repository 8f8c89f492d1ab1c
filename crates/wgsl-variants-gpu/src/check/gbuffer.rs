//! G-buffers of `standard/Deferred` rendered on the GPU and read back: the inputs of every
//! deferred check (reflections, lighting, light volumes, forward against deferred), each of
//! which compares its own pass over the very texels stored here.

use glam::Vec4;

use super::scene::TestScene;
use super::standard::{StandardOutput, standard_job};
use crate::{CheckError, GpuContext, GpuError, TargetFormat, render};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::gbuffer::{GBufferTexel, Rt3Texel};
use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
use wgsl_variants_shaders::reference::surface::{Keywords, SmoothnessSource};

/// The keywords of the G-buffers the deferred chain starts from (with
/// `UNITY_ENABLE_REFLECTION_BUFFERS`, so RT3 holds no indirect specular yet): every map on, and
/// a plain material whose smoothness comes from the albedo's alpha.
pub const CHAIN_INPUTS: [Keywords; 2] = [
    Keywords {
        reflection_buffers: true,
        ..Keywords::EVERY_MAP
    },
    Keywords {
        smoothness: SmoothnessSource::Albedo,
        normal_map: true,
        reflection_buffers: true,
        ..Keywords::NONE
    },
];

/// A G-buffer read back from the GPU: the bytes of RT0..RT3.
#[derive(Clone, Debug)]
pub struct GBufferImage {
    /// The keywords it was rendered with.
    pub keywords: Vec<String>,
    /// Whether RT3 is `Rgba16Float` (`UNITY_HDR_ON`).
    pub hdr: bool,
    /// Tightly packed RT0, RT1, RT2, RT3, and RT4 with `SHADOWS_SHADOWMASK`.
    pub targets: Vec<Vec<u8>>,
}

impl GBufferImage {
    /// The stored texels of pixel `i`.
    pub fn texel(&self, i: usize) -> GBufferTexel {
        let rt3_size = if self.hdr { 8 } else { 4 };
        let four = |t: usize| -> [u8; 4] {
            let b = &self.targets[t][i * 4..i * 4 + 4];
            [b[0], b[1], b[2], b[3]]
        };
        let rt3 = &self.targets[3][i * rt3_size..(i + 1) * rt3_size];
        GBufferTexel::from_bytes(four(0), four(1), four(2), rt3).unwrap_or(GBufferTexel {
            rt0: [0; 4],
            rt1: [0; 4],
            rt2: [0; 4],
            rt3: Rt3Texel::Ldr([0; 4]),
        })
    }

    /// RT4's stored texel of pixel `i` (the baked occlusion; `SHADOWS_SHADOWMASK`), `None`
    /// without RT4.
    pub fn shadowmask(&self, i: usize) -> Option<Vec4> {
        let rt4 = self.targets.get(4)?;
        let b = &rt4[i * 4..i * 4 + 4];
        Some(Vec4::from_array(
            [b[0], b[1], b[2], b[3]].map(|c| unorm_to_f32(u32::from(c), 8)),
        ))
    }

    /// RT3's format.
    pub fn rt3_format(&self) -> TargetFormat {
        if self.hdr {
            TargetFormat::Rgba16Float
        } else {
            TargetFormat::Rgb10a2Unorm
        }
    }
}

/// Renders one `standard/Deferred` variant of the scene and reads its G-buffer back.
pub fn render_gbuffer(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    keywords: &[&str],
) -> Result<GBufferImage, GpuError> {
    let variant = lib
        .variant("standard", "Deferred", keywords)
        .map_err(|e| CheckError::lookup(format!("standard/Deferred {keywords:?}"), e))?;
    let output = StandardOutput::gbuffer_of(keywords);
    let hdr = keywords.contains(&"UNITY_HDR_ON");
    let mut job = standard_job(scene, &variant.label(), &lib.wgsl(&variant), output);
    job.resources = scene.standard_resources();
    Ok(GBufferImage {
        keywords: keywords.iter().map(|k| (*k).to_owned()).collect(),
        hdr,
        targets: render(ctx, &job)?,
    })
}

/// How a pass adds light to RT3: One/One onto the `Rgba16Float` RT3 (`hdr`), DstColor/Zero
/// onto the `exp2(−c)` `Rgb10a2Unorm` one (the light then adds in the exponent).
pub(crate) fn rt3_blend(hdr: bool) -> wgpu::BlendState {
    let (src_factor, dst_factor) = if hdr {
        (wgpu::BlendFactor::One, wgpu::BlendFactor::One)
    } else {
        (wgpu::BlendFactor::Dst, wgpu::BlendFactor::Zero)
    };
    let blend = wgpu::BlendComponent {
        src_factor,
        dst_factor,
        operation: wgpu::BlendOperation::Add,
    };
    wgpu::BlendState {
        color: blend,
        alpha: blend,
    }
}
