//! URP's screen-space ambient occlusion in the lighting checks (`_SCREEN_SPACE_OCCLUSION`,
//! docs/urp.md §14): the SSAO texture the checks bind ([`ScreenOcclusion`], bindings 26-27 of
//! `universal/ambient_occlusion`) and what the reference reads from it
//! ([`wgsl_variants_shaders::reference::urp::ambient_occlusion`]).

use crate::{BoundResource, Resource};
use wgsl_variants_shaders::reference::urp::ambient_occlusion::AmbientOcclusionFactor;

/// The direct lighting strength the checks give URP's SSAO feature (`_AmbientOcclusionParam.w`;
/// URP's default is 0.25: a larger one makes the direct part show more).
pub const DIRECT_STRENGTH: f32 = 0.6;

/// URP's `_AmbientOcclusionParam` as the checks set it (w [`DIRECT_STRENGTH`]; x, y, z unused
/// here): the StencilDeferred passes' binding 26 ([`ScreenOcclusion::resources`]) and the
/// forward pass's `Lighting` record.
pub const AMBIENT_OCCLUSION_PARAM: [f32; 4] = [0.0, 0.0, 0.0, DIRECT_STRENGTH];

/// A camera-sized SSAO texture (`R8Unorm`, URP's `_ScreenSpaceOcclusionTexture` format): a
/// pattern of sixteen levels from 30/255 to 240/255 that changes from pixel to pixel, so values
/// both below and above a surface's own occlusion occur. It stands in for what URP's SSAO pass
/// writes (not built yet: docs/urp.md §14).
///
/// ```
/// use wgsl_variants_gpu::check::urp_occlusion::{DIRECT_STRENGTH, ScreenOcclusion};
/// let ao = ScreenOcclusion::new(4, 4);
/// let f = ao.factor(0, 0);
/// assert_eq!(f.indirect, 30.0 / 255.0);
/// assert!((f.direct - (1.0 + DIRECT_STRENGTH * (f.indirect - 1.0))).abs() < 1e-6);
/// assert_eq!(ao.resources().len(), 2);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ScreenOcclusion {
    width: u32,
    height: u32,
    texels: Vec<u8>,
}

impl ScreenOcclusion {
    /// The pattern at `width × height` pixels.
    pub fn new(width: u32, height: u32) -> ScreenOcclusion {
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (30 + ((x * 5 + y * 11) % 16) * 14) as u8))
            .collect();
        ScreenOcclusion {
            width,
            height,
            texels,
        }
    }

    /// Bindings 26 ([`AMBIENT_OCCLUSION_PARAM`], which only the StencilDeferred passes read)
    /// and 27 (the texture).
    pub fn resources(&self) -> Vec<BoundResource> {
        let params = AMBIENT_OCCLUSION_PARAM
            .into_iter()
            .flat_map(f32::to_le_bytes)
            .collect();
        vec![
            BoundResource::new(0, 26, Resource::Uniform(params)),
            BoundResource::new(
                0,
                27,
                Resource::Texture2d {
                    format: wgpu::TextureFormat::R8Unorm,
                    width: self.width,
                    height: self.height,
                    data: self.texels.clone(),
                },
            ),
        ]
    }

    /// The occlusion factors at pixel `(x, y)`, as `GetScreenSpaceAmbientOcclusion` reads them.
    pub fn factor(&self, x: u32, y: u32) -> AmbientOcclusionFactor {
        let ssao = f32::from(self.texels[(y * self.width + x) as usize]) / 255.0;
        AmbientOcclusionFactor::screen_space(ssao, DIRECT_STRENGTH)
    }
}
