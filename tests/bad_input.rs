//! The bad-input corpus: every folder under `tests/bad/` is a library (`lib/`) and the
//! diagnostic it must produce (`expect.toml`: stage, `file:line:col`, message). Each case is
//! checked through the API here, and through the command line in the CLI crate's tests.

use std::path::Path;

use test_support::bad::Expect;

use wgsl_variants::keywords::KeywordError;
use wgsl_variants::library::{LinkError, LoadProblem};
use wgsl_variants::lookup::lookup_strict;
use wgsl_variants::plan::{PlanError, PlanOptions, select_passes, variants_to_build};
use wgsl_variants::preprocess::ParseError;
use wgsl_variants::source::{DirError, SourceError};
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Library, Space};

/// The kind of a load problem, as `expect.toml` names it: the error enums matched exhaustively,
/// so a new variant must be named here.
fn kind(problem: &LoadProblem) -> &'static str {
    match problem {
        LoadProblem::Dir(DirError::Io { .. }) => "dir::io",
        LoadProblem::Dir(DirError::TooManyFiles { .. }) => "dir::too_many_files",
        LoadProblem::Dir(DirError::TooLarge { .. }) => "dir::too_large",
        LoadProblem::Source(SourceError::NotUtf8 { .. }) => "source::not_utf8",
        LoadProblem::Parse(e) => match e {
            ParseError::UnknownDirective { .. } => "parse::unknown_directive",
            ParseError::Malformed { .. } => "parse::malformed",
            ParseError::Expression { .. } => "parse::expression",
            ParseError::Unmatched { .. } => "parse::unmatched",
            ParseError::AfterElse { .. } => "parse::after_else",
            ParseError::Unterminated { .. } => "parse::unterminated",
            ParseError::Misplaced { .. } => "parse::misplaced",
            ParseError::TooDeep { .. } => "parse::too_deep",
            ParseError::Syntax { .. } => "parse::syntax",
            ParseError::Attribute { .. } => "parse::attribute",
        },
        LoadProblem::Link(e) => match e {
            LinkError::MissingImport { .. } => "link::missing_import",
            LinkError::LeavesRoot { .. } => "link::leaves_root",
            LinkError::Cycle { .. } => "link::cycle",
            LinkError::TooDeep { .. } => "link::too_deep",
            LinkError::DuplicateShader { .. } => "link::duplicate_shader",
            LinkError::DuplicatePass { .. } => "link::duplicate_pass",
            LinkError::TooLarge { .. } => "link::too_large",
            LinkError::DuplicateImportPath { .. } => "link::duplicate_import_path",
            LinkError::UnknownEntry { .. } => "link::unknown_entry",
        },
        LoadProblem::Keyword(e) => match e {
            KeywordError::DuplicateInSet { .. } => "keyword::duplicate_in_set",
            KeywordError::TooManyOptions { .. } => "keyword::too_many_options",
            KeywordError::TwoPlaceholders { .. } => "keyword::two_placeholders",
            KeywordError::InTwoSets { .. } => "keyword::in_two_sets",
            KeywordError::UnknownSkip { .. } => "keyword::unknown_skip",
            KeywordError::UnknownConstraintKeyword { .. } => "keyword::unknown_constraint_keyword",
            KeywordError::Contradictory { .. } => "keyword::contradictory",
            KeywordError::TooCoupled { .. } => "keyword::too_coupled",
        },
        LoadProblem::Declaration(_) => "declaration",
        _ => "other",
    }
}

/// Checks one case through the API; returns a description of what went wrong, if anything.
fn check_api(dir: &Path, e: &Expect) -> Result<(), String> {
    let loaded = Library::from_dir(dir.join("lib"));
    if e.stage == "load" {
        let err = match loaded {
            Ok(_) => return Err("library loaded, expected a load error".into()),
            Err(err) => err,
        };
        // The first problem, matched on its type; its location and message from its report.
        let first = err.problems.first().ok_or("no problem reported")?;
        let got_kind = kind(first);
        let report = first.diagnostic();
        let location = report
            .location(&err.files)
            .map(|l| l.to_string())
            .unwrap_or_default();
        if e.kind.as_deref() != Some(got_kind)
            || location != e.location
            || !report.message.contains(&e.message)
        {
            return Err(format!("got {got_kind} at {location}: {}", report.message));
        }
        return Ok(());
    }
    let lib = loaded.map_err(|err| format!("unexpected load error:\n{err}"))?;
    match e.stage.as_str() {
        "warning" => {
            let found = lib.warnings().iter().any(|w| {
                w.severity == wgsl_variants::Severity::Warning
                    && w.message.contains(&e.message)
                    && w.location(lib.files()).map(|l| l.to_string()) == Some(e.location.clone())
            });
            if found {
                Ok(())
            } else {
                Err(format!("warnings: {:?}", lib.warnings()))
            }
        }
        "validate" => {
            let mut options = PlanOptions::default();
            options.all = true;
            for pass in select_passes(&lib, None, None).map_err(|x| x.to_string())? {
                let choices = variants_to_build(&lib, pass, &options).map_err(|x| x.to_string())?;
                let report = validate_pass(&lib, pass, &choices, &|_| {});
                for f in &report.failures {
                    if f.keyword_sets.contains(&e.keywords) {
                        let location = f
                            .error
                            .location(lib.files())
                            .map(|l| l.to_string())
                            .unwrap_or_default();
                        if location != e.location || !f.error.message.contains(&e.message) {
                            return Err(format!("got {location}: {}", f.error.message));
                        }
                        if !f
                            .error
                            .diagnostic()
                            .notes
                            .iter()
                            .any(|n| n.contains(&format!("{{{}}}", e.keywords.join(", "))))
                        {
                            return Err("the diagnostic does not name the keyword set".into());
                        }
                        return Ok(());
                    }
                }
            }
            Err("no failure for the expected keyword set".into())
        }
        "lookup" => {
            let pass = lib
                .pass(
                    e.shader.as_deref().unwrap_or(""),
                    e.pass.as_deref().unwrap_or(""),
                )
                .map_err(|x| x.to_string())?;
            match lookup_strict(&Space::build_set(pass, None), &e.keywords, 1_000_000) {
                Ok(_) => Err("lookup succeeded".into()),
                Err(err) if err.to_string().contains(&e.message) => {
                    let location = lib.files().location(pass.span).to_string();
                    if location == e.location {
                        Ok(())
                    } else {
                        Err(format!("pass located at {location}"))
                    }
                }
                Err(err) => Err(format!("got {err}")),
            }
        }
        "budget" => {
            let pass = lib.passes().next().ok_or("no pass")?;
            match variants_to_build(&lib, pass, &PlanOptions::default()) {
                Err(PlanError::Budget { error, .. }) if error.to_string().contains(&e.message) => {
                    Ok(())
                }
                Err(other) => Err(format!("got {other}")),
                Ok(v) => Err(format!("built {} variants", v.len())),
            }
        }
        "cover" => {
            let pass = lib.passes().next().ok_or("no pass")?;
            let mut options = PlanOptions::default();
            options.cover = e.cover;
            match variants_to_build(&lib, pass, &options) {
                Err(PlanError::Cover(error)) if error.to_string().contains(&e.message) => {
                    let location = lib.files().location(pass.span).to_string();
                    if location == e.location {
                        Ok(())
                    } else {
                        Err(format!("pass located at {location}"))
                    }
                }
                Err(other) => Err(format!("got {other}")),
                Ok(v) => Err(format!("built {} variants", v.len())),
            }
        }
        other => Err(format!("unknown stage {other}")),
    }
}

#[test]
fn every_bad_input_is_diagnosed_at_its_location() {
    test_support::bad::check_all("the API", check_api);
}
