//! The test scene as pictures: the G-buffer's contents, the light in RT3 and the final frame,
//! as 8-bit RGBA images (the `render` command writes them as PNG files).

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::compare::pixel;
use super::deferred::{final_pass, render_chain, render_gbuffer};
use super::passes::standard_job;
use super::scene::TestScene;
use crate::{CheckError, GpuContext, GpuError, TargetFormat, render};
use wgsl_variants::Library;
use wgsl_variants::reference::ldr::ldr_decode;
use wgsl_variants::reference::quantize::unorm;
use wgsl_variants::reference::surface::Keywords;

/// The keyword set the pictures use by default: `standard/Deferred` with every map on and the
/// per-pixel reflection probes, LDR (so the final frame goes through the final pass); its
/// names are `DEFAULT_KEYWORDS.names()`.
pub const DEFAULT_KEYWORDS: Keywords = super::deferred::CHAIN_INPUTS[0];

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
/// RT3, decoded), and `final`: with `UNITY_ENABLE_REFLECTION_BUFFERS` after the reflection
/// probes (also `reflections`, the reflection buffer) and the add pass, then (LDR) the final
/// pass; without, the final pass (LDR) or RT3 (HDR) directly. `standard/ForwardBase`: `final`
/// (rgb) and `alpha`.
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
            let mut job = standard_job(scene, &variant.label(), &lib.wgsl(&variant), false, false);
            job.resources = scene.standard_resources();
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
        _ => Err(GpuError::from(CheckError::NoPictures(format!(
            "{shader}/{pass}"
        )))),
    }
}

/// An HDR RT3 as an `Rgba8Unorm` frame (clamped, as an 8-bit target would store it).
fn hdr_frame(rt3: &[u8], w: u32, h: u32) -> Vec<u8> {
    (0..(w * h) as usize)
        .flat_map(|i| rgb(read(TargetFormat::Rgba16Float, rt3, i)).map(|c| unorm(c, 8) as u8))
        .collect()
}
