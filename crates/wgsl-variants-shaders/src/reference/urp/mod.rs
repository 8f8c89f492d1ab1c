//! The CPU reference of Unity URP's deferred G-buffer (URP manual, "Deferred Rendering Path",
//! G-buffer layout; URP's shader library `UnityGBuffer.hlsl`): public, so a user can decode a
//! URP-layout G-buffer on the CPU. `docs/urp.md` states the layout and where each fact comes
//! from.
//!
//! | target | format | rgb | a |
//! |---|---|---|---|
//! | GBuffer0 | `Rgba8UnormSrgb` | base albedo ([`srgb`]) | material flags / 255 ([`flags`]) |
//! | GBuffer1 | `Rgba8Unorm` | specular colour, or reflectivity in r ([`workflow`]) | occlusion |
//! | GBuffer2 | `Rgba8Unorm` octahedral 8:8:8 with `_GBUFFER_NORMALS_OCT`, else `Rgba8Snorm` ([`normal`]) | normal | smoothness |
//! | GBuffer3 | `Rg11b10Ufloat` ([`ufloat`]) | emission + GI | – |
//!
//! | module | contents |
//! |---|---|
//! | [`normal`] | octahedral encode/decode, 12:12 → 8:8:8 packing, `Rgba8Snorm` normals |
//! | [`flags`] | the material-flags byte; decoding refuses reserved bits |
//! | [`srgb`] | the exact sRGB transfer function and an `Rgba8UnormSrgb` channel's byte |
//! | [`ufloat`] | `Rg11b10Ufloat`: 11-/10-bit unsigned floats, packing, decoding |
//! | [`workflow`] | metallic-workflow reflectivity (`kDielectricSpec`) and its inverse |
//! | [`gbuffer`] | what the `UniversalGBuffer` fragment writes per texel, per target |
//! | [`lighting`] | the `StencilDeferred` lighting passes: URP's attenuation and BRDF from the G-buffer |
//! | [`forward`] | the `UniversalForward` pass: the surface lit by the main light, the additional lights and GI in one pass |
//! | [`shadow`] | the ShadowCaster pass: URP's shadow bias and near-plane pancaking; the main light's map read |
//! | [`additional_shadow`] | additional-light realtime shadows: the atlas slice (a point light's cube face), the coordinate, the tap |
//! | [`cookie`] | light cookies: the main light's and the additional lights' atlas (spot perspective, point octahedral), the texel a nearest sampler reads, the formats |
//! | [`ambient_occlusion`] | screen-space ambient occlusion as the lighting reads it: the direct and indirect factors, the deferred path's GBuffer3 scale |
//! | [`accuracy`] | angular round-trip error of the normal encodings over a sphere of directions |
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::urp::{flags::MaterialFlags, normal, srgb, ufloat};
//! // Bytes of one texel as read back from the GPU.
//! let gbuffer0 = [188u8, 124, 0, 10];
//! let gbuffer2 = [0xFF, 0x91, 0xCF, 128];
//! let gbuffer3 = ufloat::pack_rg11b10(Vec3::new(1.0, 0.5, 0.25)).to_le_bytes();
//! let albedo = srgb::srgb8_to_linear_vec3([gbuffer0[0], gbuffer0[1], gbuffer0[2]]);
//! assert!((albedo - Vec3::new(0.5, 0.2, 0.0)).abs().max_element() < 4e-3); // 1 step of 8-bit sRGB
//! let flags = MaterialFlags::from_byte(gbuffer0[3]).unwrap();
//! assert!(flags.specular_setup && flags.specular_highlights_off);
//! let n = normal::decode_normal_oct([gbuffer2[0], gbuffer2[1], gbuffer2[2]]);
//! assert!((n - Vec3::new(0.6, 0.0, -0.8)).length() < 1e-3);
//! let gi = ufloat::unpack_rg11b10(u32::from_le_bytes(gbuffer3));
//! assert_eq!(gi, Vec3::new(1.0, 0.5, 0.25));
//! ```

pub mod accuracy;
pub mod additional_shadow;
pub mod ambient_occlusion;
pub mod cookie;
pub mod flags;
pub mod forward;
pub mod gbuffer;
pub mod lighting;
pub mod normal;
pub mod shadow;
pub mod srgb;
pub mod ufloat;
pub mod workflow;
