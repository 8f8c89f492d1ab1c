//! Shared pieces of the tests and benchmarks of every crate of the workspace: synthetic
//! shaders, timing, machine description, the summary file, memory. Not published.
#![allow(dead_code)] // each bench uses a subset

pub mod bad;
pub mod selection;
pub mod shaders;
pub mod timing;
pub mod workload;

use std::process::Command;
use std::time::Duration;

use serde_json::{Value, json};
use wgsl_variants::validate::validate_pass_with;
use wgsl_variants::{Library, Space};

pub use timing::*;
pub use workload::*;

/// A synthetic library: one pass with a three-way `multi_compile` set and `keywords` two-way
/// sets (3 × 2^keywords variants), each keyword guarding an entry point of its own (entry
/// points are always kept: nothing is pruned), so every variant is distinct. With `dead`, one more two-way set changes no code, so every text is
/// shared by two variants and validation keeps its index of seen texts.
pub fn synthetic(keywords: usize, dead: bool) -> Library {
    let mut body = String::from("#pragma multi_compile TIER_LOW TIER_MID TIER_HIGH\n");
    for k in 0..keywords {
        body.push_str(&format!("#pragma multi_compile _ K{k}\n"));
    }
    if dead {
        body.push_str("#pragma multi_compile _ DEAD\n");
    }
    body.push_str("#if defined(TIER_HIGH)\nconst TIER: f32 = 2.0;\n#elif defined(TIER_MID)\n");
    body.push_str("const TIER: f32 = 1.0;\n#else\nconst TIER: f32 = 0.0;\n#endif\n");
    for k in 0..keywords {
        body.push_str(&format!(
            "#ifdef K{k}\n@fragment fn f{k}() -> @location(0) vec4f {{ return vec4f({k}.0 + TIER); }}\n#endif\n"
        ));
    }
    body.push_str("@fragment fn fs_main() -> @location(0) vec4f { return vec4f(TIER); }\n");
    Library::from_sources([(
        "s.wgsl".to_string(),
        format!("#shader synthetic\n#pass P\n{body}#endpass\n"),
    )])
    .expect("synthetic library")
}

/// Peak resident memory of this process, in KiB (Linux `VmHWM`).
pub fn peak_rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(0)
}

/// In a child process (`BENCH_MEMORY_CHILD=keywords[,dead]`): validate every variant of a
/// synthetic space, streamed, and print the peak RSS. Returns true when this process is such
/// a child.
pub fn memory_child() -> bool {
    let Ok(spec) = std::env::var("BENCH_MEMORY_CHILD") else {
        return false;
    };
    let (k, dead) = match spec.split_once(',') {
        Some((k, _)) => (k, true),
        None => (spec.as_str(), false),
    };
    let lib = synthetic(k.parse().expect("keyword count"), dead);
    let pass = lib.passes().next().expect("pass");
    // Streamed: the variants are never collected.
    let report = validate_pass_with(&lib, pass, Space::full(pass).iter(), None, &|_| {});
    assert_eq!(report.invalid, 0);
    println!(
        "variants {} distinct {} peak_rss_kib {}",
        report.built,
        report.distinct,
        peak_rss_kib()
    );
    true
}

/// Peak memory validating synthetic spaces of 3,072 and 98,304 variants, each in a fresh
/// process (peak RSS only grows within a process): all distinct (the audit proves it, no
/// index is kept), and with a dead keyword (every text twice, the index of seen texts kept).
pub fn memory_flatness() -> Value {
    let exe = std::env::current_exe().expect("bench executable");
    let mut cases = Vec::new();
    for (label, dead) in [("all distinct", ""), ("dead keyword", ",dead")] {
        let mut results = Vec::new();
        for keywords in [10usize, 15] {
            let out = Command::new(&exe)
                .env("BENCH_MEMORY_CHILD", format!("{keywords}{dead}"))
                .output()
                .expect("memory child");
            let text = String::from_utf8_lossy(&out.stdout);
            let line = text
                .lines()
                .find(|l| l.starts_with("variants"))
                .unwrap_or_default()
                .to_string();
            let field = |name: &str| {
                line.split_whitespace()
                    .skip_while(|w| *w != name)
                    .nth(1)
                    .and_then(|v| v.parse::<u64>().ok())
                    .unwrap_or(0)
            };
            let r = (field("variants"), field("distinct"), field("peak_rss_kib"));
            println!(
                "memory ({label}): {:>7} variants ({} distinct) validated, peak RSS {:.1} MiB",
                r.0,
                r.1,
                r.2 as f64 / 1024.0
            );
            results.push(r);
        }
        let growth = results[1].2 as f64 / results[0].2.max(1) as f64;
        println!(
            "memory ({label}): {}x the variants, {growth:.2}x the peak RSS",
            results[1].0 / results[0].0.max(1)
        );
        cases.push(json!({
            "case": label,
            "variants": results.iter().map(|r| r.0).collect::<Vec<_>>(),
            "distinct": results.iter().map(|r| r.1).collect::<Vec<_>>(),
            "peak_rss_kib": results.iter().map(|r| r.2).collect::<Vec<_>>(),
            "peak_growth": growth,
        }));
    }
    Value::Array(cases)
}

/// naga_oil 0.23 composing and validating variants of a standard-shader pass from our module
/// tree exported in its dialect, warm: one Composer with every module registered, created
/// before any timing.
pub struct NagaOil {
    composer: naga_oil::compose::Composer,
    program: String,
    defs: Vec<std::collections::HashMap<String, naga_oil::compose::ShaderDefValue>>,
    validator: naga::valid::Validator,
}

impl NagaOil {
    /// Ready to build each of `choices`; `None` if the export does not register.
    pub fn new(
        lib: &Library,
        pass: &wgsl_variants::Pass,
        choices: &[wgsl_variants::Choice],
    ) -> Option<NagaOil> {
        use naga_oil::compose::ShaderDefValue;
        let modules = wgsl_variants::emit::naga_oil::export_all(lib, Some("wv")).ok()?;
        let composer = naga_oil_composer(&modules).ok()?;
        let program = modules
            .iter()
            .find(|m| m.path == "standard/my_lighting")?
            .source
            .clone();
        let define = if pass.name == "Deferred" {
            "DEFERRED_PASS"
        } else {
            "FORWARD_BASE_PASS"
        };
        let defs = choices
            .iter()
            .map(|c| {
                std::iter::once(define)
                    .chain(c.keywords(pass))
                    .map(|k| (k.to_string(), ShaderDefValue::Bool(true)))
                    .collect()
            })
            .collect();
        let validator = validator();
        Some(NagaOil {
            composer,
            program,
            defs,
            validator,
        })
    }

    /// naga_oil's own output for every choice, written back to WGSL by naga: the work that
    /// remains for naga once naga_oil has composed (naga_oil imports only the items a
    /// program uses, so its modules are smaller than the whole text this crate validates).
    pub fn output_texts(&mut self) -> Option<Vec<String>> {
        use naga_oil::compose::NagaModuleDescriptor;
        let defs = self.defs.clone();
        defs.into_iter()
            .map(|shader_defs| {
                let module = self
                    .composer
                    .make_naga_module(NagaModuleDescriptor {
                        source: &self.program,
                        file_path: "standard/my_lighting.wgsl",
                        shader_defs,
                        ..Default::default()
                    })
                    .ok()?;
                let info = self.validator.validate(&module).ok()?;
                naga::back::wgsl::write_string(
                    &module,
                    &info,
                    naga::back::wgsl::WriterFlags::empty(),
                )
                .ok()
            })
            .collect()
    }

    /// Composes and validates the variants `range` of the choices; whether all were valid.
    pub fn build(&mut self, range: std::ops::Range<usize>) -> bool {
        use naga_oil::compose::NagaModuleDescriptor;
        let mut ok = true;
        for shader_defs in &self.defs[range] {
            match self.composer.make_naga_module(NagaModuleDescriptor {
                source: &self.program,
                file_path: "standard/my_lighting.wgsl",
                shader_defs: shader_defs.clone(),
                ..Default::default()
            }) {
                Ok(module) => ok &= self.validator.validate(&module).is_ok(),
                Err(_) => ok = false,
            }
        }
        ok
    }
}

/// naga_oil: creating a Composer and registering the bundled modules (its cold start).
pub fn naga_oil_cold(lib: &Library, rounds: usize) -> Option<Duration> {
    let modules = wgsl_variants::emit::naga_oil::export_all(lib, Some("wv")).ok()?;
    Some(median(rounds, || {
        naga_oil_composer(&modules).expect("registers");
    }))
}

/// A new naga_oil Composer with every exported module registered, or the first module that
/// naga_oil refuses with naga_oil's error rendered.
pub fn naga_oil_composer(
    modules: &[wgsl_variants::emit::naga_oil::NagaOilModule],
) -> Result<naga_oil::compose::Composer, String> {
    use naga_oil::compose::{ComposableModuleDescriptor, Composer, ShaderLanguage};
    let mut composer = Composer::default();
    for m in modules {
        composer
            .add_composable_module(ComposableModuleDescriptor {
                source: &m.source,
                file_path: &format!("{}.wgsl", m.path),
                language: ShaderLanguage::Wgsl,
                as_name: None,
                additional_imports: &[],
                shader_defs: Default::default(),
            })
            .map_err(|e| {
                let rendered = e.emit_to_string(&Composer::default());
                format!("{}: {rendered}\n{}", m.path, m.source)
            })?;
    }
    Ok(composer)
}
