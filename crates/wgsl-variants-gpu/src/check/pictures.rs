//! The test scene as pictures: the G-buffer's contents, the light in RT3 and the final frame,
//! as 8-bit RGBA images (the `render` command writes them as PNG files).

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::compare::pixel;
use super::deferred::{final_pass, render_chain};
use super::frame::{FrameScene, reference_rgb, render_deferred, render_forward, render_shadows};
use super::gbuffer::render_gbuffer;
use super::rig::LightRig;
use super::scene::TestScene;
use super::standard::{StandardOutput, standard_job};
use super::urp::{DEFAULT_SEED, UrpColorPass, UrpScene};
use super::urp_forward::UrpForwardScene;
use super::urp_frame::{self, UrpFrame};
use super::urp_lighting::{light_gbuffer, render_urp_gbuffer};
use crate::{CheckError, GpuContext, GpuError, TargetFormat, render};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::ldr::ldr_decode;
use wgsl_variants_shaders::reference::quantize::unorm;
use wgsl_variants_shaders::reference::surface::Keywords;
use wgsl_variants_shaders::reference::urp::flags::{
    RECEIVE_SHADOWS_OFF, SPECULAR_HIGHLIGHTS_OFF, SPECULAR_SETUP, SUBTRACTIVE_MIXED_LIGHTING,
};
use wgsl_variants_shaders::reference::urp::normal::{
    decode_normal_oct, decode_normal_snorm8, snorm8_to_f32,
};

/// The keyword set the pictures use by default: `standard/Deferred` with every map on and the
/// per-pixel reflection probes, LDR (so the final frame goes through the final pass); its
/// names are `DEFAULT_KEYWORDS.names()`.
pub const DEFAULT_KEYWORDS: Keywords = super::gbuffer::CHAIN_INPUTS[0];

/// One picture: a name (the file stem) and 8-bit RGBA pixels, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    /// File stem, e.g. `albedo`.
    pub name: String,
    /// What it shows.
    pub description: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA bytes.
    pub rgba: Vec<u8>,
}

impl Picture {
    /// A picture from a per-pixel colour function (components clamped to [0, 1]).
    fn from_fn(
        name: &str,
        description: &str,
        width: u32,
        height: u32,
        mut colour: impl FnMut(usize) -> [f32; 4],
    ) -> Picture {
        let rgba = (0..(width * height) as usize)
            .flat_map(|i| colour(i).map(|c| unorm(c, 8) as u8))
            .collect();
        Picture {
            name: name.to_owned(),
            description: description.to_owned(),
            width,
            height,
            rgba,
        }
    }

    /// Writes the picture as `DIR/NAME.png`, each pixel scaled up to `scale × scale` pixels
    /// (nearest neighbour, so every stored texel stays visible). Returns the path.
    pub fn write_png(&self, dir: &Path, scale: u32) -> Result<PathBuf, image::ImageError> {
        let scale = scale.max(1);
        let (w, h) = (self.width * scale, self.height * scale);
        let mut out = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h {
            for x in 0..w {
                let i = (((y / scale) * self.width + x / scale) * 4) as usize;
                out.extend_from_slice(&self.rgba[i..i + 4]);
            }
        }
        // The buffer is made above to hold exactly w × h pixels.
        let image = image::RgbaImage::from_raw(w, h, out).expect("w × h RGBA pixels");
        let path = dir.join(format!("{}.png", self.name));
        image.save_with_format(&path, image::ImageFormat::Png)?;
        Ok(path)
    }
}

/// The frame of [`super::frame`] as pictures: the CPU reference, forward and deferred in LDR,
/// their difference (×16), and the HDR renders (clamped to 1) with their difference (×16).
pub fn frame_pictures(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
) -> Result<Vec<Picture>, GpuError> {
    let (w, h) = (frame.width, frame.height);
    let shadows = render_shadows(ctx, lib, frame)?;
    let reference: Vec<Vec3> = frame
        .pixels()
        .map(|(x, y)| reference_rgb(frame, &shadows, x, y).unwrap_or(Vec3::ZERO))
        .collect();
    let mut pictures = vec![Picture::from_fn(
        "frame_reference",
        "the CPU reference: each pixel's ray, lit by the forward formulas",
        w,
        h,
        |i| rgb(reference[i].extend(1.0).to_array()),
    )];
    for hdr in [false, true] {
        let forward = render_forward(ctx, lib, frame, &shadows, hdr)?;
        let deferred = render_deferred(ctx, lib, frame, &shadows, hdr)?;
        let mode = if hdr { "hdr" } else { "ldr" };
        let clamp = if hdr { " (clamped to 1)" } else { "" };
        pictures.push(Picture::from_fn(
            &format!("frame_forward_{mode}"),
            &format!(
                "forward: ForwardBase + ForwardAdd per light, {} draws{clamp}",
                forward.draws
            ),
            w,
            h,
            |i| rgb(forward.rgb(i).extend(1.0).to_array()),
        ));
        pictures.push(Picture::from_fn(
            &format!("frame_deferred_{mode}"),
            &format!(
                "deferred: G-buffer + Lighting per light{}, {} draws{clamp}",
                if hdr { "" } else { " + final" },
                deferred.draws
            ),
            w,
            h,
            |i| rgb(deferred.rgb(i).extend(1.0).to_array()),
        ));
        pictures.push(Picture::from_fn(
            &format!("frame_difference_{mode}"),
            "|forward − deferred| × 16",
            w,
            h,
            |i| {
                rgb(((forward.rgb(i) - deferred.rgb(i)).abs() * 16.0)
                    .extend(1.0)
                    .to_array())
            },
        ));
    }
    Ok(pictures)
}

/// URP's frame ([`super::urp_frame`]) as pictures: the CPU reference, forward and deferred
/// (HDR, clamped to 1) and their difference (×16).
pub fn urp_frame_pictures(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<Vec<Picture>, GpuError> {
    let g = &frame.geometry;
    let (w, h) = (g.width, g.height);
    let shadows = urp_frame::render_urp_shadows(ctx, lib, frame)?;
    let reference = g
        .pixels()
        .map(|(x, y)| Ok(urp_frame::reference_rgb(frame, &shadows, x, y)?.unwrap_or(Vec3::ZERO)))
        .collect::<Result<Vec<Vec3>, GpuError>>()?;
    let forward = urp_frame::render_urp_forward(ctx, lib, frame, &shadows)?;
    let deferred = urp_frame::render_urp_deferred(ctx, lib, frame, &shadows)?;
    let read = |bytes: &[u8], i: usize| {
        let c = TargetFormat::Rg11b10Ufloat.decode_pixel_f32(&bytes[i * 4..i * 4 + 4]);
        Vec3::new(c[0], c[1], c[2])
    };
    Ok(vec![
        Picture::from_fn(
            "urp_frame_reference",
            "the CPU reference: each pixel's ray, lit by URP's forward formulas (clamped to 1)",
            w,
            h,
            |i| rgb(reference[i].extend(1.0).to_array()),
        ),
        Picture::from_fn(
            "urp_frame_forward",
            &format!(
                "forward: UniversalForward per object, {} draws (clamped to 1)",
                forward.draws
            ),
            w,
            h,
            |i| rgb(read(&forward.bytes, i).extend(1.0).to_array()),
        ),
        Picture::from_fn(
            "urp_frame_deferred",
            &format!(
                "deferred: UniversalGBuffer + StencilDeferred per light, {} draws (clamped to 1)",
                deferred.draws
            ),
            w,
            h,
            |i| rgb(read(&deferred.lit, i).extend(1.0).to_array()),
        ),
        Picture::from_fn(
            "urp_frame_difference",
            "|forward − deferred| × 16",
            w,
            h,
            |i| {
                rgb(
                    ((read(&forward.bytes, i) - read(&deferred.lit, i)).abs() * 16.0)
                        .extend(1.0)
                        .to_array(),
                )
            },
        ),
    ])
}

/// A picture written as a PNG file (one entry of what `render --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct WrittenPicture {
    /// The picture's name.
    pub name: String,
    /// What it shows.
    pub description: String,
    /// The file written.
    pub path: String,
}

/// Writes every picture into `dir` (which must exist) with [`Picture::write_png`].
pub fn write_pngs(
    pictures: &[Picture],
    dir: &Path,
    scale: u32,
) -> Result<Vec<WrittenPicture>, image::ImageError> {
    pictures
        .iter()
        .map(|p| {
            Ok(WrittenPicture {
                name: p.name.clone(),
                description: p.description.clone(),
                path: p.write_png(dir, scale)?.display().to_string(),
            })
        })
        .collect()
}

/// A colour read from a target, as floats.
fn read(format: TargetFormat, bytes: &[u8], i: usize) -> [f32; 4] {
    pixel(format, bytes, i).1
}

/// Opaque rgb.
fn rgb(c: [f32; 4]) -> [f32; 4] {
    [c[0], c[1], c[2], 1.0]
}

/// A grey value.
fn grey(v: f32) -> [f32; 4] {
    [v, v, v, 1.0]
}

/// RT3's light as a colour: decoded from `exp2(−c)` (LDR) or as stored (HDR), clamped.
fn light(format: TargetFormat, bytes: &[u8], i: usize) -> [f32; 4] {
    let c = read(format, bytes, i);
    let v = Vec3::new(c[0], c[1], c[2]);
    let v = if format == TargetFormat::Rgba16Float {
        v
    } else {
        ldr_decode(v)
    };
    rgb(v.extend(1.0).to_array())
}

/// Renders the pictures of `shader/pass` with `keywords` on the test scene.
///
/// `standard/Deferred`: `albedo` (RT0 rgb), `occlusion` (RT0 a), `specular` (RT1 rgb),
/// `smoothness` (RT1 a), `normal` (RT2 rgb), `emission` (the light the G-buffer pass wrote to
/// RT3, decoded), `shadowmask` (RT4 rgb, with `SHADOWS_SHADOWMASK`), and `final`: with `UNITY_ENABLE_REFLECTION_BUFFERS` after the reflection
/// probes (also `reflections`, the reflection buffer) and the add pass, then (LDR) the final
/// pass; without, the final pass (LDR) or RT3 (HDR) directly. `standard/ForwardBase`: `final`
/// (rgb) and `alpha`. `universal_lit/UniversalGBuffer`: URP's G-buffer views and its lighting
/// (see `urp_pictures`). `universal_lit/UniversalForward`: `lit`, the camera target of
/// [`super::urp_forward`]'s scene.
pub fn render_pictures(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    shader: &str,
    pass: &str,
    keywords: &[&str],
) -> Result<Vec<Picture>, GpuError> {
    let (w, h) = (scene.width, scene.height);
    match (shader, pass) {
        ("standard", "Deferred") => {
            let g = render_gbuffer(ctx, lib, scene, keywords)?;
            let rt3_format = g.rt3_format();
            let t = &g.targets;
            let rgba8 = TargetFormat::Rgba8Unorm;
            let mut pictures = vec![
                Picture::from_fn("albedo", "RT0 rgb: diffuse colour", w, h, |i| {
                    rgb(read(rgba8, &t[0], i))
                }),
                Picture::from_fn("occlusion", "RT0 a: occlusion", w, h, |i| {
                    grey(read(rgba8, &t[0], i)[3])
                }),
                Picture::from_fn("specular", "RT1 rgb: specular colour", w, h, |i| {
                    rgb(read(rgba8, &t[1], i))
                }),
                Picture::from_fn("smoothness", "RT1 a: smoothness", w, h, |i| {
                    grey(read(rgba8, &t[1], i)[3])
                }),
                Picture::from_fn("normal", "RT2 rgb: world normal · 0.5 + 0.5", w, h, |i| {
                    rgb(read(TargetFormat::Rgb10a2Unorm, &t[2], i))
                }),
                Picture::from_fn(
                    "emission",
                    "RT3 decoded: emission + ambient (+ forward probes) written by the G-buffer pass",
                    w,
                    h,
                    |i| light(rt3_format, &t[3], i),
                ),
            ];
            if let Some(rt4) = t.get(4) {
                pictures.push(Picture::from_fn(
                    "shadowmask",
                    "RT4 rgba: baked occlusion of four lights (SHADOWS_SHADOWMASK; rgb shown)",
                    w,
                    h,
                    |i| rgb(read(rgba8, rt4, i)),
                ));
            }
            let (frame, refl) = if keywords.contains(&"UNITY_ENABLE_REFLECTION_BUFFERS") {
                let chain = render_chain(ctx, lib, scene, &g)?;
                let frame = match &chain.frame {
                    Some(frame) => frame.clone(),
                    None => hdr_frame(&chain.rt3, w, h),
                };
                (frame, Some(chain.reflections))
            } else if g.hdr {
                (hdr_frame(&g.targets[3], w, h), None)
            } else {
                (final_pass(ctx, lib, &g.targets[3], w, h)?, None)
            };
            if let Some(refl) = refl {
                pictures.push(Picture::from_fn(
                    "reflections",
                    "the reflection buffer after every probe",
                    w,
                    h,
                    |i| rgb(read(TargetFormat::Rgba16Float, &refl, i)),
                ));
            }
            pictures.push(Picture::from_fn("final", "the final frame", w, h, |i| {
                rgb(read(rgba8, &frame, i))
            }));
            Ok(pictures)
        }
        ("standard", "ForwardBase") => {
            let variant = lib
                .variant(shader, pass, keywords)
                .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))?;
            let mut job = standard_job(
                scene,
                &variant.label(),
                &lib.wgsl(&variant),
                StandardOutput::Forward,
            );
            job.resources = scene.standard_resources();
            if keywords.contains(&"SHADOWS_SCREEN") {
                // The main light's screen-space shadow: the check's directional mask.
                let mut rig = LightRig::new(scene);
                rig.render_screen_shadows(ctx, lib, scene)?;
                job.resources.extend(rig.main_light_shadow());
            }
            let out = render(ctx, &job)?.remove(0);
            let rgba8 = TargetFormat::Rgba8Unorm;
            Ok(vec![
                Picture::from_fn("final", "the forward base pass's colour", w, h, |i| {
                    rgb(read(rgba8, &out, i))
                }),
                Picture::from_fn("alpha", "the forward base pass's alpha", w, h, |i| {
                    grey(read(rgba8, &out, i)[3])
                }),
            ])
        }
        ("universal_lit", "UniversalGBuffer") => urp_pictures(ctx, lib, scene, keywords),
        ("universal_lit", "UniversalForward") => {
            let variant = lib
                .variant(shader, pass, keywords)
                .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))?;
            let mut rig = LightRig::new(scene);
            rig.render_screen_shadows(ctx, lib, scene)?;
            let forward =
                UrpForwardScene::new(ctx, lib, &UrpScene::new(scene, DEFAULT_SEED), &rig)?;
            let mut job = forward.job(&variant.label(), &lib.wgsl(&variant), &variant.keywords());
            job.resources = forward.resources();
            let out = render(ctx, &job)?.remove(0);
            Ok(vec![Picture::from_fn(
                "lit",
                "the camera target: GI, the main light (with its shadow), the additional lights and the emission (clamped)",
                w,
                h,
                |i| rgb(read(TargetFormat::Rg11b10Ufloat, &out, i)),
            )])
        }
        _ => Err(GpuError::from(CheckError::NoPictures(format!(
            "{shader}/{pass}"
        )))),
    }
}

/// URP's G-buffer views of a `UniversalGBuffer` variant on the URP scene, and the lighting:
/// `albedo` (GBuffer0 rgb as stored, sRGB), `flags` (GBuffer0 a: r ReceiveShadowsOff, g
/// SpecularHighlightsOff, b SpecularSetup, all three at half with SubtractiveMixedLighting),
/// `specular` (GBuffer1 rgb), `occlusion` (GBuffer1 a), `normal` (GBuffer2 decoded, `n · ½ + ½`),
/// `smoothness` (GBuffer2 a), `gi` (GBuffer3: emission + GI) and `lighting` (GBuffer3 after
/// `stencil_deferred`'s main light with its shadow, a point and a spot light).
fn urp_pictures(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    keywords: &[&str],
) -> Result<Vec<Picture>, GpuError> {
    let (w, h) = (scene.width, scene.height);
    let urp = UrpScene::new(scene, DEFAULT_SEED);
    let g = render_urp_gbuffer(ctx, lib, &urp, keywords)?;
    let mut rig = LightRig::new(scene);
    rig.render_screen_shadows(ctx, lib, scene)?;
    let lit = light_gbuffer(ctx, lib, scene, &rig, &g)?;
    let t = &g.targets;
    let rgba8 = TargetFormat::Rgba8Unorm;
    let texel = |t: &[u8], i: usize| [t[i * 4], t[i * 4 + 1], t[i * 4 + 2], t[i * 4 + 3]];
    let normal = |i: usize| {
        let b = texel(&t[2], i);
        let n = if g.oct {
            decode_normal_oct([b[0], b[1], b[2]])
        } else {
            decode_normal_snorm8([b[0] as i8, b[1] as i8, b[2] as i8])
        };
        rgb((n * 0.5 + Vec3::splat(0.5)).extend(1.0).to_array())
    };
    let smoothness = |i: usize| {
        let a = texel(&t[2], i)[3];
        grey(if g.oct {
            f32::from(a) / 255.0
        } else {
            snorm8_to_f32(a as i8)
        })
    };
    let flags = |i: usize| {
        let byte = texel(&t[0], i)[3];
        let bit = |b: u8| f32::from(u8::from(byte & b != 0));
        let scale = if byte & SUBTRACTIVE_MIXED_LIGHTING != 0 {
            0.5
        } else {
            1.0
        };
        [
            bit(RECEIVE_SHADOWS_OFF) * scale,
            bit(SPECULAR_HIGHLIGHTS_OFF) * scale,
            bit(SPECULAR_SETUP) * scale,
            1.0,
        ]
    };
    let ufloat = |bytes: &[u8], i: usize| rgb(read(TargetFormat::Rg11b10Ufloat, bytes, i));
    Ok(vec![
        Picture::from_fn(
            "albedo",
            "GBuffer0 rgb: base albedo (sRGB as stored)",
            w,
            h,
            |i| rgb(read(rgba8, &t[0], i)),
        ),
        Picture::from_fn(
            "flags",
            "GBuffer0 a: material flags (r ReceiveShadowsOff, g SpecularHighlightsOff, b SpecularSetup; half with SubtractiveMixedLighting)",
            w,
            h,
            flags,
        ),
        Picture::from_fn(
            "specular",
            "GBuffer1 rgb: specular colour or reflectivity",
            w,
            h,
            |i| rgb(read(rgba8, &t[1], i)),
        ),
        Picture::from_fn("occlusion", "GBuffer1 a: occlusion", w, h, |i| {
            grey(read(rgba8, &t[1], i)[3])
        }),
        Picture::from_fn(
            "normal",
            "GBuffer2 rgb decoded: world normal · 0.5 + 0.5",
            w,
            h,
            normal,
        ),
        Picture::from_fn("smoothness", "GBuffer2 a: smoothness", w, h, smoothness),
        Picture::from_fn("gi", "GBuffer3: emission + baked GI (clamped)", w, h, |i| {
            ufloat(&t[3], i)
        }),
        Picture::from_fn(
            "lighting",
            "GBuffer3 after stencil_deferred: the main light (soft shadow), a point and a spot light (clamped)",
            w,
            h,
            |i| ufloat(&lit, i),
        ),
    ])
}

/// An HDR RT3 as an `Rgba8Unorm` frame (clamped, as an 8-bit target would store it).
fn hdr_frame(rt3: &[u8], w: u32, h: u32) -> Vec<u8> {
    (0..(w * h) as usize)
        .flat_map(|i| rgb(read(TargetFormat::Rgba16Float, rt3, i)).map(|c| unorm(c, 8) as u8))
        .collect()
}
