//! The standard shader's passes (`Deferred`, `ForwardBase`, `ForwardAdd`) over their full
//! variant space:
//! every variant rendered (each distinct composed text once), read back and compared pixel by
//! pixel with the CPU reference of its keyword set; then, per keyword, whether toggling it
//! changed any output.

use std::collections::HashMap;
use std::time::Instant;

use glam::Vec4;

use super::compare::{clear_value, pixel, texel_within};
use super::coverage::{MAX_VARIANTS, add_partners, keyword_coverage, space_size};
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::rig::{LightRig, shadowed};
use super::scene::TestScene;
use super::shadows::within;
use super::standard::{StandardOutput, standard_job};
use super::workers::{Worker, render_all};
use crate::{CheckError, GpuError, GpuResources, RenderJob};
use wgsl_variants::shader::Pass;
use wgsl_variants::variants::{Choice, Space};
use wgsl_variants::{Library, Variant};
use wgsl_variants_shaders::reference::light::{Cookies, LightType};
use wgsl_variants_shaders::reference::shadow::ShadowKeywords;
use wgsl_variants_shaders::reference::surface::{
    Keywords, shade_deferred, shade_forward, shade_forward_add,
};

/// Whether `pass` is the standard shader's G-buffer pass (else its forward base pass).
fn is_deferred(pass: &Pass) -> bool {
    pass.name == "Deferred"
}

/// The reference outputs of a standard pass at pixel `(x, y)`, one per target of `output`;
/// `None` where the pixel is discarded. `main_shadow` scales ForwardBase's main light (its
/// `SHADOWS_SCREEN` factor; 1 without).
pub fn reference_outputs(
    scene: &TestScene,
    output: StandardOutput,
    kw: &Keywords,
    main_shadow: f32,
    x: u32,
    y: u32,
) -> Option<Vec<Vec4>> {
    let texels = scene.texels(x, y);
    let geometry = scene.geometry(x, y);
    if let StandardOutput::GBuffer { shadowmask, .. } = output {
        shade_deferred(kw, &scene.material, &texels, &geometry, &scene.scene).map(|g| {
            let mut targets = vec![g.rt0, g.rt1, g.rt2, g.rt3];
            if shadowmask {
                // RT4 stores the baked occlusion texel as it is (docs/shading.md §13).
                targets.push(scene.shadowmask_texel(kw.lightmap, x, y));
            }
            targets
        })
    } else {
        let lit = scene.scene.with_main_shadow(main_shadow);
        shade_forward(kw, &scene.material, &texels, &geometry, &lit).map(|c| vec![c])
    }
}

/// The reference output of `standard/ForwardAdd` at pixel `(x, y)` under the rig's light of
/// type `light`, its colour scaled by the shadow factor `shadow` (1: unshadowed); `None` where
/// the pixel is discarded.
#[allow(clippy::too_many_arguments)]
pub fn forward_add_output(
    scene: &TestScene,
    rig: &LightRig,
    kw: &Keywords,
    light: LightType,
    shadow: f32,
    x: u32,
    y: u32,
) -> Option<Vec4> {
    let cookie = rig.cookie_2d();
    let cookies = Cookies {
        texture: &cookie,
        cube: &rig.cube,
    };
    shade_forward_add(
        kw,
        &scene.material,
        &scene.texels(x, y),
        &scene.geometry(x, y),
        scene.scene.camera_position,
        &shadowed(rig.params(light), shadow),
        light,
        Some(cookies),
    )
}

/// A standard pass's variant as the reference sees it.
#[derive(Clone, Copy, Debug)]
struct Parsed {
    /// The material and output keywords.
    kw: Keywords,
    /// ForwardAdd's light keyword.
    light: Option<LightType>,
    /// The shadow keywords (SHADOWS_SHADOWMASK included).
    shadow: ShadowKeywords,
}

impl Parsed {
    /// Splits the keywords of `choice`.
    fn of(pass: &Pass, choice: &Choice) -> Result<Parsed, GpuError> {
        let names = choice.keywords(pass);
        let (light, names) = LightType::split(&names);
        let (shadow, names) = ShadowKeywords::split(&names);
        let kw = Keywords::from_names(&names).map_err(|e| {
            GpuError::from(CheckError::UnknownToReference {
                variant: choice.label(pass),
                message: e.to_string(),
            })
        })?;
        Ok(Parsed { kw, light, shadow })
    }

    /// What the variant writes.
    fn output(&self, deferred: bool) -> StandardOutput {
        if deferred {
            StandardOutput::GBuffer {
                hdr: self.kw.hdr,
                shadowmask: self.shadow.shadowmask,
            }
        } else {
            StandardOutput::Forward
        }
    }
}

/// The reference of a standard pass's variant at pixel `i`, `(x, y)`: one value per target
/// (`Deferred`, `ForwardBase`), or `ForwardAdd`'s colour at the two ends of the light's shadow
/// interval (a point wherever no shadow tap is within a hair of flipping); `None` where the
/// pixel is discarded.
fn reference_pixel(
    scene: &TestScene,
    rig: &LightRig,
    deferred: bool,
    v: &Parsed,
    i: usize,
    (x, y): (u32, u32),
) -> Option<Vec<Vec4>> {
    match v.light {
        Some(light) => {
            let p = scene.world_position(x, y);
            let (lo, hi) = rig.received_factor(light, v.shadow, (p, i), 1.0);
            let a = forward_add_output(scene, rig, &v.kw, light, lo, x, y)?;
            let b = forward_add_output(scene, rig, &v.kw, light, hi, x, y)?;
            Some(vec![a, b])
        }
        None => {
            // ForwardBase's main light reads the directional light's mask, faded.
            let main_shadow = rig.main_light_factor(v.shadow, scene.world_position(x, y), i);
            reference_outputs(scene, v.output(deferred), &v.kw, main_shadow, x, y)
        }
    }
}

/// Checks every variant of a standard pass (`Deferred`, `ForwardBase` or `ForwardAdd`; the
/// last lit by the rig's light of each variant's light keyword), or a `cover`-wise covering
/// set of it plus, for each keyword, a partner pair whose reference says the keyword matters
/// ([`add_partners`]), so keyword coverage is judged either way.
#[allow(clippy::too_many_arguments)]
pub fn check_standard_pass(
    workers: &[Worker<'_>],
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    pass: &Pass,
    sample: usize,
    shard: Option<wgsl_variants::variants::Shard>,
    cover: Option<usize>,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let deferred = is_deferred(pass);
    let mut report = PassReport::new(&pass.shader, &pass.name);
    let all = match cover {
        Some(t) => Space::full(pass)
            .covering(t)
            .map_err(|e| GpuError::from(CheckError::from(e)))?,
        None => Space::full(pass)
            .enumerate(MAX_VARIANTS)
            .map_err(|source| {
                GpuError::from(CheckError::Budget {
                    what: format!("{}/{}", pass.shader, pass.name),
                    source,
                })
            })?,
    };
    // Sample first, then shard the sample by its own numbering: sharding by the index in the
    // space would leave a shard empty whenever the sample step and the shard count share a
    // factor (`--sample 64 --shard 2/2`).
    let every = sample.max(1);
    let sampled = every > 1 || shard.is_some();
    let mut choices: Vec<Choice> = all
        .into_iter()
        .step_by(every)
        .enumerate()
        .filter(|(i, _)| shard.is_none_or(|s| s.contains(*i as u64)))
        .map(|(_, c)| c)
        .collect();
    let partners = if cover.is_some() && !sampled {
        let image_of = |choice: &Choice| -> Result<Vec<Option<Vec<Vec4>>>, GpuError> {
            let v = Parsed::of(pass, choice)?;
            Ok(scene
                .pixels()
                .enumerate()
                .map(|(i, xy)| reference_pixel(scene, rig, deferred, &v, i, xy))
                .collect())
        };
        add_partners(pass, &mut choices, &image_of)?
    } else {
        0
    };

    // Compose every variant; render each distinct text once.
    let mut distinct: HashMap<String, usize> = HashMap::new();
    let mut jobs = Vec::new();
    let mut text_of = Vec::with_capacity(choices.len());
    let mut parsed = Vec::with_capacity(choices.len());
    let mut job_light: Vec<Option<LightType>> = Vec::new();
    for choice in &choices {
        let variant = Variant {
            pass,
            choice: choice.clone(),
        };
        let v = Parsed::of(pass, choice)?;
        let text = lib.wgsl(&variant);
        let index = match distinct.get(&text) {
            Some(&index) => index,
            None => {
                let index = jobs.len();
                jobs.push(standard_job(
                    scene,
                    &variant.label(),
                    &text,
                    v.output(deferred),
                ));
                job_light.push(v.light);
                distinct.insert(text, index);
                index
            }
        };
        text_of.push(index);
        parsed.push(v);
    }
    report.distinct_shaders = jobs.len();
    report.draws = jobs.len();
    let outputs = render_grouped_by_light(workers, scene, rig, &jobs, &job_light)?;

    // Compare every variant with its own reference.
    for (v, choice) in choices.iter().enumerate() {
        let label = choice.label(pass);
        let targets = parsed[v].output(deferred).targets();
        let bytes = &outputs[text_of[v]];
        for (i, (x, y)) in scene.pixels().enumerate() {
            let reference = reference_pixel(scene, rig, deferred, &parsed[v], i, (x, y));
            let expected = match reference {
                // ForwardAdd: the GPU value is held to the shadow interval.
                Some(ends) if parsed[v].light.is_some() => {
                    let (_, got) = pixel(targets[0].1.format, &bytes[0], i);
                    Some(vec![within(got, ends[0], ends[1])])
                }
                other => other,
            };
            if expected.is_none() {
                report.discarded_compared += targets.len();
            }
            for (t, (name, target)) in targets.iter().enumerate() {
                let want = match &expected {
                    Some(values) => values[t],
                    None => clear_value(target.clear),
                };
                let (raw, got) = pixel(target.format, &bytes[t], i);
                let ok = texel_within(target.format, raw, want);
                report.record(ok, || Mismatch {
                    shader: pass.shader.clone(),
                    pass: pass.name.clone(),
                    keywords: label.clone(),
                    target: if expected.is_none() {
                        format!("{name} (discarded: clear colour)")
                    } else {
                        name.clone()
                    },
                    pixel: [x, y],
                    expected: want.to_array().to_vec(),
                    got: got.to_vec(),
                    got_raw: raw.to_vec(),
                });
            }
        }
        report.variants_run += 1;
    }

    // Keyword coverage: each keyword against its set's first option.
    let decoded: Vec<Vec<Vec<[f32; 4]>>> = outputs
        .iter()
        .zip(&jobs)
        .map(|(targets, job)| {
            targets
                .iter()
                .zip(&job.targets)
                .map(|(bytes, t)| t.format.decode_image_f32(bytes))
                .collect()
        })
        .collect();
    report.keywords = keyword_coverage(pass, &choices, |a, b| {
        decoded[text_of[a]] != decoded[text_of[b]]
    });
    if sampled {
        report.notes.push(format!(
            "sampled every {every}th variant{}: keyword coverage is judged on the full space or a covering set only",
            shard.map(|s| format!(" of shard {s}")).unwrap_or_default()
        ));
    } else {
        report.judge_keywords();
    }
    if let Some(t) = cover {
        report.notes.push(format!(
            "{t}-wise covering set of {} variants (every {t}-way combination of keyword options), plus {partners} partners: for each keyword, the first covering variant with it on whose reference changes with it off is rendered with it off too",
            choices.len() - partners
        ));
    }
    report.notes.push(format!(
        "{}x{} pixels, {} targets per variant; discarded pixels compared with the clear colour",
        scene.width,
        scene.height,
        if deferred {
            "4 (5 with SHADOWS_SHADOWMASK)"
        } else {
            "1"
        }
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// A standard pass's entry in the check's registry: its variants spread over the workers,
/// which every standard pass of a run shares.
pub(crate) struct StandardPass {
    passes: &'static [(&'static str, &'static str)],
    needs: Needs,
}

/// `standard/Deferred`: the G-buffer.
pub(crate) static DEFERRED: StandardPass = StandardPass {
    passes: &[("standard", "Deferred")],
    needs: Needs {
        workers: true,
        ..Needs::NOTHING
    },
};

/// `standard/ForwardBase`: its main light reads the directional light's `SHADOWS_SCREEN` mask.
pub(crate) static FORWARD_BASE: StandardPass = StandardPass {
    passes: &[("standard", "ForwardBase")],
    needs: Needs {
        workers: true,
        screen_masks: true,
        ..Needs::NOTHING
    },
};

/// `standard/ForwardAdd`: the rig's lights, shadowed by their maps and the directional masks.
pub(crate) static FORWARD_ADD: StandardPass = StandardPass {
    passes: &[("standard", "ForwardAdd")],
    needs: Needs {
        workers: true,
        screen_masks: true,
        shadow_maps: true,
    },
};

impl PassCheck for StandardPass {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        self.passes
    }

    fn needs(&self) -> Needs {
        self.needs
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        let workers = setup.standard_workers()?;
        let (shader, name) = self.passes[0];
        let pass = setup.pass(shader, name)?;
        let options = setup.options;
        Ok(vec![check_standard_pass(
            workers,
            setup.lib,
            setup.scene,
            setup.rig,
            pass,
            options.sample,
            options.shard,
            options.cover_for(space_size(pass)),
        )?])
    }
}

/// Renders `jobs`; those with a light keyword (`job_light[i]`, ForwardAdd) on workers whose
/// resources add the rig's light of that type, one group per light type.
fn render_grouped_by_light(
    workers: &[Worker<'_>],
    scene: &TestScene,
    rig: &LightRig,
    jobs: &[RenderJob],
    job_light: &[Option<LightType>],
) -> Result<Vec<Vec<Vec<u8>>>, GpuError> {
    if job_light.iter().all(Option::is_none) {
        return render_all(workers, jobs);
    }
    let mut outputs: Vec<Option<Vec<Vec<u8>>>> = (0..jobs.len()).map(|_| None).collect();
    for light in LightType::ALL {
        let group: Vec<usize> = (0..jobs.len())
            .filter(|&i| job_light[i] == Some(light))
            .collect();
        if group.is_empty() {
            continue;
        }
        let mut resources = scene.standard_resources();
        resources.extend(rig.resources(light));
        let lit = workers
            .iter()
            .map(|w| {
                Ok(Worker {
                    ctx: w.ctx,
                    resources: GpuResources::upload(w.ctx, light.keyword(), &resources)?,
                })
            })
            .collect::<Result<Vec<_>, GpuError>>()?;
        let group_jobs: Vec<RenderJob> = group.iter().map(|&i| jobs[i].clone()).collect();
        for (i, out) in group.into_iter().zip(render_all(&lit, &group_jobs)?) {
            outputs[i] = Some(out);
        }
    }
    outputs
        .into_iter()
        .map(|o| o.ok_or_else(|| GpuError::from(CheckError::NoWorker)))
        .collect()
}
