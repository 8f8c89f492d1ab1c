//! `audit` with several `--profile`s: the build set of each pass validated once per profile
//! (each variant composed once where composing does not depend on the device), and a table of
//! the variants valid on each.

use wgsl_variants::validate::{ProfileCounts, validate_plan};

use super::context::{BuildArgs, Context, Failed};

/// One pass's row: built variants and the verdicts per profile (`audit --json`:
/// `valid_per_profile`).
#[derive(Debug, serde::Serialize)]
pub struct PassProfiles {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Variants built (the build set).
    pub built: u64,
    /// Valid and invalid variants per profile, in the order the profiles were given.
    pub profiles: Vec<ProfileCounts>,
}

/// Validates the build set of the selected passes on every profile (with the default cache of
/// valid texts, as `validate` uses it): one row per pass.
pub fn validate(ctx: &Context, build: &BuildArgs) -> Result<Vec<PassProfiles>, Failed> {
    let cache_dir = super::cache::default_dir(None);
    let cache = cache_dir.as_deref().map(super::cache::open);
    let options = super::context::plan_options(build, false, None)?;
    let plan = ctx.plan(&options)?;
    let bar = super::output::progress(
        plan.iter().map(|p| p.1.len() as u64).sum(),
        "validating per profile",
    );
    let report = validate_plan(&ctx.lib, &plan, &options, cache.as_ref(), &|n| bar.inc(n));
    bar.finish_and_clear();
    if let Some(cache) = &cache
        && let Err(e) = cache.save()
    {
        eprintln!("warning: could not write the validation cache: {e}");
    }
    Ok(report
        .passes
        .into_iter()
        .map(|r| PassProfiles {
            shader: r.shader,
            pass: r.pass,
            built: r.built,
            profiles: r.profiles,
        })
        .collect())
}

/// The table "variants valid per profile": per pass, the variants built and those valid on
/// each profile (a column per profile, in order of first appearance; `-` where a pass is not
/// validated for one).
pub fn table(rows: &[PassProfiles], names: &[String]) -> String {
    let mut cells = vec![
        ["shader/pass".to_string(), "built".into()]
            .into_iter()
            .chain(names.iter().cloned())
            .collect::<Vec<String>>(),
    ];
    for r in rows {
        let mut row = vec![format!("{}/{}", r.shader, r.pass), r.built.to_string()];
        for name in names {
            row.push(
                r.profiles
                    .iter()
                    .find(|p| &p.profile == name)
                    .map_or("-".into(), |p| p.valid.to_string()),
            );
        }
        cells.push(row);
    }
    format!(
        "variants valid per profile (build set, validated):\n{}",
        super::table::columns(&cells, "  ", 1)
    )
}
