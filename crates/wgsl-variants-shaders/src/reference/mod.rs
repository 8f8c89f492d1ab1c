//! The CPU reference of the bundled deferred-shading library: the math of `docs/shading.md`
//! (which names the Unity and tutorial sources of each formula) in plain Rust with `glam`.
//!
//! It has two uses:
//!
//! - **Tests.** The GPU tests render the WGSL library's passes and compare every target texel
//!   with what this module computes for the same inputs, through the tolerances stated once in
//!   [`tolerance`]. The WGSL and this module are written independently from the same contract,
//!   so an agreement means both follow it.
//! - **Users decoding a G-buffer on the CPU.** [`gbuffer::GBufferTexel`] takes the raw texel
//!   values of RT0–RT3 and gives back diffuse colour, occlusion, specular colour, smoothness,
//!   the world normal and the light in RT3 (undoing the LDR `exp2(−c)` encoding).
//!
//! | module | contents |
//! |---|---|
//! | [`tolerance`] | the one place tolerances are stated, and the comparison functions |
//! | [`quantize`] | unorm and half-float conversions, `Rgb10a2Unorm` packing |
//! | [`ldr`] | RT3's LDR encoding `exp2(−c)`, its accumulation and decoding |
//! | [`gbuffer`] | normal encoding, the four targets, quantization and decoding |
//! | [`cube`] | the test scene's cube maps (one colour per face) |
//! | [`probe`] | reflection probes: box projection, mip, RGBM, blending, falloff, draw order |
//! | [`brdf`] | metallic workflow, ambient SH, indirect specular, direct light |
//! | [`light`] | per-pixel lights: the host API with its errors, falloff, cookies, spot cone, position from depth |
//! | [`shadow`] | shadows: the host API with its errors, spot and cube-face matrices, depth comparison, PCF footprints and weights, strength |
//! | [`lightmap`] | baked and realtime lightmaps: decoding (RGBM, HDR, dLDR, realtime), directional maps |
//! | [`shadow_fade`] | the realtime shadows' distance fade (view depth or a sphere) |
//! | [`cascades`] | a directional light's 1, 2 or 4 shadow cascades: fitting, the atlas, cascade selection by split depths or spheres |
//! | [`skybox`] | the background: Unity's `Skybox/Cubemap` (rotation, decode, tint, exposure) and the faces a filtered sample reads |
//! | [`surface`] | keywords, material and texel inputs, and each pass at one pixel |
//! | [`texel`] | nearest-texel addressing with repeat, and the texels an edge leaves undecided |
//! | [`vector`] | `reflect` and the view and reflection directions |
//! | [`urp`] | Unity URP's deferred G-buffer: octahedral normals, flags, sRGB, `Rg11b10Ufloat` |
//!
//! Everything is linear colour, `f32`, one pixel at a time. Special values (NaN, ±∞, zero
//! vectors) follow the contract where it says what happens, and otherwise are documented on
//! each function.
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::{shade_deferred, GBufferTexel, Geometry, Keywords, Material, Scene, Texels};
//! let kw = Keywords::from_names(&["_EMISSION_MAP"]).unwrap();
//! let material = Material { emission: Vec3::splat(2.0), ..Material::default() };
//! let texels = Texels { emission_map: Vec4::new(0.5, 1.0, 0.0, 1.0), ..Texels::default() };
//! let geometry = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::X };
//! let g = shade_deferred(&kw, &material, &texels, &geometry, &Scene::default()).unwrap();
//! let stored = GBufferTexel::quantize(&g, kw.hdr);
//! let c = stored.decode().c; // the light, decoded from the 10-bit exp2(−c) target
//! assert!((c - Vec3::new(1.0, 2.0, 0.0)).abs().max_element() < 0.01);
//! ```

pub mod brdf;
pub mod cascades;
pub mod cube;
pub mod gbuffer;
pub mod ldr;
pub mod light;
pub mod lightmap;
pub mod probe;
pub mod quantize;
pub mod shadow;
pub mod shadow_fade;
pub mod skybox;
pub mod surface;
pub mod texel;
pub mod tolerance;
pub mod urp;
pub mod vector;

pub use cube::CubeFaces;
pub use gbuffer::{DecodedSurface, GBuffer, GBufferTexel, Rt3Texel, decode_normal, encode_normal};
pub use ldr::{ldr_accumulate, ldr_decode, ldr_encode};
pub use light::{Light, LightError, LightParams, LightType};
pub use probe::Probe;
pub use surface::{
    Geometry, Keywords, Material, RenderingMode, Scene, SmoothnessSource, Surface, Texels,
    final_ldr, reflection_buffer, reflection_probe_pixel, reflections_add, shade_deferred,
    shade_forward, shade_forward_add,
};
