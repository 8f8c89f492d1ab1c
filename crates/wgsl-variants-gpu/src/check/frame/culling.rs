//! The light culling mask through the deferred path's stencil (docs/shading.md §12).
//!
//! A light lights only the objects whose layer its culling mask holds
//! ([`FrameLight::lights`]). Forward, that is a draw left out. Deferred, the Lighting pass
//! cannot tell objects apart, so the G-buffer pass marks each pixel with a stencil bit for the
//! layer of the object it keeps, and each light's draw passes only where none of the bits of
//! the layers it leaves out is set. The Unity Manual's Deferred Shading rendering path allows
//! at most four such layers ("28 of the 32 layers must be set"), which is four stencil bits.

use super::scene::{FrameLight, FrameObject, FrameScene};
use crate::{CheckError, GpuError};

/// The most layers the lights together may leave out in the deferred path.
pub const MAX_CULLED_LAYERS: usize = 4;

/// The stencil bit a light volume's pre-pass sets where the surface lies in front of the
/// volume, and the light's draw clears again (above the four layer bits).
pub const VOLUME_STENCIL_BIT: u32 = 1 << 7;

/// Which stencil bit stands for which culled layer: bit `i` for the `i`-th layer (ascending)
/// that some light's culling mask leaves out.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LayerStencil {
    layers: Vec<u32>,
}

impl LayerStencil {
    /// The bits of `frame`'s lights.
    ///
    /// # Errors
    /// [`GpuError::Check`] with [`CheckError::TooManyCulledLayers`] when the masks leave out more than
    /// [`MAX_CULLED_LAYERS`] layers.
    ///
    /// ```
    /// use wgsl_variants_gpu::check::frame::{FrameScene, LAYER_GLASS, LAYER_SHELTERED, LayerStencil};
    /// let frame = FrameScene::new();
    /// let stencil = LayerStencil::new(&frame).unwrap();
    /// assert_eq!(stencil.layers(), [LAYER_SHELTERED, LAYER_GLASS]);
    /// // The cool point light leaves out the glowing sphere's layer: bit 0.
    /// assert_eq!(stencil.light_bits(&frame.lights[2]), 0b01);
    /// assert_eq!(stencil.object_bits(&frame.objects[2]), 0b01);
    /// assert_eq!(stencil.object_bits(&frame.objects[0]), 0);
    /// // The main light leaves it out too.
    /// assert_eq!(stencil.mask_bits(frame.main_culling_mask), 0b01);
    /// ```
    pub fn new(frame: &FrameScene) -> Result<LayerStencil, GpuError> {
        let masks = frame.lights.iter().map(|l| l.culling_mask);
        let culled = masks.fold(!frame.main_culling_mask, |c, m| c | !m);
        let layers: Vec<u32> = (0..32).filter(|l| culled & (1 << l) != 0).collect();
        if layers.len() > MAX_CULLED_LAYERS {
            return Err(CheckError::TooManyCulledLayers { layers }.into());
        }
        Ok(LayerStencil { layers })
    }

    /// The culled layers, ascending: bit `i` stands for `layers()[i]`.
    pub fn layers(&self) -> &[u32] {
        &self.layers
    }

    /// Whether any light leaves any layer out (otherwise no draw needs the stencil).
    pub fn any(&self) -> bool {
        !self.layers.is_empty()
    }

    /// The bit the G-buffer pass marks `object`'s pixels with (0: a layer no light leaves out).
    pub fn object_bits(&self, object: &FrameObject) -> u32 {
        self.bits(|layer| layer == object.layer)
    }

    /// The bits of the layers `light` leaves out: its draw passes where none is set.
    pub fn light_bits(&self, light: &FrameLight) -> u32 {
        self.mask_bits(light.culling_mask)
    }

    /// The bits of the layers a light with `culling_mask` leaves out (the main light's is
    /// [`FrameScene::main_culling_mask`]).
    pub fn mask_bits(&self, culling_mask: u32) -> u32 {
        self.bits(|layer| culling_mask & (1 << layer) == 0)
    }

    fn bits(&self, take: impl Fn(u32) -> bool) -> u32 {
        (0u32..)
            .zip(&self.layers)
            .filter(|(_, layer)| take(**layer))
            .fold(0, |bits, (i, _)| bits | (1 << i))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn five_culled_layers_are_refused_four_are_not() {
        let mut frame = FrameScene::new();
        for light in &mut frame.lights {
            light.culling_mask = u32::MAX;
        }
        frame.main_culling_mask = u32::MAX;
        frame.lights[0].culling_mask = !0b1111;
        frame.lights[1].culling_mask = !0b0110;
        let four = LayerStencil::new(&frame).expect("four layers");
        assert_eq!(four.layers(), [0, 1, 2, 3]);
        assert_eq!(four.light_bits(&frame.lights[1]), 0b0110);
        frame.main_culling_mask = !(1 << 20);
        match LayerStencil::new(&frame) {
            Err(GpuError::Check(e)) => match *e {
                CheckError::TooManyCulledLayers { layers } => {
                    assert_eq!(layers, [0, 1, 2, 3, 20]);
                }
                other => panic!("expected TooManyCulledLayers, got {other:?}"),
            },
            other => panic!("expected TooManyCulledLayers, got {other:?}"),
        }
    }
}
