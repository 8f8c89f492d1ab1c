//! Forward = deferred, per pixel, for one light (docs/shading.md §10): the same surface lit by
//! `standard/ForwardAdd` and by `standard/Deferred` + `deferred_shading/Lighting`, both in HDR
//! (`Rgba16Float`), compared within
//! [`wgsl_variants_shaders::reference::tolerance::gbuffer_light_bound`] — the G-buffer's 8- and 10-bit
//! quantization propagated through the direct-light formula — plus 1 f16 step on each side.
//!
//! The deferred pass rebuilds positions from a depth buffer of the scene's own orthographic view
//! (depth 0.5 on the plane `z = 0`), so both passes light the same points; the lighting pass
//! draws onto an RT3 of zeros, so its output is the light alone.

use glam::{Mat4, Vec3, Vec4};

use super::camera::LightingCamera;
use super::compare::pixel;
use super::gbuffer::render_gbuffer;
use super::lighting::render_lighting;
use super::rig::LightRig;
use super::scene::TestScene;
use super::standard::{StandardOutput, standard_job};
use crate::{CheckError, ColorTarget, GpuContext, GpuError, TargetFormat, render};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::brdf::{Dots, diffuse_and_specular_from_metallic};
use wgsl_variants_shaders::reference::light::{Cookies, LightType};
use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32;
use wgsl_variants_shaders::reference::surface::{Keywords, surface};
use wgsl_variants_shaders::reference::tolerance::{f16_step, gbuffer_light_bound};

/// One pixel of the comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPair {
    /// Pixel `(x, y)`.
    pub pixel: [u32; 2],
    /// The ForwardAdd light (rgb, read back from `Rgba16Float`).
    pub forward: Vec3,
    /// The deferred light (rgb, read back from `Rgba16Float`).
    pub deferred: Vec3,
    /// The allowed difference per channel: the G-buffer bound plus one f16 step of each value.
    pub allowed: Vec3,
}

impl LightPair {
    /// Whether the two lights agree within `allowed` on every channel.
    pub fn agrees(&self) -> bool {
        ((self.forward - self.deferred).abs() - self.allowed).max_element() <= 0.0
    }
}

/// Lights the scene's surface with keywords `kw` (opaque; the light keyword is added) by the
/// rig's light of type `light`, forward and deferred, and returns every pixel's pair.
pub fn forward_vs_deferred(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    kw: &Keywords,
    light: LightType,
) -> Result<Vec<LightPair>, GpuError> {
    let (w, h) = (scene.width, scene.height);
    // Forward: ForwardAdd has neither the occlusion nor the emission map.
    let forward_kw = Keywords {
        occlusion_map: false,
        emission_map: false,
        hdr: false,
        reflection_buffers: false,
        ..*kw
    };
    let mut names = forward_kw.names();
    names.push(light.keyword());
    let variant = lib
        .variant("standard", "ForwardAdd", &names)
        .map_err(|e| CheckError::lookup(format!("standard/ForwardAdd {names:?}"), e))?;
    let mut job = standard_job(
        scene,
        &variant.label(),
        &lib.wgsl(&variant),
        StandardOutput::Forward,
    );
    job.targets = vec![ColorTarget::new(TargetFormat::Rgba16Float)];
    job.resources = scene.standard_resources();
    job.resources.extend(rig.resources(light));
    let forward = render(ctx, &job)?.remove(0);

    // Deferred: the HDR G-buffer, then the lighting pass onto zeros.
    let gbuffer_names = Keywords { hdr: true, ..*kw }.names();
    let gbuffer = render_gbuffer(ctx, lib, scene, &gbuffer_names)?;
    let mut lighting_names = vec![light.keyword(), "UNITY_HDR_ON"];
    lighting_names.extend(kw.brdf.keyword());
    let variant = lib
        .variant("deferred_shading", "Lighting", &lighting_names)
        .map_err(|e| CheckError::lookup("deferred_shading/Lighting", e))?;
    // The scene's orthographic view with depth = 0.5 + z / 20, so it can be inverted.
    let view_proj = scene.view_proj
        + Mat4::from_cols(
            Vec4::ZERO,
            Vec4::ZERO,
            Vec4::new(0.0, 0.0, 0.05, 0.0),
            Vec4::ZERO,
        );
    let depth = vec![0.5f32; (w * h) as usize];
    let camera = LightingCamera {
        view_proj,
        position: scene.scene.camera_position,
        depth: &depth,
    };
    let zeros = vec![0u8; (w * h * 8) as usize];
    let deferred = render_lighting(
        ctx,
        scene,
        rig,
        &gbuffer,
        &variant.label(),
        &lib.wgsl(&variant),
        rig.params(light),
        &camera,
        zeros,
    )?;

    let cookie = rig.cookie_2d();
    let cookies = Cookies {
        texture: &cookie,
        cube: &rig.cube,
    };
    let params = rig.params(light);
    let rgb = |bytes: &[u8], i: usize| {
        let raw = pixel(TargetFormat::Rgba16Float, bytes, i).0;
        Vec3::new(
            f16_bits_to_f32(raw[0] as u16),
            f16_bits_to_f32(raw[1] as u16),
            f16_bits_to_f32(raw[2] as u16),
        )
    };
    Ok(scene
        .pixels()
        .enumerate()
        .map(|(i, (x, y))| {
            // The forward pass's exact surface, for the bound.
            let geo = scene.geometry(x, y);
            let s = surface(&forward_kw, &scene.material, &scene.texels(x, y), &geo);
            let (diffuse, spec, _) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
            let p = geo.world_position;
            let (l, attenuation) = params.sample(light, p, Some(cookies));
            let v = (scene.scene.camera_position - p).normalize();
            let bound = gbuffer_light_bound(
                kw.brdf,
                diffuse,
                spec,
                s.smoothness,
                &Dots::new(s.normal, v, l),
                params.color * attenuation,
            );
            let (f, d) = (rgb(&forward, i), rgb(&deferred, i));
            let steps = Vec3::new(
                f16_step(f.x) + f16_step(d.x),
                f16_step(f.y) + f16_step(d.y),
                f16_step(f.z) + f16_step(d.z),
            );
            LightPair {
                pixel: [x, y],
                forward: f,
                deferred: d,
                allowed: bound + steps,
            }
        })
        .collect())
}
