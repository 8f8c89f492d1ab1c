//! `universal_lit/UniversalGBuffer` on the test scene: every selected variant rendered into
//! the targets its keywords give ([`crate::urp_gbuffer_formats`]), read back and compared
//! texel by texel with [`wgsl_variants_shaders::reference::urp::gbuffer`] through
//! [`wgsl_variants_shaders::reference::tolerance::urp_texel_within`]; then, per keyword, whether it
//! changed a texel.
//!
//! The scene is [`TestScene`]'s quad, material maps, camera, ambient light, main light and
//! first probe cube (the environment), plus what URP adds: a 16 × 16 `Rgba16Float` lightmap and
//! an `Rgba8Unorm` shadowmask read at `uv · (½, ½) + (¼, ¼)` through a second UV set (each
//! pixel lands ¼ texel or more from a texel edge, so nearest sampling is exact), shadow
//! attenuation, subtractive shadow colour, glossy environment colour, probe occlusion and a
//! rendering-layer mask with layer 31 on.
//!
//! Keyword coverage. Over the full space (`--full`), each keyword is judged on the variant
//! pairs that differ only in it, as for the standard passes. Over a covering set, such pairs
//! are rare, so the check adds them: for each keyword, the first covering variant with the
//! keyword on whose reference changes when the keyword is turned off gets that partner
//! rendered (and compared with its own reference, like every other variant); the keyword is
//! proven when the two GPU renderings differ in at least one texel.

use std::collections::HashMap;
use std::time::Instant;

use glam::{Mat4, Vec3, Vec4};

use super::compare::format_name;
use super::coverage::{add_partners, keyword_coverage, space_size};
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::scene::{MapTexture, Rng, TestScene, cube_resource, push_mat4, push_vec4};
use super::standard::CLEAR;
use super::urp_occlusion::AMBIENT_OCCLUSION_PARAM;
use super::workers::{Worker, render_all};
use crate::urp::writes_shadow_mask;
use crate::{
    BoundResource, CheckError, ColorTarget, GpuError, RenderJob, Resource, TargetFormat,
    VertexBuffer, urp_gbuffer_formats,
};
use wgsl_variants::shader::Pass;
use wgsl_variants::variants::{Choice, Shard};
use wgsl_variants::{Library, Variant};
use wgsl_variants_shaders::reference::cube::CubeFaces;
use wgsl_variants_shaders::reference::quantize::{f16_bits_to_f32, f32_to_f16_bits};
use wgsl_variants_shaders::reference::tolerance::urp_texel_within;
use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;
use wgsl_variants_shaders::reference::urp::gbuffer::{
    UrpGBufferOutput, UrpKeywords, UrpLighting, UrpMaterial, UrpPixel, UrpTexel, UrpTexels,
    shade_gbuffer,
};

/// The clear values of the optional targets, in location order: depth as colour, rendering
/// layers, shadowmask (none of them a value the scene writes).
pub const CLEAR_OPTIONAL: [[f64; 4]; 3] = [
    [0.25, 0.0, 0.0, 0.0],
    [7.0, 0.0, 0.0, 0.0],
    [0.125, 0.875, 0.5, 0.375],
];

/// The seed of the URP scene's lightmap and shadowmask.
pub const DEFAULT_SEED: u64 = 0x0052_5047_B0FF;

/// The rendering-layer mask of the scene's mesh: layers 0, 2, 8 and 31 (31 needs all 32 bits).
pub const RENDERING_LAYERS: u32 = 0x8000_0105;

/// The lightmap's scale and offset (`unity_LightmapST`).
pub const LIGHTMAP_ST: Vec4 = Vec4::new(0.5, 0.5, 0.25, 0.25);

/// The URP test scene: the built-in [`TestScene`] with URP's material, lighting, lightmap and
/// shadowmask.
#[derive(Clone, Debug)]
pub struct UrpScene {
    /// The built-in scene (geometry, maps, camera, environment cube).
    pub scene: TestScene,
    /// URP Lit's material.
    pub material: UrpMaterial,
    /// The per-frame lighting.
    pub lighting: UrpLighting,
    /// The lightmap: `width × height` texels of four f16 bit patterns.
    pub lightmap: Vec<[u16; 4]>,
    /// The baked shadowmask.
    pub shadowmask: MapTexture,
}

impl UrpScene {
    /// URP's scene over `scene`; the lightmap and shadowmask come from `seed`.
    pub fn new(scene: &TestScene, seed: u64) -> UrpScene {
        let mut rng = Rng::new(seed);
        let (w, h) = (scene.width, scene.height);
        let m = &scene.material;
        let material = UrpMaterial {
            base_color: m.tint,
            spec_color: Vec3::new(0.2, 0.35, 0.5),
            emission_color: m.emission,
            metallic: m.metallic,
            smoothness: m.smoothness,
            cutoff: m.cutoff,
            bump_scale: m.bump_scale,
            occlusion_strength: m.occlusion_strength,
        };
        let s = &scene.scene;
        let lighting = UrpLighting {
            camera_position: s.camera_position,
            sh_r: s.sh_r,
            sh_g: s.sh_g,
            sh_b: s.sh_b,
            main_light_dir: s.light_dir,
            main_light_color: s.light_color,
            shadow_attenuation: 0.35,
            shadow_strength: 0.8,
            subtractive_shadow_color: Vec3::new(0.1, 0.12, 0.15),
            glossy_environment_color: Vec3::new(0.3, 0.25, 0.2),
            probes_occlusion: Vec4::new(0.8, 0.6, 0.4, 0.2),
        };
        // HDR lightmap values up to 2.5: quantized to f16 once, so the reference reads what
        // the texture holds.
        let lightmap = (0..w * h)
            .map(|_| {
                let c = [0.0, 1.0, 2.0].map(|_| f32_to_f16_bits(rng.range(0.05, 2.5)));
                [c[0], c[1], c[2], f32_to_f16_bits(1.0)]
            })
            .collect();
        let shadowmask = MapTexture {
            width: w,
            height: h,
            texels: (0..w * h)
                .map(|_| [0, 1, 2, 3].map(|_| rng.byte(0.0, 1.0)))
                .collect(),
        };
        UrpScene {
            scene: scene.clone(),
            material,
            lighting,
            lightmap,
            shadowmask,
        }
    }

    /// The lightmap texel pixel `(x, y)` reads: `uv · ½ + ¼` in texels is `x/2 + 4 + ¼` or
    /// `+ ¾`.
    pub fn lightmap_texel(&self, x: u32, y: u32) -> (u32, u32) {
        let texel = |p: u32, size: u32, scale: f32, offset: f32| {
            let u = (p as f32 + 0.5) / size as f32 * scale + offset;
            ((u * size as f32).floor() as u32).min(size - 1)
        };
        let (w, h) = (self.scene.width, self.scene.height);
        (
            texel(x, w, LIGHTMAP_ST.x, LIGHTMAP_ST.z),
            texel(y, h, LIGHTMAP_ST.y, LIGHTMAP_ST.w),
        )
    }

    /// The texels pixel `(x, y)` reads.
    pub fn texels(&self, x: u32, y: u32) -> UrpTexels {
        let m = &self.scene.maps;
        let (lx, ly) = self.lightmap_texel(x, y);
        let l = self.lightmap[(ly * self.scene.width + lx) as usize];
        UrpTexels {
            base_map: m.main_tex.get(x, y),
            bump_map: m.normal_map.get(x, y),
            metallic_gloss_map: m.metallic_map.get(x, y),
            occlusion_map: m.occlusion_map.get(x, y),
            emission_map: m.emission_map.get(x, y),
            lightmap: Vec3::new(
                f16_bits_to_f32(l[0]),
                f16_bits_to_f32(l[1]),
                f16_bits_to_f32(l[2]),
            ),
            shadowmask: self.shadowmask.get(lx, ly),
        }
    }

    /// The per-pixel inputs at `(x, y)`: the depth is the clip position's `z / w`.
    pub fn pixel(&self, x: u32, y: u32) -> UrpPixel {
        let geometry = self.scene.geometry(x, y);
        let clip = self.scene.view_proj * geometry.world_position.extend(1.0);
        UrpPixel {
            geometry,
            depth: clip.z / clip.w,
            rendering_layers: RENDERING_LAYERS,
        }
    }

    /// The environment cube (the built-in scene's first probe cube).
    pub fn environment(&self) -> &CubeFaces {
        &self.scene.scene.cubes[0]
    }

    /// The reference at pixel `(x, y)`; `None` where the variant discards it.
    pub fn reference(&self, k: &UrpKeywords, x: u32, y: u32) -> Option<UrpGBufferOutput> {
        shade_gbuffer(
            k,
            &self.material,
            &self.texels(x, y),
            &self.pixel(x, y),
            &self.lighting,
            self.environment(),
        )
    }

    /// Every resource of `wgsl/universal/bindings.wgsl`; a variant binds those it uses.
    pub fn resources(&self) -> Vec<BoundResource> {
        let s = &self.scene;
        let l = &self.lighting;
        let m = &self.material;
        let camera = camera_uniform(s.view_proj, l);
        let lighting = lighting_uniform(l);
        let material = material_uniform(m);
        let object = object_uniform(s.model, s.normal_matrix, LIGHTMAP_ST, RENDERING_LAYERS);
        let nearest_repeat = Resource::SamplerAddressed {
            nearest: true,
            address_mode: wgpu::AddressMode::Repeat,
        };
        let maps = &s.maps;
        vec![
            BoundResource::new(0, 0, Resource::Uniform(camera)),
            BoundResource::new(0, 1, Resource::Uniform(lighting)),
            BoundResource::new(0, 2, cube_resource(self.environment())),
            BoundResource::new(0, 3, Resource::Sampler { nearest: true }),
            BoundResource::new(1, 0, Resource::Uniform(material)),
            BoundResource::new(1, 1, nearest_repeat.clone()),
            BoundResource::new(1, 2, maps.main_tex.resource()),
            BoundResource::new(1, 3, maps.normal_map.resource()),
            BoundResource::new(1, 4, maps.metallic_map.resource()),
            BoundResource::new(1, 5, maps.occlusion_map.resource()),
            BoundResource::new(1, 6, maps.emission_map.resource()),
            BoundResource::new(2, 0, Resource::Uniform(object)),
            BoundResource::new(
                2,
                1,
                Resource::Texture2d {
                    format: wgpu::TextureFormat::Rgba16Float,
                    width: s.width,
                    height: s.height,
                    data: self
                        .lightmap
                        .iter()
                        .flatten()
                        .flat_map(|h| h.to_le_bytes())
                        .collect(),
                },
            ),
            BoundResource::new(2, 2, self.shadowmask.resource()),
            BoundResource::new(2, 3, nearest_repeat),
        ]
    }

    /// The second UV set (`@location(4)`, slot 1): the quad's uv again (URP's uv1).
    pub fn lightmap_uvs(&self) -> VertexBuffer {
        // The quad's vertex order: top-left, bottom-left, top-right twice, bottom-left,
        // bottom-right (`TestScene::quad`).
        let (tl, tr, bl, br) = ([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]);
        VertexBuffer::from_f32(&[(4, 2)], &[tl, bl, tr, tr, bl, br])
    }

    /// The render job of one variant's composed text.
    pub fn job(&self, label: &str, wgsl: &str, keywords: &[&str]) -> RenderJob {
        let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
        job.width = self.scene.width;
        job.height = self.scene.height;
        job.targets = urp_targets(keywords).into_iter().map(|(_, t)| t).collect();
        job.vertex_buffers = vec![self.scene.quad(), self.lightmap_uvs()];
        job.vertex_count = 6;
        job
    }
}

/// The main light's shadow fade of a check: a ramp over most of the camera distances of
/// `positions` (the shadowed ones; from 10 % to 90 % of their range), so the nearest keep the
/// realtime shadow, the farthest lose it and most lose part of it. No fade without positions.
pub(crate) fn fade_across(positions: &[Vec3], camera: Vec3) -> UrpShadowFade {
    let (near, far) = positions
        .iter()
        .map(|p| p.distance(camera))
        .fold((f32::INFINITY, 0.0f32), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    let span = far - near;
    // No positions (or one distance): nothing to ramp across.
    if span.is_nan() || span <= 0.0 {
        return UrpShadowFade::NONE;
    }
    UrpShadowFade::between(near + 0.1 * span, near + 0.9 * span)
}

/// The bindings of the main light's shadow in URP's passes: the map, the cascades and their
/// atlas, the screen-space texture (10-12, 14-16) and URP's `_MainLightShadowParams` (13: the
/// strength and the fade).
pub(crate) fn main_shadow_resources(
    shadow: &super::screen_masks::ScreenShadow,
    fade: &UrpShadowFade,
) -> Vec<BoundResource> {
    let mut out = shadow.urp_resources();
    let params = fade.uniform(shadow.params.strength);
    out.push(BoundResource::new(0, 13, Resource::Uniform(params)));
    out
}

/// `wgsl/universal/bindings.wgsl`'s `Camera`: view-projection and the camera's position.
pub(crate) fn camera_uniform(view_proj: Mat4, l: &UrpLighting) -> Vec<u8> {
    let mut out = Vec::new();
    push_mat4(&mut out, view_proj);
    push_vec4(&mut out, l.camera_position.extend(1.0));
    out
}

/// `wgsl/universal/bindings.wgsl`'s `Lighting`, its `_AmbientOcclusionParam` the checks' SSAO
/// ([`AMBIENT_OCCLUSION_PARAM`]).
pub(crate) fn lighting_uniform(l: &UrpLighting) -> Vec<u8> {
    let mut out = Vec::new();
    for v in [
        l.sh_r,
        l.sh_g,
        l.sh_b,
        l.main_light_dir.extend(0.0),
        l.main_light_color.extend(1.0),
        Vec4::new(l.shadow_attenuation, l.shadow_strength, 0.0, 0.0),
        l.subtractive_shadow_color.extend(0.0),
        l.glossy_environment_color.extend(0.0),
        l.probes_occlusion,
        Vec4::from_array(AMBIENT_OCCLUSION_PARAM),
    ] {
        push_vec4(&mut out, v);
    }
    out
}

/// `wgsl/universal/bindings.wgsl`'s `Material`.
pub(crate) fn material_uniform(m: &UrpMaterial) -> Vec<u8> {
    let mut out = Vec::new();
    for v in [
        m.base_color,
        m.spec_color.extend(0.0),
        m.emission_color.extend(0.0),
        Vec4::new(m.metallic, m.smoothness, m.cutoff, m.bump_scale),
        Vec4::new(m.occlusion_strength, 0.0, 0.0, 0.0),
    ] {
        push_vec4(&mut out, v);
    }
    out
}

/// `wgsl/universal/bindings.wgsl`'s `Object`: model and normal matrices, `unity_LightmapST`,
/// the mesh's rendering-layer mask.
pub(crate) fn object_uniform(
    model: Mat4,
    normal_matrix: Mat4,
    lightmap_st: Vec4,
    rendering_layers: u32,
) -> Vec<u8> {
    let mut out = Vec::new();
    push_mat4(&mut out, model);
    push_mat4(&mut out, normal_matrix);
    push_vec4(&mut out, lightmap_st);
    for word in [rendering_layers, 0, 0, 0] {
        out.extend(word.to_le_bytes());
    }
    out
}

/// The colour targets of a `UniversalGBuffer` variant with these keywords, named for reports,
/// each cleared to a value the scene never writes.
pub fn urp_targets(keywords: &[&str]) -> Vec<(String, ColorTarget)> {
    let names = ["GBuffer0", "GBuffer1", "GBuffer2", "GBuffer3"];
    let optional = [
        ("depth", keywords.contains(&"_RENDER_PASS_ENABLED")),
        (
            "rendering layers",
            keywords.contains(&"_WRITE_RENDERING_LAYERS"),
        ),
        ("shadowmask", writes_shadow_mask(keywords)),
    ];
    let extra = optional
        .iter()
        .zip(CLEAR_OPTIONAL)
        .filter(|((_, on), _)| *on)
        .map(|((name, _), clear)| (*name, clear));
    let labels = names.iter().copied().zip(CLEAR).chain(extra);
    urp_gbuffer_formats(keywords)
        .into_iter()
        .zip(labels)
        .filter_map(|(format, (name, clear))| {
            let format = TargetFormat::from_wgpu(format)?;
            Some((
                format!("{name} {}", format_name(format)),
                ColorTarget::new(format).with_clear(clear),
            ))
        })
        .collect()
}

/// The texel a cleared target holds, as the reference states it (the GPU converts the clear
/// value as if the shader had written it).
pub fn cleared(target: &ColorTarget) -> UrpTexel {
    let c = Vec4::from_array(target.clear.map(|x| x as f32));
    match target.format {
        TargetFormat::Rgba8UnormSrgb => UrpTexel::Srgb8(c),
        TargetFormat::Rgba8Snorm => UrpTexel::Snorm8(c),
        TargetFormat::Rg11b10Ufloat => UrpTexel::Ufloat(c.truncate()),
        TargetFormat::R32Float => UrpTexel::F32(c.x),
        TargetFormat::R32Uint => UrpTexel::U32(target.clear[0] as u32),
        _ => UrpTexel::Unorm8(c),
    }
}

/// What the check needs of one of `universal_lit`'s colour passes (`UniversalGBuffer`,
/// `UniversalForward`): its targets, its render job and its reference, so one loop renders,
/// compares and judges both.
pub(crate) trait UrpColorPass {
    /// The URP scene the pass draws.
    fn urp(&self) -> &UrpScene;
    /// Every resource a variant of the pass may bind (uploaded once per worker).
    fn resources(&self) -> Vec<BoundResource>;
    /// The colour targets of a variant with these keywords, named for reports.
    fn targets(&self, keywords: &[&str]) -> Vec<(String, ColorTarget)>;
    /// The render job of one variant's composed text.
    fn job(&self, label: &str, wgsl: &str, keywords: &[&str]) -> RenderJob;
    /// The reference texels of every target at every pixel (`None`: discarded); `Err` names
    /// a keyword the reference does not know.
    fn reference_image(&self, keywords: &[&str]) -> Result<Vec<Option<Vec<UrpTexel>>>, String>;
    /// What the report says of the scene and the comparison.
    fn note(&self) -> String;
}

impl UrpColorPass for UrpScene {
    fn urp(&self) -> &UrpScene {
        self
    }

    fn resources(&self) -> Vec<BoundResource> {
        UrpScene::resources(self)
    }

    fn targets(&self, keywords: &[&str]) -> Vec<(String, ColorTarget)> {
        urp_targets(keywords)
    }

    fn job(&self, label: &str, wgsl: &str, keywords: &[&str]) -> RenderJob {
        UrpScene::job(self, label, wgsl, keywords)
    }

    fn reference_image(&self, keywords: &[&str]) -> Result<Vec<Option<Vec<UrpTexel>>>, String> {
        let k = UrpKeywords::from_names(keywords).map_err(|e| e.to_string())?;
        Ok(self
            .scene
            .pixels()
            .map(|(x, y)| self.reference(&k, x, y).map(|o| o.texels(&k)))
            .collect())
    }

    fn note(&self) -> String {
        format!(
            "{}x{} pixels, GBuffer0-3 and the optional targets of each variant; discarded pixels compared with the clear colour; octahedral normals by their 12-bit codes",
            self.scene.width, self.scene.height
        )
    }
}

/// Which variants of the pass to check.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Selection {
    /// A t-wise covering set (else the full space).
    pub(crate) cover: Option<usize>,
    /// Every n-th variant.
    pub(crate) sample: usize,
    /// Only this shard.
    pub(crate) shard: Option<Shard>,
}

/// The variants of `pass` the selection keeps, numbered as the standard passes' are.
pub(crate) fn select(pass: &Pass, selection: Selection) -> Result<Vec<Choice>, GpuError> {
    let space = wgsl_variants::Space::full(pass);
    let all = match selection.cover {
        Some(t) => space
            .covering(t)
            .map_err(|e| GpuError::from(CheckError::from(e)))?,
        None => space
            .enumerate(super::coverage::MAX_VARIANTS)
            .map_err(|source| {
                GpuError::from(CheckError::Budget {
                    what: format!("{}/{}", pass.shader, pass.name),
                    source,
                })
            })?,
    };
    Ok(all
        .into_iter()
        .step_by(selection.sample.max(1))
        .enumerate()
        .filter(|(i, _)| selection.shard.is_none_or(|s| s.contains(*i as u64)))
        .map(|(_, c)| c)
        .collect())
}

/// Compares one variant's read-back targets with its reference image; every texel recorded
/// in `report`.
pub fn compare_variant(
    report: &mut PassReport,
    scene: &TestScene,
    pass: &Pass,
    label: &str,
    targets: &[(String, ColorTarget)],
    expected: &[Option<Vec<UrpTexel>>],
    bytes: &[Vec<u8>],
) {
    for (i, (x, y)) in scene.pixels().enumerate() {
        let want = &expected[i];
        if want.is_none() {
            report.discarded_compared += targets.len();
        }
        for (t, (name, target)) in targets.iter().enumerate() {
            let texel = match want {
                Some(texels) => texels[t],
                None => cleared(target),
            };
            let px = &bytes[t][i * 4..i * 4 + 4];
            let got = [px[0], px[1], px[2], px[3]];
            let ok = urp_texel_within(got, &texel);
            report.record(ok, || Mismatch {
                shader: pass.shader.clone(),
                pass: pass.name.clone(),
                keywords: label.to_owned(),
                target: if want.is_none() {
                    format!("{name} (discarded: clear colour)")
                } else {
                    name.clone()
                },
                pixel: [x, y],
                expected: texel.to_vec(),
                got: target.format.decode_pixel_f32(px).to_vec(),
                got_raw: target.format.decode_pixel(px).to_vec(),
            });
        }
    }
}

/// Checks the selected variants of one of `universal_lit`'s colour passes (`spec` says which):
/// each distinct text rendered once, every texel of every target against the reference.
pub(crate) fn check_urp_color_pass(
    workers: &[Worker<'_>],
    lib: &Library,
    spec: &dyn UrpColorPass,
    pass: &Pass,
    selection: Selection,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let mut report = PassReport::new(&pass.shader, &pass.name);
    let mut choices = select(pass, selection)?;
    let image_of = |choice: &Choice| -> Result<Vec<Option<Vec<UrpTexel>>>, GpuError> {
        spec.reference_image(&choice.keywords(pass))
            .map_err(|message| {
                GpuError::from(CheckError::UnknownToReference {
                    variant: choice.label(pass),
                    message,
                })
            })
    };
    let covering = selection.cover.is_some();
    let sampled = selection.sample > 1 || selection.shard.is_some();
    let partners = if covering && !sampled {
        add_partners(pass, &mut choices, &image_of)?
    } else {
        0
    };

    // Compose every variant; render each distinct text once.
    let mut distinct: HashMap<String, usize> = HashMap::new();
    let mut jobs = Vec::new();
    let mut text_of = Vec::with_capacity(choices.len());
    for choice in &choices {
        let variant = Variant {
            pass,
            choice: choice.clone(),
        };
        let text = lib.wgsl(&variant);
        let index = match distinct.get(&text) {
            Some(&index) => index,
            None => {
                jobs.push(spec.job(&variant.label(), &text, &variant.keywords()));
                distinct.insert(text, jobs.len() - 1);
                jobs.len() - 1
            }
        };
        text_of.push(index);
    }
    report.distinct_shaders = jobs.len();
    report.draws = jobs.len();
    let outputs = render_all(workers, &jobs)?;

    // References are computed per variant as it is compared (the full space's would not fit
    // in memory at once).
    for (v, choice) in choices.iter().enumerate() {
        let targets = spec.targets(&choice.keywords(pass));
        compare_variant(
            &mut report,
            &spec.urp().scene,
            pass,
            &choice.label(pass),
            &targets,
            &image_of(choice)?,
            &outputs[text_of[v]],
        );
        report.variants_run += 1;
    }

    report.keywords = keyword_coverage(pass, &choices, |a, b| {
        outputs[text_of[a]] != outputs[text_of[b]]
    });
    if sampled {
        report.notes.push(format!(
            "sampled every {}th variant{}: keyword coverage is not judged",
            selection.sample.max(1),
            selection
                .shard
                .map(|s| format!(" of shard {s}"))
                .unwrap_or_default()
        ));
    } else {
        report.judge_keywords();
    }
    if let Some(t) = selection.cover {
        report.notes.push(format!(
            "{t}-wise covering set of {} variants, plus {partners} partners: for each keyword, the first covering variant with it on whose reference changes with it off is rendered with it off too",
            choices.len() - partners
        ));
    }
    report.notes.push(spec.note());
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `universal_lit/UniversalGBuffer` in the check's registry.
pub(crate) struct UniversalGBuffer;

/// The entry of `universal_lit/UniversalGBuffer`.
pub(crate) static UNIVERSAL_GBUFFER: UniversalGBuffer = UniversalGBuffer;

impl PassCheck for UniversalGBuffer {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("universal_lit", "UniversalGBuffer")]
    }

    fn needs(&self) -> Needs {
        Needs {
            workers: true,
            ..Needs::NOTHING
        }
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        let urp = UrpScene::new(setup.scene, DEFAULT_SEED);
        check_color_entry(setup, "UniversalGBuffer", &urp)
    }
}

/// Checks `universal_lit/<name>` over `spec` on workers with `spec`'s resources: what the
/// entries of both URP colour passes share.
pub(crate) fn check_color_entry(
    setup: &Setup<'_>,
    name: &str,
    spec: &dyn UrpColorPass,
) -> Result<Vec<PassReport>, GpuError> {
    let pass = setup.pass("universal_lit", name)?;
    let workers = setup.workers(&spec.resources(), name)?;
    let options = setup.options;
    Ok(vec![check_urp_color_pass(
        &workers,
        setup.lib,
        spec,
        pass,
        Selection {
            cover: options.cover_for(space_size(pass)),
            sample: options.sample,
            shard: options.shard,
        },
    )?])
}
