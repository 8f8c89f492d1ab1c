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

/// The median of some durations.
pub fn median_of(times: &[Duration]) -> Duration {
    let mut times = times.to_vec();
    times.sort();
    times[times.len() / 2]
}

/// The median over rounds of `a[r] / b[r]`: a paired ratio, so that a slow moment of the
/// machine, which slows both sides of a round alike, does not move it.
pub fn median_ratio(a: &[Duration], b: &[Duration]) -> f64 {
    let mut ratios: Vec<f64> = a
        .iter()
        .zip(b)
        .map(|(a, b)| a.as_secs_f64() / b.as_secs_f64())
        .collect();
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// Times contestants doing the same work, interleaved: in each round every contestant runs
/// on each of `slices` slices of the work in turn, the order rotating, so that drift of a
/// noisy machine falls on all of them alike. Returns, per contestant, its total time in each
/// round (after one warm-up pass over the first slice).
pub fn interleaved(
    rounds: usize,
    slices: usize,
    contestants: &mut [&mut dyn FnMut(usize)],
) -> Vec<Vec<Duration>> {
    let n = contestants.len();
    for c in contestants.iter_mut() {
        c(0);
    }
    let mut totals = vec![vec![Duration::ZERO; rounds.max(1)]; n];
    for (round, step) in (0..rounds.max(1)).flat_map(|r| (0..slices).map(move |s| (r, s))) {
        for k in 0..n {
            let c = (k + round + step) % n;
            let t = Instant::now();
            contestants[c](step);
            totals[c][round] += t.elapsed();
        }
    }
    totals
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

/// A synthetic library: one pass with a three-way `multi_compile` set and `keywords` two-way
/// sets (3 × 2^keywords variants), each keyword guarding a function of its own, so every
/// variant is distinct. With `dead`, one more two-way set changes no code, so every text is
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
            "#ifdef K{k}\nfn f{k}(x: f32) -> f32 {{ return x * {k}.0 + TIER; }}\n#endif\n"
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
        let composer = naga_oil_composer(&modules)?;
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
        let validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        );
        Some(NagaOil {
            composer,
            program,
            defs,
            validator,
        })
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
