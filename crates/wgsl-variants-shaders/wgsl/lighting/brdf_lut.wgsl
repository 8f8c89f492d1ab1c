// lighting/brdf_lut: the lookup table of the Standard BRDF's lowest tier (UNITY_PBS_USE_BRDF3),
// Unity's unity_NHxRoughness: a normalized Blinn-Phong lobe around the mirrored view direction,
// indexed by x = (r·l)⁴ and perceptual roughness, scaled by 1/16 (docs/shading.md §5; the host
// generates it with wgsl_variants_shaders::brdf_lut). Bound where a pass evaluates the direct
// term with UNITY_PBS_USE_BRDF3:
//
//   group 0: 17 brdf_lut (texture_2d<f32>, R16Float, 256 × 64; read with textureLoad)
//
// Read with textureLoad and interpolated here in f32, not through a filtering sampler: the
// sampler's sub-texel precision is implementation-defined, so the same table would give
// different highlights on different GPUs.
//
// Provides:
//   const BRDF_LUT_RANGE: f32 = 16.0       Unity's LUT_RANGE
//   fn brdf_lut_sample(x: f32, pr: f32) -> f32
//       t = clamp((x, pr) · size - 0.5, 0, size - 1); the texels at floor(t) and
//       min(floor(t) + 1, size - 1), mixed by fract(t) along x, then along pr

const BRDF_LUT_RANGE: f32 = 16.0;

@group(0) @binding(17) var brdf_lut: texture_2d<f32>;

fn brdf_lut_sample(x: f32, pr: f32) -> f32 {
    let size = vec2i(textureDimensions(brdf_lut));
    let t = clamp(vec2f(x, pr) * vec2f(size) - 0.5, vec2f(0.0), vec2f(size - 1));
    let i = floor(t);
    let f = t - i;
    let lo = vec2i(i);
    let hi = min(lo + 1, size - 1);
    let a = textureLoad(brdf_lut, lo, 0).r;
    let b = textureLoad(brdf_lut, vec2i(hi.x, lo.y), 0).r;
    let c = textureLoad(brdf_lut, vec2i(lo.x, hi.y), 0).r;
    let d = textureLoad(brdf_lut, hi, 0).r;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}
