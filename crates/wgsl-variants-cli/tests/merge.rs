//! `merge` and the shared cache, driving the built binary: shards in separate processes put
//! back together byte for byte, concurrent writers of one cache, and every bad shard set
//! refused with the shard named.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("run wgsl-variants")
}

fn ok(args: &[&str]) -> Output {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Starts the binary with stdout into `stdout` (a file).
fn spawn(args: &[String], stdout: &Path) -> Child {
    bin()
        .args(args)
        .stdout(std::fs::File::create(stdout).unwrap())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start wgsl-variants")
}

fn wait(child: Child, what: &str) {
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{what} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Every file under `dir`, by relative path, with its bytes.
fn tree(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut out = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.insert(
                    p.strip_prefix(dir).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    out
}

/// The variant and distinct-text counts of a `validate --json` report.
fn counts(report: &[u8]) -> (u64, u64) {
    let report: serde_json::Value = serde_json::from_slice(report).unwrap();
    let totals = &report["totals"];
    (
        totals["built"].as_u64().unwrap(),
        totals["distinct"].as_u64().unwrap(),
    )
}

fn cache_info(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&ok(&["cache", "--cache", s(dir), "info", "--json"]).stdout).unwrap()
}

/// The selection these tests shard (arguments after `--all`): a 3-wise covering set of every
/// pass of the bundled library, 547 variants on 2026-11-29. Sharding, merging and
/// sharing a cache do not depend on which variants they carry; a larger selection only made
/// this binary the slowest of the suite (each test runs it several times).
fn selection() -> Vec<String> {
    vec!["--cover".into(), "3".into()]
}

/// The bundled library (the tests' selection of it) as 4 shards in 4 processes at once,
/// sharing one cache folder: the merged `validate --json` report, emit folder and manifest are
/// byte for byte those of one process.
#[test]
fn four_shard_processes_merge_to_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let cache = t.join("cache");
    let targets = ["--target", "wgsl", "--target", "spirv"];

    let sel = selection();
    let sel: Vec<&str> = sel.iter().map(String::as_str).collect();
    let whole = ok(&[
        ["validate", "--all", "--json", "--no-cache"].as_slice(),
        &sel,
    ]
    .concat())
    .stdout;
    let (built, distinct) = counts(&whole);
    let whole_dir = t.join("whole");
    let mut emit: Vec<&str> = vec!["emit", "--all", "--out", s(&whole_dir)];
    emit.extend(targets);
    emit.extend(&sel);
    ok(&emit);

    let shard_args = |k: usize| -> (Vec<String>, Vec<String>) {
        let shard = format!("{k}/4");
        let validate = [
            "validate",
            "--all",
            "--json",
            "--shard",
            &shard,
            "--cache",
            s(&cache),
        ];
        let out = t.join(format!("emit-{k}"));
        let mut emit = vec!["emit", "--all", "--shard", &shard, "--out", s(&out)];
        emit.extend(targets);
        emit.extend(&sel);
        (
            validate.iter().chain(&sel).map(|a| a.to_string()).collect(),
            emit.iter().map(|a| a.to_string()).collect(),
        )
    };
    let children: Vec<(Child, Child)> = (1..=4)
        .map(|k| {
            let (validate, emit) = shard_args(k);
            (
                spawn(&validate, &t.join(format!("validate-{k}.json"))),
                spawn(&emit, &t.join(format!("emit-{k}.txt"))),
            )
        })
        .collect();
    for (k, (v, e)) in children.into_iter().enumerate() {
        wait(v, &format!("validate shard {}", k + 1));
        wait(e, &format!("emit shard {}", k + 1));
    }

    // Shards given in any order.
    let reports: Vec<String> = [3, 1, 4, 2]
        .iter()
        .map(|k| t.join(format!("validate-{k}.json")).display().to_string())
        .collect();
    let mut merge = vec!["merge"];
    merge.extend(reports.iter().map(String::as_str));
    let merged = ok(&merge).stdout;
    assert_eq!(
        String::from_utf8_lossy(&merged),
        String::from_utf8_lossy(&whole),
        "merged validate report"
    );

    let merged_dir = t.join("merged");
    let folders: Vec<String> = [2, 4, 1, 3]
        .iter()
        .map(|k| t.join(format!("emit-{k}")).display().to_string())
        .collect();
    let mut merge = vec!["merge", "--out", s(&merged_dir)];
    merge.extend(folders.iter().map(String::as_str));
    ok(&merge);
    let (a, b) = (tree(&t.join("whole")), tree(&merged_dir));
    assert_eq!(
        a.len(),
        2 * built as usize + 1,
        "wgsl and spirv for every variant, and the manifest"
    );
    assert_eq!(
        String::from_utf8_lossy(&a[Path::new("manifest.json")]),
        String::from_utf8_lossy(&b[Path::new("manifest.json")])
    );
    assert!(a == b, "the merged folder differs from the single run's");

    // The four processes filled one cache: every distinct text once, nothing corrupt; a run
    // from it prints the same report.
    let info = cache_info(&cache);
    assert_eq!(
        (info["entries"].as_u64(), info["corrupt"].as_u64()),
        (Some(distinct), Some(0))
    );
    let cached = ok(&[
        ["validate", "--all", "--json", "--cache", s(&cache)].as_slice(),
        &sel,
    ]
    .concat())
    .stdout;
    assert_eq!(cached, whole);
}

/// Two processes validating different halves into one cache folder at the same moment: every
/// entry of both is there afterwards, none corrupt, and export/import carries them all.
#[test]
fn two_processes_writing_one_cache_lose_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    let sel = selection();
    let sel: Vec<&str> = sel.iter().map(String::as_str).collect();
    let (_, distinct) = counts(
        &ok(&[
            ["validate", "--all", "--json", "--no-cache"].as_slice(),
            &sel,
        ]
        .concat())
        .stdout,
    );
    for round in 0..3 {
        let children: Vec<Child> = (1..=2)
            .map(|k| {
                let args: Vec<String> = [
                    "validate",
                    "--all",
                    "--json",
                    "--shard",
                    &format!("{k}/2"),
                    "--cache",
                    s(&cache),
                ]
                .iter()
                .chain(&sel)
                .map(|a| a.to_string())
                .collect();
                spawn(&args, &tmp.path().join(format!("out-{round}-{k}.json")))
            })
            .collect();
        for c in children {
            wait(c, "validate");
        }
        let info = cache_info(&cache);
        assert_eq!(info["entries"], distinct, "round {round}: {info}");
        assert_eq!(info["corrupt"], 0, "round {round}: {info}");
    }
    let file = tmp.path().join("cache.bin");
    ok(&["cache", "--cache", s(&cache), "export", s(&file)]);
    let fresh = tmp.path().join("fresh");
    ok(&["cache", "--cache", s(&fresh), "import", s(&file)]);
    assert_eq!(cache_info(&fresh)["entries"], distinct);
    // A damaged byte in the file: that entry is left out and reported, never trusted.
    let mut bytes = std::fs::read(&file).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 0xff;
    std::fs::write(&file, &bytes).unwrap();
    let other = tmp.path().join("other");
    let out = ok(&["cache", "--cache", s(&other), "import", s(&file)]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("1 corrupt record(s)"));
    assert_eq!(cache_info(&other)["entries"], distinct - 1);
}

/// Copies the bundled library to `dir` with one comment added: another library version.
fn changed_library(dir: &Path) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../wgsl-variants-shaders/wgsl");
    for (rel, bytes) in tree(&src) {
        let path = dir.join(&rel);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, bytes).unwrap();
    }
    let standard = dir.join("standard.wgsl");
    let mut text = std::fs::read_to_string(&standard).unwrap();
    text.push_str("\n// a later edit\n");
    std::fs::write(&standard, text).unwrap();
}

fn refused(args: &[&str]) -> String {
    let out = run(args);
    assert_eq!(out.status.code(), Some(1), "{args:?} should fail");
    assert!(out.stdout.is_empty(), "nothing merged is printed");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A missing shard, a repeated shard and a shard of another library version: each refused
/// with a clear error naming the shard. The reports shard `deferred_shading/Lighting` (384
/// variants, every one validated by each report): refusing does not depend on the size.
#[test]
fn merge_refuses_missing_repeated_and_foreign_shards() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let lib = t.join("lib");
    changed_library(&lib);
    let report = |k: usize, root: Option<&Path>| -> String {
        let path = t.join(format!(
            "{}-{k}.json",
            if root.is_some() { "other" } else { "s" }
        ));
        let mut args = vec![
            "validate",
            "--all",
            "--json",
            "--no-cache",
            "--pass",
            "Lighting",
        ];
        let shard = format!("{k}/3");
        args.extend(["--shard", &shard]);
        if let Some(root) = root {
            args.extend(["--root", s(root)]);
        }
        std::fs::write(&path, ok(&args).stdout).unwrap();
        path.display().to_string()
    };
    let [s1, s2, s3] = [1, 2, 3].map(|k| report(k, None));
    let other2 = report(2, Some(&lib));
    ok(&["merge", &s1, &s2, &s3]);

    let missing = refused(&["merge", &s1, &s3]);
    assert!(missing.contains("missing shard(s) 2 of 3"), "{missing}");
    let repeated = refused(&["merge", &s1, &s2, &s2, &s3]);
    assert!(
        repeated.contains(&format!("`{s2}` repeats shard 2/3")),
        "{repeated}"
    );
    let foreign = refused(&["merge", &s1, &other2, &s3]);
    assert!(
        foreign.contains(&format!("`{other2}` has fingerprint"))
            && foreign.contains("another library"),
        "{foreign}"
    );
    let whole = t.join("whole.json");
    std::fs::write(
        &whole,
        ok(&["validate", "--all", "--json", "--pass", "Lighting"]).stdout,
    )
    .unwrap();
    let unsharded = refused(&["merge", s(&whole), &s2]);
    assert!(unsharded.contains("is not a shard"), "{unsharded}");

    // Emit folders: a missing shard, a foreign shard and a file changed after writing.
    let folder = |k: usize, root: Option<&Path>| -> String {
        let out = t.join(format!(
            "{}-emit-{k}",
            if root.is_some() { "other" } else { "s" }
        ));
        let shard = format!("{k}/2");
        let mut args = vec![
            "emit",
            "--out",
            s(&out),
            "--shard",
            &shard,
            "--shader",
            "deferred_reflections",
        ];
        if let Some(root) = root {
            args.extend(["--root", s(root)]);
        }
        ok(&args);
        out.display().to_string()
    };
    let [e1, e2] = [1, 2].map(|k| folder(k, None));
    let other = folder(2, Some(&lib));
    let merged = t.join("merged");
    let missing = refused(&["merge", "--out", s(&merged), &e1]);
    assert!(missing.contains("missing shard(s) 2 of 2"), "{missing}");
    let foreign = refused(&["merge", "--out", s(&merged), &e1, &other]);
    assert!(
        foreign.contains(&format!("`{other}` has fingerprint")),
        "{foreign}"
    );
    let file = tree(Path::new(&e2))
        .into_keys()
        .find(|p| p.extension().is_some_and(|e| e == "wgsl"))
        .unwrap();
    std::fs::write(Path::new(&e2).join(&file), "// changed\n").unwrap();
    let changed = refused(&["merge", "--out", s(&merged), &e1, &e2]);
    assert!(
        changed.contains(&format!("`{e2}` does not fit")) && changed.contains("BLAKE3"),
        "{changed}"
    );
    assert!(
        !merged.exists(),
        "nothing is written when a shard is refused"
    );
}
