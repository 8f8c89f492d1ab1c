//! `watch::Session`: a tree validated again as it changes. Its verdict is the report
//! `validate_plan` makes of the same tree; passes whose files did not change keep their report;
//! the error of an edit streams with its place and keyword set; recently failing variants come
//! first; a tree that does not load, or a cancelled run, leaves the session usable.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

use wgsl_variants::plan::{PlanOptions, plan};
use wgsl_variants::validate::validate_plan;
use wgsl_variants::watch::{Event, Outcome, Session, Verdict, WatchError};
use wgsl_variants::{Library, LoadOptions};

/// `a/P` imports `lib/color` (whose `RED` branch line 3 is what the tests break); `b/Q` reads
/// nothing but its own file.
fn tree() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("lib")).unwrap();
    write(dir.path(), "lib/color.wgsl", COLOR);
    write(
        dir.path(),
        "a.wgsl",
        "#shader a\n#pass P\n#pragma multi_compile _ RED\n#pragma multi_compile _ X Y\n#import lib/color\n\
         @fragment fn fs() -> @location(0) vec4f { return tint(); }\n#endpass\n",
    );
    write(
        dir.path(),
        "b.wgsl",
        "#shader b\n#pass Q\n#pragma multi_compile _ Z\n\
         @fragment fn fs() -> @location(0) vec4f { return vec4f(0.0); }\n#endpass\n",
    );
    dir
}

const COLOR: &str = "fn tint() -> vec4f {\n#if defined(RED)\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n#else\n    return vec4f(0.5);\n#endif\n}\n";

fn write(root: &Path, path: &str, text: &str) {
    std::fs::write(root.join(path), text).unwrap();
}

/// A session over `root` with the default options and no cache folder.
fn new_session(root: &Path) -> Session {
    Session::new(root, LoadOptions::default(), PlanOptions::default(), None)
}

/// One run that is not cancelled: its verdict (or load/plan error) and the errors it
/// streamed, as `message @ location in variant`.
fn run(session: &mut Session) -> (Result<Verdict, WatchError>, Vec<String>) {
    let events = Mutex::new(Vec::new());
    let outcome = session.run(&AtomicBool::new(false), &|e| {
        if let Event::Failure { library, error } = e {
            let at = error
                .location(library.files())
                .map(|l| l.to_string())
                .unwrap_or_default();
            events
                .lock()
                .unwrap()
                .push(format!("{} @ {at} in {}", error.message, error.variant));
        }
    });
    let verdict = outcome.map(|o| match o {
        Outcome::Verdict(v) => v,
        other => panic!("not cancelled, yet {other:?}"),
    });
    (verdict, events.into_inner().unwrap())
}

/// The JSON of what `validate` reports for the tree as it is now.
fn validate_json(root: &Path) -> serde_json::Value {
    let lib = Library::from_dir(root).unwrap();
    let options = PlanOptions::default();
    let planned = plan(&lib, &options).unwrap();
    serde_json::to_value(validate_plan(&lib, &planned, &options, None, &|_| {})).unwrap()
}

#[test]
fn an_edit_streams_its_error_and_the_verdict_is_what_validate_reports() {
    let dir = tree();
    let mut session = new_session(dir.path());
    let (verdict, errors) = run(&mut session);
    let verdict = verdict.unwrap();
    assert!(verdict.report.ok && errors.is_empty());
    assert_eq!(verdict.validated, ["a/P", "b/Q"]);
    assert_eq!(verdict.kept, 0);
    assert_eq!(
        serde_json::to_value(&verdict.report).unwrap(),
        validate_json(dir.path())
    );

    // Break the RED branch: the error streams once, at its line, naming a variant with RED;
    // only a/P (which imports the file) is validated again.
    write(
        dir.path(),
        "lib/color.wgsl",
        &COLOR.replace("1.0, 0.0", "1.0, ,"),
    );
    let (verdict, errors) = run(&mut session);
    let verdict = verdict.unwrap();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(
        errors[0].contains("@ lib/color.wgsl:3:") && errors[0].contains("in a/P {RED"),
        "{errors:?}"
    );
    assert_eq!(verdict.validated, ["a/P"]);
    assert_eq!(verdict.kept, 1);
    assert!(!verdict.report.ok);
    assert_eq!(verdict.report.totals.invalid, 3);
    assert_eq!(
        serde_json::to_value(&verdict.report).unwrap(),
        validate_json(dir.path())
    );
    // The session's library is the tree as loaded for this verdict.
    let lib = session.library().unwrap();
    let color = (0..lib.files().len())
        .find(|&f| lib.files().path(f) == "lib/color.wgsl")
        .unwrap();
    assert!(lib.files().text(color).contains("1.0, ,"));

    // The fix: the diagnostic is gone.
    write(dir.path(), "lib/color.wgsl", COLOR);
    let (verdict, errors) = run(&mut session);
    let verdict = verdict.unwrap();
    assert!(verdict.report.ok && errors.is_empty(), "{errors:?}");
    assert_eq!(verdict.validated, ["a/P"]);
    assert_eq!(
        serde_json::to_value(&verdict.report).unwrap(),
        validate_json(dir.path())
    );

    // Nothing changed: nothing is validated, the report stands.
    let (verdict, _) = run(&mut session);
    let verdict = verdict.unwrap();
    assert!(verdict.validated.is_empty() && verdict.kept == 2);
    assert_eq!(
        serde_json::to_value(&verdict.report).unwrap(),
        validate_json(dir.path())
    );
}

#[test]
fn a_tree_that_does_not_load_is_an_error_and_the_session_goes_on() {
    let dir = tree();
    let mut session = new_session(dir.path());
    write(
        dir.path(),
        "b.wgsl",
        "#shader b\n#pass Q\n#import lib/missing\n#endpass\n",
    );
    let (verdict, _) = run(&mut session);
    match verdict {
        Err(WatchError::Load(e)) => assert_eq!(e.locations(), ["b.wgsl:3:9"]),
        other => panic!("expected a load error, got {other:?}"),
    }
    assert!(session.library().is_none());
    write(
        dir.path(),
        "b.wgsl",
        "#shader b\n#pass Q\n@fragment fn fs() -> @location(0) vec4f { return vec4f(0.0); }\n#endpass\n",
    );
    let (verdict, _) = run(&mut session);
    assert!(verdict.unwrap().report.ok);
}

#[test]
fn a_cancelled_run_gives_no_verdict_and_the_next_run_does() {
    let dir = tree();
    let mut session = new_session(dir.path());
    let outcome = session.run(&AtomicBool::new(true), &|_| {}).unwrap();
    assert!(matches!(outcome, Outcome::Cancelled), "{outcome:?}");
    let (verdict, _) = run(&mut session);
    let verdict = verdict.unwrap();
    assert!(verdict.report.ok && verdict.report.totals.built == 8);
}

/// A pass of 81 variants (past what is validated whole before the sweep) where the 4-way
/// combination A2 B2 C2 D2 breaks line 9 and, with `more`, every variant breaks line 11.
fn combinations(more: bool) -> String {
    format!(
        "#shader s\n#pass P\n#pragma multi_compile _ A1 A2\n#pragma multi_compile _ B1 B2\n\
         #pragma multi_compile _ C1 C2\n#pragma multi_compile _ D1 D2\n\
         @fragment fn fs() -> @location(0) vec4f {{\n\
         #if defined(A2) && defined(B2) && defined(C2) && defined(D2)\n    let e2 = ;\n#endif\n\
         {}    return vec4f(1.0);\n}}\n#endpass\n",
        if more { "    let e1 = ;\n" } else { "" }
    )
}

#[test]
fn the_variant_that_failed_last_is_validated_first() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "s.wgsl", &combinations(false));
    let mut session = new_session(dir.path());
    let (verdict, errors) = run(&mut session);
    assert_eq!(verdict.unwrap().report.totals.invalid, 1);
    assert_eq!(errors.len(), 1);
    assert!(errors[0].contains("s.wgsl:9:") && errors[0].contains("{A2, B2, C2, D2}"));

    // Now every variant fails, the first ones in enumeration order with the new error (line
    // 11); the variant that failed last run comes first all the same.
    write(dir.path(), "s.wgsl", &combinations(true));
    let (verdict, errors) = run(&mut session);
    assert_eq!(verdict.unwrap().report.totals.invalid, 81);
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(errors[0].contains("s.wgsl:9:"), "{errors:?}");
    assert!(errors[1].contains("s.wgsl:11:"), "{errors:?}");

    // A fresh session has no history: the error of the first variants comes first.
    let mut fresh = new_session(dir.path());
    let (_, errors) = run(&mut fresh);
    assert!(errors[0].contains("s.wgsl:11:"), "{errors:?}");
}

#[test]
fn a_cache_folder_carries_valid_texts_to_the_next_session() {
    let (dir, cache) = (tree(), tempfile::tempdir().unwrap());
    let new = || {
        Session::new(
            dir.path(),
            LoadOptions::default(),
            PlanOptions::default(),
            Some(cache.path()),
        )
    };
    let (verdict, _) = run(&mut new());
    assert!(verdict.unwrap().report.ok);
    let saved = wgsl_variants::cache::ValidCache::open(cache.path());
    assert_eq!(
        Some(saved.len() as u64),
        validate_json(dir.path())["totals"]["distinct"].as_u64()
    );
    let (verdict, _) = run(&mut new());
    assert!(verdict.unwrap().report.ok);
}

/// Copies a fixture tree (files and one level of folders) into a temporary folder.
fn copy_fixture(name: &str) -> tempfile::TempDir {
    let from = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    let dir = tempfile::tempdir().unwrap();
    let copy = |from: &Path, to: &Path| {
        for entry in std::fs::read_dir(from).unwrap() {
            let entry = entry.unwrap().path();
            if entry.is_file() {
                std::fs::copy(&entry, to.join(entry.file_name().unwrap())).unwrap();
            }
        }
    };
    copy(&from, dir.path());
    for entry in std::fs::read_dir(&from).unwrap() {
        let folder = entry.unwrap().path();
        if folder.is_dir() {
            let to = dir.path().join(folder.file_name().unwrap());
            std::fs::create_dir(&to).unwrap();
            copy(&folder, &to);
        }
    }
    dir
}

/// naga_oil and WESL trees (composed by their own engines) are watched the same way: an edit
/// of an imported module changes the verdict, which stays what `validate` reports.
#[test]
fn naga_oil_and_wesl_trees_are_watched_too() {
    for (fixture, module) in [
        ("naga_oil", "common/lighting.wgsl"),
        ("wesl", "common/lighting.wesl"),
    ] {
        let dir = copy_fixture(fixture);
        let mut session = new_session(dir.path());
        let (verdict, _) = run(&mut session);
        let verdict = verdict.unwrap();
        // The fixtures carry a bug in 4 of their 12 variants.
        assert_eq!(verdict.report.totals.invalid, 4, "{fixture}");
        assert_eq!(
            serde_json::to_value(&verdict.report).unwrap(),
            validate_json(dir.path()),
            "{fixture}"
        );
        let original = std::fs::read_to_string(dir.path().join(module)).unwrap();
        write(
            dir.path(),
            module,
            &original.replacen("(0.0, 0.0, 1.0)", "(0.0, 0.0, 1.0, 2.0)", 1),
        );
        let (verdict, errors) = run(&mut session);
        let verdict = verdict.unwrap();
        assert!(verdict.report.totals.invalid > 4, "{fixture}: {errors:?}");
        assert!(!errors.is_empty());
        assert_eq!(
            serde_json::to_value(&verdict.report).unwrap(),
            validate_json(dir.path()),
            "{fixture}"
        );
        write(dir.path(), module, &original);
        let (verdict, _) = run(&mut session);
        assert_eq!(verdict.unwrap().report.totals.invalid, 4, "{fixture}");
    }
}
