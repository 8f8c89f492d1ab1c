//! `standard/ShadowCaster`, every variant, per texel (docs/shading.md §11).
//!
//! Each variant renders the occluder scene of [`super::shadows`] (two cut-out quads) from the
//! check's lights: `SHADOWS_DEPTH` into the spot light's 64 × 64 `Depth16Unorm` map,
//! `SHADOWS_CUBE` into the point light's six 16 × 16 faces (`Rgba16Float` distance + depth).
//! Every texel is compared with the reference: along the ray through the texel's centre, the
//! nearest occluder point the caster keeps ([`wgsl_variants_shaders::reference::surface::surface`]'s
//! alpha against the cutoff) gives the depth ([`shadow_coords`]`.z`, 1 LSB of 16-bit unorm)
//! and, for a cube face, [`caster_distance`] (`F16_ULP` f16 steps); where the ray meets
//! nothing kept, the clear values (depth 1, distance 1). The GPU's value is compared with the
//! reference's value nearest to it over the texel's sub-pixel window
//! ([`wgsl_variants_shaders::reference::tolerance::SUBPIXEL_WINDOW`]): the rasterizer snaps vertices to
//! its sub-pixel grid, which on a surface seen at a grazing angle moves the depth by several
//! steps (NVIDIA's H200 showed two).
//!
//! A texel whose footprint straddles an occluder's edge or a hole's edge is decided by the
//! rasterizer's coverage rules, not by the math: the reference classifies the texel's centre
//! and four corners (which occluder is nearest and kept, if any) and skips the texel when they
//! disagree. The report's notes count those texels.

use std::time::Instant;

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::coverage::judge_every_variant;
use super::pass_check::{PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::shadows::{
    CUBE_SIZE, CUTOFF, MAP_SIZE, OCCLUDERS, occluder_texture, render_caster, rig_params,
};
use crate::{CheckError, GpuContext, GpuError};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::Light;
use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32;
use wgsl_variants_shaders::reference::shadow::{
    ShadowKeywords, caster_distance, cube_face_view_proj, shadow_coords,
};
use wgsl_variants_shaders::reference::surface::{Geometry, Keywords, Material, Texels, surface};
use wgsl_variants_shaders::reference::tolerance::{f16_within, unorm_within, window_offsets};

/// What one view of one variant rendered: depth codes and, for cube faces, the distances'
/// f16 bits.
type ViewImage = (Vec<u16>, Option<Vec<u16>>);

/// One map the caster renders: its view-projection, the light and its `1 / range`, the size.
struct View {
    name: String,
    view_proj: Mat4,
    light: Vec3,
    inv_range: f32,
    size: u32,
}

/// Whether the caster variant `keywords` keeps the occluder fragment at `uv`: the lit passes'
/// alpha (`tint.a · main_tex.a`, `tint.a` alone with `_SMOOTHNESS_ALBEDO`) against the cutoff
/// under `_RENDERING_CUTOUT`.
fn kept(kw: &Keywords, uv: Vec2) -> bool {
    let texture = occluder_texture();
    let texel = |c: f32, n: u32| ((c * n as f32).floor() as i64).clamp(0, i64::from(n) - 1) as u32;
    let main_tex = texture.get(texel(uv.x, texture.width), texel(uv.y, texture.height));
    let material = Material {
        tint: Vec4::ONE,
        cutoff: CUTOFF,
        ..Material::default()
    };
    let texels = Texels {
        main_tex,
        ..Texels::default()
    };
    let geometry = Geometry {
        world_position: Vec3::ZERO,
        normal: Vec3::Z,
        tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
    };
    !(kw.cutout() && surface(kw, &material, &texels, &geometry).alpha < material.cutoff)
}

/// The nearest kept occluder point along the ray through NDC `(x, y)` of `view_proj`, with
/// the occluder's index.
fn nearest_kept(kw: &Keywords, view_proj: Mat4, ndc: Vec2) -> Option<(usize, Vec3)> {
    let inverse = view_proj.inverse();
    let near = inverse.project_point3(ndc.extend(0.0));
    let far = inverse.project_point3(ndc.extend(1.0));
    OCCLUDERS
        .iter()
        .enumerate()
        .filter_map(|(i, &(lo, hi, z))| {
            let t = (z - near.z) / (far.z - near.z);
            if !(0.0..=1.0).contains(&t) {
                return None;
            }
            let p = near + (far - near) * t;
            let uv = (Vec2::new(p.x, p.y) - lo) / (hi - lo);
            let inside = (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y);
            (inside && kept(kw, uv)).then_some((i, p))
        })
        .min_by(|a, b| {
            let depth = |p: Vec3| shadow_coords(view_proj, p).z;
            depth(a.1).total_cmp(&depth(b.1))
        })
}

/// The texel's reference: `Some((occluder, point))` or `Some(None)` for the clear value where
/// the centre and the four corners agree on the nearest kept occluder, `None` for an edge
/// texel.
fn reference_texel(kw: &Keywords, view: &View, x: u32, y: u32) -> Option<Option<(usize, Vec3)>> {
    let n = view.size as f32;
    let ndc = |fx: f32, fy: f32| Vec2::new(fx / n * 2.0 - 1.0, 1.0 - fy / n * 2.0);
    let (fx, fy) = (x as f32, y as f32);
    let centre = nearest_kept(kw, view.view_proj, ndc(fx + 0.5, fy + 0.5));
    let class = centre.map(|(i, _)| i);
    let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];
    corners
        .iter()
        .all(|&(dx, dy)| {
            nearest_kept(kw, view.view_proj, ndc(fx + dx, fy + dy)).map(|(i, _)| i) == class
        })
        .then_some(centre)
}

/// The range of the texel's depth and distance over its sub-pixel window
/// ([`wgsl_variants_shaders::reference::tolerance::SUBPIXEL_WINDOW`]): the reference at
/// each of [`window_offsets`] that sees the centre's occluder (`(lo, hi)` twice).
fn window_ranges(kw: &Keywords, view: &View, x: u32, y: u32, occluder: usize) -> [(f32, f32); 2] {
    let n = view.size as f32;
    let mut ranges = [(f32::INFINITY, f32::NEG_INFINITY); 2];
    for (dx, dy) in window_offsets() {
        let (fx, fy) = (x as f32 + 0.5 + dx, y as f32 + 0.5 + dy);
        let ndc = Vec2::new(fx / n * 2.0 - 1.0, 1.0 - fy / n * 2.0);
        let Some((i, p)) = nearest_kept(kw, view.view_proj, ndc) else {
            continue;
        };
        if i != occluder {
            continue;
        }
        let values = [
            shadow_coords(view.view_proj, p).z,
            caster_distance(p, view.light, view.inv_range),
        ];
        for (range, v) in ranges.iter_mut().zip(values) {
            *range = (range.0.min(v), range.1.max(v));
        }
    }
    ranges
}

/// Checks every variant of `standard/ShadowCaster` over the occluder scene, lit by the check's
/// spot light (`SHADOWS_DEPTH`) and point light (`SHADOWS_CUBE`, all six faces).
///
/// # Errors
/// A GPU failure, a variant that does not compile, or a light the shadow API refuses.
pub fn check_shadow_caster(
    ctx: &GpuContext,
    lib: &Library,
    spot_light: &Light,
    point_light: &Light,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let pass = lib
        .pass("standard", "ShadowCaster")
        .map_err(|e| CheckError::lookup(String::from("standard/ShadowCaster"), e))?;
    let (spot, point) = rig_params(spot_light, point_light)?;
    let spot_view = View {
        name: "spot map".to_owned(),
        view_proj: spot.world_to_shadow,
        light: spot.light_position,
        inv_range: spot.inv_range,
        size: MAP_SIZE,
    };
    let cube_views: Vec<View> = (0..6)
        .map(|face| View {
            name: format!("cube face {face}"),
            view_proj: cube_face_view_proj(point.light_position, face, 1.0 / point.inv_range),
            light: point.light_position,
            inv_range: point.inv_range,
            size: CUBE_SIZE,
        })
        .collect();

    let mut report = PassReport::new("standard", "ShadowCaster");
    let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    let mut outputs: Vec<Vec<ViewImage>> = Vec::with_capacity(choices.len());
    let mut edges = 0usize;
    for choice in &choices {
        let names = choice.keywords(pass);
        let label = choice.label(pass);
        let (shadow, rest) = ShadowKeywords::split(&names);
        let kw = Keywords::from_names(&rest).map_err(|e| CheckError::UnknownToReference {
            variant: label.clone(),
            message: e.to_string(),
        })?;
        let views = if shadow.cube {
            cube_views.iter().collect::<Vec<_>>()
        } else {
            vec![&spot_view]
        };
        let mut images = Vec::with_capacity(views.len());
        for view in views {
            let image = render_caster(
                ctx,
                lib,
                &names,
                view.view_proj,
                view.light.extend(view.inv_range),
                view.size,
            )?;
            report.draws += 1;
            let distances: Option<Vec<u16>> = image.color.as_ref().map(|bytes| {
                bytes
                    .chunks_exact(8)
                    .map(|t| u16::from_le_bytes([t[0], t[1]]))
                    .collect()
            });
            for y in 0..view.size {
                for x in 0..view.size {
                    let i = (y * view.size + x) as usize;
                    let Some(point) = reference_texel(&kw, view, x, y) else {
                        edges += 1;
                        continue;
                    };
                    let depth = point.map_or(1.0, |(_, p)| shadow_coords(view.view_proj, p).z);
                    let distance =
                        point.map_or(1.0, |(_, p)| caster_distance(p, view.light, view.inv_range));
                    let [depth_range, distance_range] = match point {
                        Some((occluder, _)) => window_ranges(&kw, view, x, y, occluder),
                        None => [(1.0, 1.0); 2],
                    };
                    let got_depth = image.depth[i];
                    let got_distance = distances.as_ref().map(|d| d[i]);
                    // Each against the reference's value nearest to it over the window.
                    let depth_near =
                        (f32::from(got_depth) / 65535.0).clamp(depth_range.0, depth_range.1);
                    let ok = unorm_within(u32::from(got_depth), depth_near, 16)
                        && got_distance.is_none_or(|bits| {
                            let near =
                                f16_bits_to_f32(bits).clamp(distance_range.0, distance_range.1);
                            f16_within(bits, near)
                        });
                    if point.is_none() {
                        report.discarded_compared += 1;
                    }
                    report.record(ok, || Mismatch {
                        shader: "standard".to_owned(),
                        pass: "ShadowCaster".to_owned(),
                        keywords: label.clone(),
                        target: view.name.clone(),
                        pixel: [x, y],
                        expected: std::iter::once(depth)
                            .chain(got_distance.map(|_| distance))
                            .collect(),
                        got: std::iter::once(f32::from(got_depth) / 65535.0)
                            .chain(got_distance.map(f16_bits_to_f32))
                            .collect(),
                        got_raw: std::iter::once(u32::from(got_depth))
                            .chain(got_distance.map(u32::from))
                            .collect(),
                    });
                }
            }
            images.push((image.depth, distances));
        }
        outputs.push(images);
    }
    judge_every_variant(&mut report, pass, &choices, &outputs);
    report.notes.push(format!(
        "SHADOWS_DEPTH: the spot's {MAP_SIZE}x{MAP_SIZE} Depth16Unorm map; SHADOWS_CUBE: the \
         point light's six {CUBE_SIZE}x{CUBE_SIZE} faces (Rgba16Float distance and depth); \
         {edges} texels on an occluder's or a hole's edge left to the rasterizer"
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `standard/ShadowCaster` in the check's registry.
pub(crate) struct ShadowCaster;

/// The entry of `standard/ShadowCaster`: the rig's spot and point lights' maps.
pub(crate) static SHADOW_CASTER: ShadowCaster = ShadowCaster;

impl PassCheck for ShadowCaster {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("standard", "ShadowCaster")]
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        let rig = setup.rig;
        Ok(vec![check_shadow_caster(
            setup.ctx,
            setup.lib,
            &rig.spot_light,
            &rig.point_light,
        )?])
    }
}
