//! The properties each fuzz target checks, shared with `tests/fuzz_regressions.rs` (every saved
//! input is replayed through exactly the same code), `tests/line_breaks.rs` and
//! `tests/pass_through.rs`.

use std::collections::HashSet;

use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Library, Space, Variant};

/// Any text as a module: parsing its directives never panics, and composing what parses stays
/// within the input's size (no blow-up).
pub fn preprocess(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let main = "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma shader_feature _ B C\n#import m\n#endpass\n";
    let Ok(lib) = Library::from_sources([("m.wgsl", text), ("main.wgsl", main)]) else {
        return;
    };
    for keywords in [&[][..], &["A"][..], &["A", "C"][..]] {
        if let Ok(v) = lib.variant("s", "P", keywords) {
            let out = lib.wgsl(&v);
            assert!(
                out.len() <= text.len() + text.lines().count() + 1,
                "output larger than its input"
            );
        }
    }
}

/// Any `#if` expression: parsing is bounded and never panics; evaluating what parses never
/// panics, integer edge cases included.
pub fn expr(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = wgsl_variants::preprocess::eval_expr(text, &|n: &str| match n.len() % 3 {
        0 => None,
        1 => Some(i64::MIN),
        _ => Some(n.len() as i64),
    });
}

/// Any pass body (pragmas, tags, defines, conditionals): loading never panics, and every
/// variant of what loads (up to 64 per pass) composes.
pub fn pragmas(data: &[u8]) {
    let Ok(body) = std::str::from_utf8(data) else {
        return;
    };
    let main = format!("#shader s\n#pass P\n{body}\n#endpass\n");
    let Ok(lib) = Library::from_sources([("main.wgsl", main)]) else {
        return;
    };
    for pass in lib.passes() {
        let _ = Space::full(pass).count();
        if let Ok(choices) = Space::after_skip(pass).enumerate(64) {
            for choice in choices {
                let _ = lib.wgsl(&Variant { pass, choice });
            }
        }
    }
}

/// A declaration file (`wgsl-variants.toml`) of any text, over a fixed tree of two modules
/// (`lit.wgsl`, `lib/color.wgsl`): loading never panics (malformed TOML, wrong types, huge or
/// odd values, excludes, constraints are diagnostics), and a tree that loads lists, plans and
/// composes its variants without panicking.
pub fn declaration(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let files = [
        (
            "lit.wgsl",
            "#import lib::color::tint\n@fragment fn fs() -> @location(0) vec4f {\n#ifdef A\n    return tint();\n#endif\n    return vec4f(1.0);\n}\n",
        ),
        (
            "lib/color.wgsl",
            "#define_import_path lib::color\nfn tint() -> vec4f { return vec4f(0.5); }\n",
        ),
    ];
    if let Ok(lib) = Library::from_declared_sources(&text, files) {
        for pass in lib.passes() {
            for choice in Space::full(pass).iter().take(16) {
                let _ = lib.wgsl(&Variant { pass, choice });
            }
        }
    }
}

/// Shard reports for `merge` (`validate --json` output, edited or not): the input is split at
/// `\0` into at most four reports, named `K/N`. Merging never panics; a merge that succeeds
/// gives totals that agree with its passes and failures (a shard that contradicts itself is
/// refused, never summed).
pub fn merge(data: &[u8]) {
    let parts: Vec<String> = data
        .split(|&b| b == 0)
        .take(4)
        .map(|b| String::from_utf8_lossy(b).into_owned())
        .collect();
    let n = parts.len();
    let inputs: Vec<(String, String)> = parts
        .into_iter()
        .enumerate()
        .map(|(k, text)| (format!("{}/{n}", k + 1), text))
        .collect();
    if let Ok((merged, ok)) = wgsl_variants::merge::validate::merge_reports(&inputs) {
        let value: serde_json::Value =
            serde_json::from_str(&merged).expect("a merged report is JSON");
        let totals = &value["totals"];
        let (built, valid, invalid) = (
            totals["built"].as_u64().expect("built"),
            totals["valid"].as_u64().expect("valid"),
            totals["invalid"].as_u64().expect("invalid"),
        );
        assert_eq!(valid + invalid, built, "merged totals add up: {merged}");
        assert_eq!(ok, invalid == 0, "ok says whether a variant failed");
    }
}

/// A cache segment of any bytes, read by a cache that trusts one secret: opening and importing
/// never panic, every record is either trusted or counted as corrupt, and nothing is trusted
/// that was not signed with the secret (a record copied from a segment of another secret).
pub fn cache(data: &[u8]) {
    use wgsl_variants::cache::{Secret, ValidCache, import_with, key};
    let secret = Secret::from_hex(&"3".repeat(64)).expect("64 hex digits");
    let Ok(dir) = tempfile::tempdir() else { return };
    let folder = dir.path().join(key());
    if std::fs::create_dir_all(&folder).is_err()
        || std::fs::write(folder.join("input.seg"), data).is_err()
    {
        return;
    }
    let cache = ValidCache::open_with(dir.path(), secret.clone());
    // A segment's records are 48 bytes after its header: no more entries than that allows.
    assert!(cache.len() <= data.len() / 48, "entries from nowhere");
    let file = dir.path().join("export.bin");
    if cache.export(&file).is_ok() {
        let other = Secret::from_hex(&"4".repeat(64)).expect("64 hex digits");
        let Ok(elsewhere) = tempfile::tempdir() else {
            return;
        };
        if let Ok(imported) = import_with(elsewhere.path(), &file, &other) {
            // Signed with another secret: every record of the export is untrusted there.
            assert_eq!(
                imported.entries, 0,
                "a record of another secret was trusted"
            );
        }
    }
    let _ = import_with(dir.path(), &folder.join("input.seg"), &secret);
}

/// Several modules with imports between them (cycles, diamonds, missing and escaping paths):
/// the input is split into files at `\0`, named m0..mN. Loading never panics or hangs.
pub fn loader(data: &[u8]) {
    if let Ok(lib) = Library::from_sources(split_files(data, 64, "wgsl")) {
        for pass in lib.passes() {
            if let Ok(v) = lib.variant(&pass.shader, &pass.name, &[] as &[&str]) {
                let _ = lib.wgsl(&v);
            }
        }
    }
}

/// naga_oil's dialect: the input is split into files at `\0` (m0 is the entry, each file may
/// `#define_import_path`), declared with keywords `A` and `B`. Loading never panics; neither
/// does composing a variant through naga_oil (its errors become diagnostics).
pub fn naga_oil(data: &[u8]) {
    declared_tree(split_files(data, 16, "wgsl"), "m0.wgsl");
}

/// WESL's dialect: the input is split into files at `\0` (m0.wesl is the entry; `@if`
/// attributes, `import package::m1::f;`), declared with keywords `A` and `B`. Loading (the
/// `@if` tree read from wgsl-parse's syntax tree) never panics; neither does composing a
/// variant through the `wesl` crate (its errors become diagnostics), nor the audit.
pub fn wesl(data: &[u8]) {
    declared_tree(split_files(data, 16, "wesl"), "m0.wesl");
}

/// The input split into files at `\0`, at most `max`, named `m0.EXT`, `m1.EXT`…
fn split_files(data: &[u8], max: usize, ext: &str) -> Vec<(String, String)> {
    data.split(|&b| b == 0)
        .take(max)
        .enumerate()
        .map(|(i, bytes)| {
            (
                format!("m{i}.{ext}"),
                String::from_utf8_lossy(bytes).into_owned(),
            )
        })
        .collect()
}

/// A tree of `files` declared with one pass (keywords `A` and `B`) composing `entry`: every
/// variant composes and validates or fails with a diagnostic; the audit runs.
fn declared_tree(files: Vec<(String, String)>, entry: &str) {
    let declaration = format!(
        "[[shader]]\nname = \"s\"\nentry = \"{entry}\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"A\"], [\"_\", \"B\"]]\n"
    );
    if let Ok(lib) = Library::from_declared_sources(&declaration, files)
        && let Ok(pass) = lib.pass("s", "P")
    {
        for choice in Space::full(pass).iter() {
            let _ = lib.naga_module(&Variant { pass, choice });
        }
        let _ = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default());
    }
}

/// Any text as a module, imported by a pass with keywords `A` and `B`: see
/// [`lean_matches_emitted`]. Inputs past 16 KiB are skipped to keep naga's share bounded.
pub fn lean(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if text.len() > 16 * 1024 {
        return;
    }
    let main = "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma shader_feature _ B\n#import m\n#endpass\n";
    if let Ok(lib) = Library::from_sources([("m.wgsl", text), ("main.wgsl", main)]) {
        lean_matches_emitted(&lib);
    }
}

/// naga's verdict on a WGSL text, comparable across texts whose spans differ: the validated
/// module written back to WGSL, or the error message (`Err`).
pub fn naga_outcome(text: &str) -> Result<String, String> {
    let module = naga::front::wgsl::parse_str(text).map_err(|e| e.message().to_string())?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| e.as_inner().to_string())?;
    // naga 30's WGSL writer panics on a few valid modules (an `unreachable!` in constant
    // expressions): that module is then compared as SPIR-V, which carries no spans either.
    let wgsl = quietly(|| {
        naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty())
    });
    Ok(match wgsl {
        Some(Ok(wgsl)) => wgsl,
        Some(Err(e)) => format!("<wgsl-out failed: {e}>"),
        None => {
            let options = naga::back::spv::Options::default();
            match quietly(|| naga::back::spv::write_vec(&module, &info, &options, None)) {
                Some(Ok(words)) => format!("<SPIR-V {words:x?}>"),
                Some(Err(e)) => format!("<wgsl-out panicked, spv-out failed: {e}>"),
                None => "<wgsl-out and spv-out panicked>".to_string(),
            }
        }
    })
}

/// Whether two naga outcomes are the same program: the same module written back, or both
/// rejected. Messages are not compared: naga quotes the rest of the text in some (an
/// unterminated block comment), and that rest loses its blank lines in the lean text.
pub fn same_outcome(a: &Result<String, String>, b: &Result<String, String>) -> bool {
    match (a, b) {
        (Ok(a), Ok(b)) => a == b,
        (Err(_), Err(_)) => true,
        _ => false,
    }
}

/// Runs `f`, turning a panic into `None` without printing it (and without the fuzzer's
/// abort-on-panic hook). Hooks are process-wide, so swaps are serialised.
fn quietly<T>(f: impl FnOnce() -> T) -> Option<T> {
    static HOOK: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = HOOK.lock().unwrap_or_else(|e| e.into_inner());
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).ok();
    std::panic::set_hook(hook);
    result
}

/// For every variant (up to 64 per pass): naga gives the same outcome for the lean text
/// (`Library::compose_text`, what is hashed and validated) as for the emitted text
/// (`Library::compose`), and `validate` reports a variant invalid exactly when naga rejects
/// its emitted text. Returns the number of variants compared.
pub fn lean_matches_emitted(lib: &Library) -> usize {
    let mut compared = 0;
    for pass in lib.passes() {
        let Ok(choices) = Space::full(pass).enumerate(64) else {
            continue;
        };
        let report = validate_pass(lib, pass, &choices, &|_| {});
        let failing: HashSet<Vec<String>> = report
            .failures
            .iter()
            .flat_map(|f| f.keyword_sets.iter().cloned())
            .collect();
        for choice in choices {
            let variant = Variant { pass, choice };
            let full = lib.compose(&variant).text;
            let lean = lib.compose_text(&variant).text;
            let emitted = naga_outcome(&full);
            let lean_outcome = naga_outcome(&lean);
            assert!(
                same_outcome(&emitted, &lean_outcome),
                "naga differs on the lean and the emitted text of {}: {emitted:?} vs {lean_outcome:?}\nemitted: {full:?}\nlean: {lean:?}",
                variant.label()
            );
            let keywords: Vec<String> = variant.keywords().into_iter().map(String::from).collect();
            assert_eq!(
                failing.contains(&keywords),
                emitted.is_err(),
                "validate and naga disagree on {}: {emitted:?}\nemitted: {full:?}",
                variant.label()
            );
            compared += 1;
        }
    }
    compared
}
