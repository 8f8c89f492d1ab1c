//! `skybox/Cubemap` (docs/shading.md §15) against [`Skybox`]'s reference: the pass drawn full
//! screen through a wide camera whose view crosses five faces of the cube, its edges and a
//! corner, into `Rgba16Float` and `Rgba8Unorm`, every pixel compared.
//!
//! The cube has one encoded colour per face (RGBM-like, decoded with `(4, 2.2, _, 1)`), is
//! turned 30° and tinted, with exposure 1.25. A pixel's sample is its face's colour, or within
//! half a texel of an edge a mix of the faces there ([`seam_faces`]): the reference allows the
//! colour of the smallest to the largest of their texels (the colour increases in every texel
//! component), widened by the target's store.

use std::time::Instant;

use glam::{Mat4, Vec3, Vec4};

use super::camera::{deferred_camera, pixel_ray};
use super::compare::pixel;
use super::pass_check::{PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::scene::{CUBE_SIZE, cube_resource};
use crate::{BoundResource, ColorTarget, Draw, DrawPass, GpuContext, GpuError, Resource};
use crate::{TargetFormat, render_pass};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cube::CubeFaces;
use wgsl_variants_shaders::reference::light::{look_at_rh, perspective_rh};
use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
use wgsl_variants_shaders::reference::skybox::{Skybox, seam_faces};
use wgsl_variants_shaders::reference::tolerance::{f16_store_error, unorm_store_error};

/// A sky to draw: the material, its cube (one 8-bit encoded texel per face) and the camera.
#[derive(Clone, Debug, PartialEq)]
pub struct Sky {
    /// The `Skybox/Cubemap` material.
    pub skybox: Skybox,
    /// The cube's texels, one per face (wgpu's layer order), as `Rgba8Unorm` codes.
    pub faces: [[u8; 4]; 6],
}

impl Sky {
    /// The check's sky (see the module's documentation).
    pub fn check() -> Sky {
        Sky {
            skybox: Skybox {
                tint: Vec3::new(0.6, 0.5, 0.45),
                exposure: 1.25,
                rotation_degrees: 30.0,
                decode: Vec4::new(4.0, 2.2, 0.0, 1.0),
                ..Skybox::default()
            },
            faces: [
                [250, 120, 60, 200],
                [40, 90, 220, 150],
                [160, 200, 255, 230],
                [90, 70, 50, 110],
                [200, 230, 120, 180],
                [230, 60, 170, 90],
            ],
        }
    }

    /// The faces as the reference reads them (`code / 255`).
    pub fn cube(&self) -> CubeFaces {
        CubeFaces(
            self.faces
                .map(|c| Vec4::from_array(c.map(|x| unorm_to_f32(u32::from(x), 8)))),
        )
    }

    /// The pass's bindings: the camera (`DeferredCamera` of `view_proj` seen from `camera`),
    /// the `Skybox` uniform, the cube and a linear sampler.
    pub fn resources(&self, view_proj: Mat4, camera: Vec3) -> Vec<BoundResource> {
        let uniform = self
            .skybox
            .uniform()
            .into_iter()
            .flat_map(f32::to_le_bytes)
            .collect();
        vec![
            BoundResource::new(0, 0, Resource::Uniform(deferred_camera(view_proj, camera))),
            BoundResource::new(0, 1, Resource::Uniform(uniform)),
            BoundResource::new(0, 2, cube_resource(&self.cube())),
            BoundResource::new(0, 3, Resource::Sampler { nearest: false }),
        ]
    }

    /// The range of the sky's colour (before the target stores it) over the world directions
    /// `dirs` (a pixel's centre, or its sub-pixel window), as `reference` computes it: from
    /// the colour of the smallest to that of the largest texel of every face the directions'
    /// samples may read.
    pub fn range(&self, reference: &Skybox, dirs: &[Vec3]) -> (Vec3, Vec3) {
        let cube = self.cube();
        let (mut lo, mut hi) = (Vec4::splat(f32::INFINITY), Vec4::splat(f32::NEG_INFINITY));
        for &d in dirs {
            for f in seam_faces(reference.texcoord(d), CUBE_SIZE) {
                lo = lo.min(cube.0[f]);
                hi = hi.max(cube.0[f]);
            }
        }
        (reference.color(lo), reference.color(hi))
    }
}

/// The draw of `skybox/Cubemap` for `sky` seen through `view_proj` from `camera` (full
/// screen at the far plane; the caller sets the depth test).
pub fn sky_draw(lib: &Library, sky: &Sky, view_proj: Mat4, camera: Vec3) -> Result<Draw, GpuError> {
    let variant = lib
        .variant("skybox", "Cubemap", &[] as &[&str])
        .map_err(|e| crate::CheckError::lookup("skybox/Cubemap", e))?;
    let wgsl: std::sync::Arc<str> = std::sync::Arc::from(lib.wgsl(&variant));
    Ok(
        Draw::fullscreen(&variant.label(), &wgsl, "vs_main", "fs_main")
            .with_resources(sky.resources(view_proj, camera)),
    )
}

/// The world direction of the ray through the target point `(px, py)` (pixels) of a
/// `width × height` view: its far-plane point minus its near-plane point, in `f64`.
pub fn view_direction(view_proj: Mat4, size: (u32, u32), px: f64, py: f64) -> Vec3 {
    pixel_ray(view_proj, size, px, py).1.as_vec3()
}

/// The interval a target of `format` may hold for a value in `[lo, hi]` after one store.
pub fn stored_range(format: TargetFormat, lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
    if format == TargetFormat::Rgba16Float {
        let e = |v: Vec3| Vec3::from_array(v.abs().to_array().map(f16_store_error));
        (lo - e(lo), hi + e(hi))
    } else {
        let e = Vec3::splat(unorm_store_error(8));
        (
            lo.clamp(Vec3::ZERO, Vec3::ONE) - e,
            hi.clamp(Vec3::ZERO, Vec3::ONE) + e,
        )
    }
}

/// The check's view: 64 × 48 pixels, vertical field of view 1.9 rad, looking up and along
/// `(1, 0.45, 0.8)`, so that five faces, their edges and the corner `(+X, +Y, +Z)` (turned by
/// the sky's rotation) are in view.
fn check_view() -> (u32, u32, Mat4, Vec3) {
    let (w, h) = (64, 48);
    let eye = Vec3::new(0.0, 0.0, 0.0);
    let view_proj = perspective_rh(1.9, w as f32 / h as f32, 0.1, 10.0)
        * look_at_rh(eye, Vec3::new(1.0, 0.45, 0.8), Vec3::Y);
    (w, h, view_proj, eye)
}

/// Draws `sky` through the check's view into `format` and compares every pixel with
/// `reference`'s colour (the true sky's, or a planted fault's).
pub fn check_sky(
    ctx: &GpuContext,
    lib: &Library,
    sky: &Sky,
    reference: &Skybox,
    format: TargetFormat,
    report: &mut PassReport,
) -> Result<(), GpuError> {
    let (w, h, view_proj, eye) = check_view();
    let mut pass = DrawPass::new("skybox/Cubemap", w, h, vec![ColorTarget::new(format)]);
    pass.draws.push(sky_draw(lib, sky, view_proj, eye)?);
    let out = render_pass(ctx, &pass)?.targets.remove(0);
    report.draws += 1;
    let target = format!("out {format:?}");
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let dir = view_direction(view_proj, (w, h), f64::from(x) + 0.5, f64::from(y) + 0.5);
            let (lo, hi) = sky.range(reference, &[dir]);
            let (lo, hi) = stored_range(format, lo, hi);
            let (raw, got) = pixel(format, &out, i);
            let rgb = Vec3::new(got[0], got[1], got[2]);
            let ok = rgb.cmpge(lo).all() && rgb.cmple(hi).all() && got[3] == 1.0;
            report.record(ok, || Mismatch {
                shader: String::from("skybox"),
                pass: String::from("Cubemap"),
                keywords: String::from("{}"),
                target: target.clone(),
                pixel: [x, y],
                expected: ((lo + hi) * 0.5).extend(1.0).to_array().to_vec(),
                got: got.to_vec(),
                got_raw: raw.to_vec(),
            });
        }
    }
    Ok(())
}

/// `skybox/Cubemap` in the check's registry.
pub(crate) struct Cubemap;

/// The entry of `skybox/Cubemap`: HDR and LDR targets.
pub(crate) static CUBEMAP: Cubemap = Cubemap;

impl PassCheck for Cubemap {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("skybox", "Cubemap")]
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        let start = Instant::now();
        let mut report = PassReport::new("skybox", "Cubemap");
        let sky = Sky::check();
        for format in [TargetFormat::Rgba16Float, TargetFormat::Rgba8Unorm] {
            check_sky(setup.ctx, setup.lib, &sky, &sky.skybox, format, &mut report)?;
        }
        report.variants_run = 1;
        report.distinct_shaders = 1;
        report.notes.push(String::from(
            "one variant (no keywords) into Rgba16Float and Rgba8Unorm; five faces, their \
             edges and a corner in view",
        ));
        report.seconds = start.elapsed().as_secs_f64();
        Ok(vec![report])
    }
}
