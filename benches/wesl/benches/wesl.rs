//! Build + validate of the bundled `standard/Deferred` pass's whole space (6144 variants):
//! this crate vs the naga floor vs WESL (`wesl` 0.6.0) composing a hand-written WESL dialect
//! copy of the same module tree (`benches/wesl/wesl/`).
//!
//! From the repository root:
//!
//! ```text
//! CARGO_TARGET_DIR="$PWD/target" cargo bench --manifest-path benches/wesl/Cargo.toml
//! ```
//!
//! Before any timing every variant is checked (the ForwardBase pass's too, whose branches the
//! dialect copy translates as well): WESL's output must parse and validate with naga, and must
//! show a renderer what our text shows it (entry points, the resources each entry point uses,
//! vertex inputs and fragment outputs), with the same functions left after naga's dead-code
//! removal. Mismatches are printed and counted in the summary, not hidden.
//!
//! Then the contestants build the same slices of the space in turn, round after round
//! (`BENCH_ROUNDS`, default 5), on one thread, interleaved as in `benches/build.rs`:
//! (a) the naga floor (parse + validate) of our final texts, (b) this crate's compose +
//! validate, (c) WESL as `Compiler::new` sets it up (compile + `to_string`) + naga parse + validate,
//! (d) the naga floor of WESL's own outputs, (e) WESL tuned: no source map and no WESL-side
//! validation (naga validates). Ratios are medians over rounds of the ratio within a round;
//! they and the times are merged into `target/bench-summary.json` under `wesl_*` keys and
//! `ratio_vs_wesl` (ours / WESL, lower is faster).

// The timing helpers and the workload every bench shares (crates/test-support).
use test_support::{timing, workload};
use workload::{naga_floor, validator};

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Duration;

use naga::valid::{ModuleInfo, Validator};
use serde_json::json;
use wesl::syntax::ModulePath;
use wesl::resolver::VirtualResolver;
use wesl::{Compiler, Resolver};
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Library, Space, Variant};

/// The WESL dialect copy of the modules the Deferred and ForwardBase passes use, by WESL module path. Each
/// file's header says what the translation from `wgsl/` had to change.
const MODULES: [(&str, &str); 8] = [
    (
        "package::standard::my_lighting",
        include_str!("../wesl/standard/my_lighting.wesl"),
    ),
    (
        "package::standard::bindings",
        include_str!("../wesl/standard/bindings.wesl"),
    ),
    (
        "package::standard::surface",
        include_str!("../wesl/standard/surface.wesl"),
    ),
    (
        "package::lighting::brdf",
        include_str!("../wesl/lighting/brdf.wesl"),
    ),
    (
        "package::lighting::screen_shadow",
        include_str!("../wesl/lighting/screen_shadow.wesl"),
    ),
    (
        "package::deferred::gbuffer",
        include_str!("../wesl/deferred/gbuffer.wesl"),
    ),
    (
        "package::deferred::ldr",
        include_str!("../wesl/deferred/ldr.wesl"),
    ),
    (
        "package::deferred::probe",
        include_str!("../wesl/deferred/probe.wesl"),
    ),
];

/// The root module. It holds the entry points, and WESL keeps (strips down to) the root's
/// entry points and what they reach, so the pass's `#import standard/my_lighting` becomes
/// compiling this module.
const ROOT: &str = "package::standard::my_lighting";

/// The WESL release compared (pinned in Cargo.toml: the last one that builds on Rust < 1.96).
const WESL_VERSION: &str = "0.4.0";

/// The Deferred pass's `#define`, a WESL feature the caller sets.
const PASS_DEFINE: &str = "DEFERRED_PASS";

/// The ForwardBase pass's `#define`: the dialect copy translates its branches too, and the
/// check covers that pass as well (it is not timed).
const FORWARD_DEFINE: &str = "FORWARD_BASE_PASS";

/// Every module of [`MODULES`] in a `VirtualResolver`, as a WESL user embedding its shaders
/// would register them.
fn virtual_resolver() -> VirtualResolver<'static> {
    let mut resolver = VirtualResolver::new();
    for (path, source) in MODULES {
        resolver.add_module(path.parse().expect("module path"), Cow::Borrowed(source));
    }
    resolver
}

/// One variant's WESL features: the pass's define, and every keyword of the pass on or off
/// (all of them set each time, since the compiler keeps the previous variant's flags).
fn set_features<R: Resolver>(
    wesl: &mut Compiler<R>,
    define: &str,
    keywords: &[&str],
    on: &[&str],
) {
    wesl.options.features.set(define, true);
    for k in keywords {
        wesl.options.features.set(k, on.contains(k));
    }
}

/// WESL's build of some variants: compile, write WGSL, and naga parse + validate it (WESL
/// does not validate fully; naga is what a wgpu renderer would run on the text).
fn wesl_build<R: Resolver>(
    wesl: &mut Compiler<R>,
    root: &ModulePath,
    keywords: &[&str],
    on: &[Vec<&str>],
    validator: &mut Validator,
) {
    for variant in on {
        set_features(wesl, PASS_DEFINE, keywords, variant);
        let text = wesl.compile_module(root).expect("WESL compiles").to_string();
        let module = naga::front::wgsl::parse_str(&text).expect("parses");
        validator.validate(&module).expect("valid");
    }
}

/// What a renderer sees of one entry point.
#[derive(Debug, PartialEq, Eq)]
struct EntryInterface {
    /// Vertex or fragment.
    stage: naga::ShaderStage,
    /// The entry point's name (root-module names are not mangled by WESL).
    name: String,
    /// (group, binding, address space and type) of each resource the entry point uses,
    /// directly or through the functions it calls (naga's analysis).
    resources: BTreeSet<(u32, u32, String)>,
    /// `@location` inputs.
    inputs: usize,
    /// `@location` outputs (the G-buffer targets of the fragment stage).
    outputs: usize,
}

/// `@location`s of an argument or result: itself, or the members of its struct.
fn locations(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    binding: &Option<naga::Binding>,
) -> usize {
    match binding {
        Some(naga::Binding::Location { .. }) => 1,
        Some(naga::Binding::BuiltIn(_)) => 0,
        None => match &module.types[ty].inner {
            naga::TypeInner::Struct { members, .. } => members
                .iter()
                .filter(|m| matches!(m.binding, Some(naga::Binding::Location { .. })))
                .count(),
            _ => 0,
        },
    }
}

/// A resource's address space and type, without names (WESL mangles imported names): structs
/// by member count and size, which is what a bind group layout needs.
fn resource_kind(module: &naga::Module, var: &naga::GlobalVariable) -> String {
    let ty = match &module.types[var.ty].inner {
        naga::TypeInner::Struct { members, span } => {
            format!("struct of {} members, {span} bytes", members.len())
        }
        other => format!("{other:?}"),
    };
    format!("{:?} {ty}", var.space)
}

/// The entry points of a validated module, sorted by stage and name.
fn interface(module: &naga::Module, info: &ModuleInfo) -> Vec<EntryInterface> {
    let mut entries: Vec<EntryInterface> = module
        .entry_points
        .iter()
        .enumerate()
        .map(|(i, ep)| {
            let uses = info.get_entry_point(i);
            let resources = module
                .global_variables
                .iter()
                .filter(|(h, _)| !uses[*h].is_empty())
                .filter_map(|(_, var)| {
                    let b = var.binding.as_ref()?;
                    Some((b.group, b.binding, resource_kind(module, var)))
                })
                .collect();
            let inputs = ep
                .function
                .arguments
                .iter()
                .map(|a| locations(module, a.ty, &a.binding))
                .sum();
            let outputs = ep
                .function
                .result
                .as_ref()
                .map_or(0, |r| locations(module, r.ty, &r.binding));
            EntryInterface {
                stage: ep.stage,
                name: ep.name.clone(),
                resources,
                inputs,
                outputs,
            }
        })
        .collect();
    entries.sort_by(|a, b| (a.name.as_str(), a.stage as u8).cmp(&(b.name.as_str(), b.stage as u8)));
    entries
}

/// Resources a module declares, used or not.
fn declared(module: &naga::Module) -> BTreeSet<(u32, u32)> {
    module
        .global_variables
        .iter()
        .filter_map(|(_, v)| v.binding.as_ref().map(|b| (b.group, b.binding)))
        .collect()
}

/// The code an entry point can run, as naga sees it after dead-code removal (our texts keep
/// unused functions, WESL strips them): per function and entry point, (arguments, locals,
/// expressions, named expressions, i.e. `let`s), sorted. Names are left out (WESL mangles
/// them), and so are statement counts, which the `{ }` blocks WESL forced change.
fn shape(mut module: naga::Module) -> Vec<(usize, usize, usize, usize)> {
    naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
    let of = |f: &naga::Function| {
        (
            f.arguments.len(),
            f.local_variables.len(),
            f.expressions.len(),
            f.named_expressions.len(),
        )
    };
    let mut shapes: Vec<_> = module
        .functions
        .iter()
        .map(|(_, f)| of(f))
        .chain(module.entry_points.iter().map(|ep| of(&ep.function)))
        .collect();
    shapes.sort();
    shapes
}

/// Parses and validates a text, with naga's analysis.
fn parse_validate(
    validator: &mut Validator,
    text: &str,
) -> Result<(naga::Module, ModuleInfo), String> {
    let module = naga::front::wgsl::parse_str(text).map_err(|e| e.emit_to_string(text))?;
    let info = validator
        .validate(&module)
        .map_err(|e| format!("{:?}", e.into_inner()))?;
    Ok((module, info))
}

/// A WGSL text's top-level declarations (WESL writes them separated by blank lines), sorted.
fn declarations(text: &str) -> Vec<&str> {
    let mut d: Vec<&str> = text.split("\n\n").map(str::trim).collect();
    d.sort_unstable();
    d
}

/// The correctness check's counts.
#[derive(Default)]
struct Check {
    /// Variants checked; WESL's output of each one validated with naga (or the bench stops).
    variants: usize,
    /// Variants whose WESL output did not show a renderer what ours does.
    interface_mismatches: usize,
    /// Variants whose code after naga's dead-code removal differs in shape.
    shape_mismatches: usize,
    /// Variants where WESL's output declares a resource its entry points do not use.
    wesl_unused_declared: usize,
    /// Variants where our text declares a resource its entry points do not use.
    ours_unused_declared: usize,
    /// Those resources of ours, (group, binding), with the number of variants.
    ours_unused: BTreeMap<(u32, u32), usize>,
    /// The first few mismatches, described.
    examples: Vec<String>,
}

/// Checks every variant of `pass` (`define` its `#define`): WESL, as `Compiler::new` sets it
/// up and tuned, must compile it, naga must validate the output, which must show a renderer
/// what our text shows it. Returns the counts and WESL's output texts.
fn check_pass(
    lib: &Library,
    pass: &wgsl_variants::Pass,
    define: &str,
    root: &ModulePath,
) -> (Check, Vec<String>) {
    let (mut wesl, mut wesl_tuned) = (compiler(false), compiler(true));
    let keywords: Vec<&str> = pass.keywords().collect();
    let choices = Space::full(pass).enumerate(1_000_000).expect("enumerable");
    let mut check = Check {
        variants: choices.len(),
        ..Check::default()
    };
    let mut v = validator();
    let mut wesl_texts = Vec::with_capacity(choices.len());
    for choice in choices {
        let variant = choice.keywords(pass);
        let label = format!("standard/{} {{{}}}", pass.name, variant.join(" "));
        set_features(&mut wesl, define, &keywords, &variant);
        let text = match wesl.compile_module(root) {
            Ok(out) => out.to_string(),
            Err(e) => panic!("{label}: WESL does not compile:\n{e}"),
        };
        set_features(&mut wesl_tuned, define, &keywords, &variant);
        let tuned = wesl_tuned
            .compile_module(root)
            .expect("tuned WESL compiles")
            .to_string();
        // The same declarations; their order may differ (WESL's module order is not fixed).
        assert_eq!(
            declarations(&tuned),
            declarations(&text),
            "{label}: the tuned WESL set-up writes other declarations"
        );
        let ours = lib.wgsl(&Variant { pass, choice });
        let (wm, wi) = parse_validate(&mut v, &text)
            .unwrap_or_else(|e| panic!("{label}: naga rejects WESL's output: {e}\n{text}"));
        let (om, oi) = parse_validate(&mut v, &ours).expect("our text validates");
        let (wf, of) = (interface(&wm, &wi), interface(&om, &oi));
        let used = |f: &[EntryInterface]| -> BTreeSet<(u32, u32)> {
            f.iter()
                .flat_map(|e| e.resources.iter().map(|r| (r.0, r.1)))
                .collect()
        };
        check.wesl_unused_declared += usize::from(declared(&wm) != used(&wf));
        let ours_unused: Vec<_> = declared(&om).difference(&used(&of)).copied().collect();
        check.ours_unused_declared += usize::from(!ours_unused.is_empty());
        for r in ours_unused {
            *check.ours_unused.entry(r).or_default() += 1;
        }
        if wf != of {
            check.interface_mismatches += 1;
            if check.examples.len() < 5 {
                check
                    .examples
                    .push(format!("{label}: interface\n  ours {of:?}\n  wesl {wf:?}"));
            }
        }
        let (ws, os) = (shape(wm), shape(om));
        if ws != os {
            check.shape_mismatches += 1;
            if check.examples.len() < 5 {
                check.examples.push(format!(
                    "{label}: shape after dead-code removal\n  ours {os:?}\n  wesl {ws:?}"
                ));
            }
        }
        wesl_texts.push(text);
    }
    (check, wesl_texts)
}

/// A WESL compiler over [`virtual_resolver`], as `Compiler::new` sets it up, or `tuned`: no
/// source map and no WESL-side validation, which only make WESL's own error messages better
/// (naga validates the output anyway, in every contestant).
///
/// Parsed modules cannot be kept between compiles: wgsl-parse's identifiers are shared
/// (`Arc<RwLock<String>>`) and WESL's mangling renames them in place, so a cloned tree comes
/// back renamed; every compile parses the modules again, as with any of WESL's resolvers.
fn compiler(tuned: bool) -> Compiler<VirtualResolver<'static>> {
    let mut options = wesl::CompileOptions::default();
    if tuned {
        options.validate = false;
        options.sourcemap = false;
    }
    Compiler::new(options).with_resolver(virtual_resolver())
}

/// Checks every variant, then times the contestants and writes the summary.
impl Check {
    /// Prints the counts and the first mismatches.
    fn print(&self, what: &str) {
        println!(
            "check {what}, {} variants: WESL's output of each validates with naga; interface \
             (entry points, resources used, inputs, outputs) differs in {}, code shape after \
             naga's dead-code removal in {}",
            self.variants, self.interface_mismatches, self.shape_mismatches
        );
        println!(
            "  declared but unused by the entry points: WESL in {} variants, ours in {} {:?} \
             ((group, binding): variants; the interface compares what the entry points use)",
            self.wesl_unused_declared, self.ours_unused_declared, self.ours_unused
        );
        for e in &self.examples {
            println!("  MISMATCH {e}");
        }
    }

    /// The counts for the summary file.
    fn json(&self) -> serde_json::Value {
        json!({
            "variants": self.variants,
            "naga_valid": self.variants,
            "interface_mismatches": self.interface_mismatches,
            "shape_mismatches": self.shape_mismatches,
            "wesl_declared_unused_variants": self.wesl_unused_declared,
            "ours_declared_unused_variants": self.ours_unused_declared,
            "ours_declared_unused": self
                .ours_unused
                .iter()
                .map(|((g, b), n)| json!({"group": g, "binding": b, "variants": n}))
                .collect::<Vec<_>>(),
        })
    }
}

fn main() {
    let rounds = timing::rounds();
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let pass = lib.pass("standard", "Deferred").expect("Deferred");
    let choices = Space::full(pass).enumerate(1_000_000).expect("enumerable");
    let n = choices.len() as f64;
    let keywords: Vec<&str> = pass.keywords().collect();
    let on: Vec<Vec<&str>> = choices.iter().map(|c| c.keywords(pass)).collect();
    let texts = workload::final_texts(&lib, pass, &choices);

    // WESL's warm setup, outside timing: the modules registered once; one compiler per
    // contestant, since features are set on the compiler.
    let root: ModulePath = ROOT.parse().expect("root path");
    let (mut wesl, mut wesl_tuned) = (compiler(false), compiler(true));

    // The check (both passes: the dialect copy translates both), and WESL's own outputs of
    // the Deferred pass for (d).
    let forward_pass = lib.pass("standard", "ForwardBase").expect("ForwardBase");
    let (forward, _) = check_pass(&lib, forward_pass, FORWARD_DEFINE, &root);
    let (check, wesl_texts) = check_pass(&lib, pass, PASS_DEFINE, &root);
    let bytes = texts.iter().map(String::len).sum::<usize>() as f64 / n;
    let wesl_bytes = wesl_texts.iter().map(String::len).sum::<usize>() as f64 / n;
    println!(
        "standard/Deferred: {} variants; WESL {} (default features off) composing wesl/ ({} modules)",
        choices.len(),
        WESL_VERSION,
        MODULES.len()
    );
    check.print("standard/Deferred");
    forward.print("standard/ForwardBase (checked, not timed)");
    println!(
        "output texts: ours {:.1} KB on average (not tree-shaken), WESL's {:.1} KB (stripped to \
         what the entry points reach)",
        bytes / 1024.0,
        wesl_bytes / 1024.0
    );

    // One thread: this crate validates on rayon's pool, so it runs inside a pool of one.
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let slices = 12;
    let per_slice = choices.len().div_ceil(slices);
    let range = |s: usize| s * per_slice..((s + 1) * per_slice).min(choices.len());
    let (mut v_floor, mut v_wesl, mut v_wesl_floor, mut v_tuned) =
        (validator(), validator(), validator(), validator());
    let times = timing::interleaved(
        rounds,
        slices,
        &mut [
            &mut |s| naga_floor(&mut v_floor, &texts[range(s)]),
            &mut |s| {
                one.install(|| {
                    let report = validate_pass(&lib, pass, &choices[range(s)], &|_| {});
                    assert_eq!(report.invalid, 0);
                })
            },
            &mut |s| wesl_build(&mut wesl, &root, &keywords, &on[range(s)], &mut v_wesl),
            &mut |s| naga_floor(&mut v_wesl_floor, &wesl_texts[range(s)]),
            &mut |s| {
                wesl_build(
                    &mut wesl_tuned,
                    &root,
                    &keywords,
                    &on[range(s)],
                    &mut v_tuned,
                )
            },
        ],
    );
    let [floor, ours, wesl_t, wesl_floor, tuned] = [0, 1, 2, 3, 4].map(|i| &times[i]);

    let per = |d: Duration| d.as_secs_f64() * 1e3 / n;
    println!(
        "{:<58} {:>10} {:>12}",
        format!(
            "{} variants, {rounds} rounds, median, 1 thread",
            choices.len()
        ),
        "total",
        "per variant"
    );
    for (name, times) in [
        ("(a) naga floor: parse + validate our final texts", floor),
        ("(b) wgsl-variants: compose + validate", ours),
        (
            "(c) WESL (Compiler::new) compile + naga parse + validate",
            wesl_t,
        ),
        ("(d) naga floor on WESL's own outputs", wesl_floor),
        (
            "(e) WESL tuned (no sourcemap, no WESL validation) + naga",
            tuned,
        ),
    ] {
        let d = timing::median_of(times);
        println!(
            "{name:<58} {:>8.0}ms {:>9.3}ms",
            d.as_secs_f64() * 1e3,
            per(d)
        );
    }
    let ratio_floor = timing::median_ratio(ours, floor);
    let ratio_wesl = timing::median_ratio(ours, wesl_t);
    let ratio_tuned = timing::median_ratio(ours, tuned);
    let wesl_vs_own = timing::median_ratio(wesl_t, wesl_floor);
    let tuned_vs_own = timing::median_ratio(tuned, wesl_floor);
    let wesl_vs_floor = timing::median_ratio(wesl_t, floor);
    println!("ratios are medians over rounds of the ratio within each round (lower is faster):");
    println!("  ours vs naga floor of our texts: {ratio_floor:.3}");
    println!(
        "  ratio_vs_wesl (ours / WESL): {ratio_wesl:.3} ({:.2}x faster); vs WESL tuned: \
         {ratio_tuned:.3} ({:.2}x faster)",
        1.0 / ratio_wesl,
        1.0 / ratio_tuned
    );
    println!(
        "  WESL vs the naga floor of its own outputs: {wesl_vs_own:.3} (tuned {tuned_vs_own:.3}); \
         vs the floor of our texts: {wesl_vs_floor:.3}"
    );

    timing::write_summary(json!({
        "wesl_machine": timing::machine(),
        "wesl_version": WESL_VERSION,
        "wesl_rounds": rounds,
        "wesl_variants": choices.len(),
        "wesl_method": "1 thread; contestants interleaved slice by slice; ratios are medians of per-round ratios; WESL = Compiler::new + VirtualResolver built once, compile + to_string + naga parse + validate",
        "wesl_check": check.json(),
        "wesl_check_forward_base": forward.json(),
        "wesl_ours_ms_per_variant": per(timing::median_of(ours)),
        "wesl_naga_floor_ms_per_variant": per(timing::median_of(floor)),
        "wesl_ms_per_variant": per(timing::median_of(wesl_t)),
        "wesl_tuned_ms_per_variant": per(timing::median_of(tuned)),
        "wesl_own_output_floor_ms_per_variant": per(timing::median_of(wesl_floor)),
        "wesl_ours_ratio_vs_naga_floor": ratio_floor,
        "ratio_vs_wesl": ratio_wesl,
        "wesl_ratio_vs_wesl_tuned": ratio_tuned,
        "wesl_ratio_vs_own_output_floor": wesl_vs_own,
        "wesl_tuned_ratio_vs_own_output_floor": tuned_vs_own,
        "wesl_ratio_vs_naga_floor": wesl_vs_floor,
        "wesl_output_bytes_avg": wesl_bytes,
        "wesl_ours_composed_bytes_avg": bytes,
    }));
}
