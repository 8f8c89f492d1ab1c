//! Shared pieces of the benchmarks: timing, machine description, the summary file, memory.
#![allow(dead_code)] // each bench uses a subset

use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use wgsl_variants::validate::validate_pass_with;
use wgsl_variants::{Library, Space};

/// Median wall time of `rounds` runs of `f` (after one warm-up run).
pub fn median(rounds: usize, mut f: impl FnMut()) -> Duration {
    f();
    let mut times: Vec<Duration> = (0..rounds.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    times.sort();
    times[times.len() / 2]
}

/// What the numbers were measured on.
pub fn machine() -> Value {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_default();
    json!({ "cpu": cpu, "cores": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1) })
}

/// `target/bench-summary.json`, next to cargo's target dir.
fn summary_path() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("bench-summary.json")
}

/// Merges `values` (an object) into `target/bench-summary.json`, so every bench adds its
/// measurements to one file.
pub fn write_summary(values: Value) {
    let path = summary_path();
    let mut summary: Value = std::fs::read_to_string(&path)
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
        .unwrap_or_else(|| json!({}));
    if let (Some(into), Some(from)) = (summary.as_object_mut(), values.as_object()) {
        for (k, v) in from {
            into.insert(k.clone(), v.clone());
        }
    }
    let text = serde_json::to_string_pretty(&summary).expect("json");
    std::fs::create_dir_all(path.parent().expect("parent")).expect("target dir");
    std::fs::write(&path, text + "\n").expect("write bench summary");
    println!("wrote {}", path.display());
}

/// A synthetic library: one pass with `keywords` two-way multi_compile sets, each keyword
/// guarding a function of its own, so every variant is distinct.
pub fn synthetic(keywords: usize) -> Library {
    let mut body = String::new();
    for k in 0..keywords {
        body.push_str(&format!("#pragma multi_compile _ K{k}\n"));
    }
    for k in 0..keywords {
        body.push_str(&format!(
            "#ifdef K{k}\nfn f{k}(x: f32) -> f32 {{ return x * {k}.0 + 1.0; }}\n#endif\n"
        ));
    }
    body.push_str("@fragment fn fs_main() -> @location(0) vec4f { return vec4f(1.0); }\n");
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

/// In a child process (`BENCH_MEMORY_CHILD=keywords`): validate every variant of a synthetic
/// space and print the peak RSS. Returns true when this process is such a child.
pub fn memory_child() -> bool {
    let Some(k) = std::env::var("BENCH_MEMORY_CHILD")
        .ok()
        .and_then(|k| k.parse::<usize>().ok())
    else {
        return false;
    };
    let lib = synthetic(k);
    let pass = lib.passes().next().expect("pass");
    // Streamed: the variants are never collected.
    let report = validate_pass_with(&lib, pass, Space::full(pass).iter(), None, &|_| {});
    assert_eq!(report.invalid, 0);
    println!("variants {} peak_rss_kib {}", report.built, peak_rss_kib());
    true
}

/// Peak memory validating synthetic spaces of 4096 and 131072 variants, each in a fresh
/// process (peak RSS only grows within a process).
pub fn memory_flatness() -> Value {
    let exe = std::env::current_exe().expect("bench executable");
    let mut results = Vec::new();
    for keywords in [12usize, 17] {
        let out = Command::new(&exe)
            .env("BENCH_MEMORY_CHILD", keywords.to_string())
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
        results.push((field("variants"), field("peak_rss_kib")));
    }
    for (variants, kib) in &results {
        println!(
            "memory: {variants:>7} variants validated, peak RSS {:.1} MiB",
            *kib as f64 / 1024.0
        );
    }
    let growth = results[1].1 as f64 / results[0].1.max(1) as f64;
    println!(
        "memory: {}x the variants, {:.2}x the peak RSS",
        results[1].0 / results[0].0.max(1),
        growth
    );
    json!({ "variants": results.iter().map(|r| r.0).collect::<Vec<_>>(), "peak_rss_kib": results.iter().map(|r| r.1).collect::<Vec<_>>(), "peak_growth": growth })
}

/// naga_oil 0.23 composing and validating every variant of `pass` (a standard-shader pass)
/// from our module tree exported in its dialect, warm: one Composer with every module
/// registered, created outside the timing. `None` if the export does not compose.
pub fn naga_oil_deferred(
    lib: &Library,
    pass: &wgsl_variants::Pass,
    choices: &[wgsl_variants::Choice],
    rounds: usize,
) -> Option<Duration> {
    use naga_oil::compose::{NagaModuleDescriptor, ShaderDefValue};
    let modules = wgsl_variants::emit::naga_oil::export_all(lib, Some("wv")).ok()?;
    let mut composer = naga_oil_composer(&modules)?;
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
    let defs: Vec<std::collections::HashMap<String, ShaderDefValue>> = choices
        .iter()
        .map(|c| {
            std::iter::once(define)
                .chain(c.keywords(pass))
                .map(|k| (k.to_string(), ShaderDefValue::Bool(true)))
                .collect()
        })
        .collect();
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    );
    let mut ok = true;
    let time = median(rounds, || {
        for shader_defs in &defs {
            match composer.make_naga_module(NagaModuleDescriptor {
                source: &program,
                file_path: "standard/my_lighting.wgsl",
                shader_defs: shader_defs.clone(),
                ..Default::default()
            }) {
                Ok(module) => ok &= validator.validate(&module).is_ok(),
                Err(_) => ok = false,
            }
        }
    });
    ok.then_some(time)
}

/// naga_oil: creating a Composer and registering the bundled modules (its cold start).
pub fn naga_oil_cold(lib: &Library, rounds: usize) -> Option<Duration> {
    let modules = wgsl_variants::emit::naga_oil::export_all(lib, Some("wv")).ok()?;
    Some(median(rounds, || {
        naga_oil_composer(&modules).expect("registers");
    }))
}

/// A new naga_oil Composer with every exported module registered (`None` if one is refused).
fn naga_oil_composer(
    modules: &[wgsl_variants::emit::naga_oil::NagaOilModule],
) -> Option<naga_oil::compose::Composer> {
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
            .ok()?;
    }
    Some(composer)
}
