//! Case 9: work that grows with the input grows linearly, and work that cannot finish soon is
//! refused up front with its size, not started.

use std::time::{Duration, Instant};

use super::{assert_clean_exit, run_on_within};

fn tree(sets: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("s.wgsl"),
        format!(
            "#shader s\n#pass P\n{sets}@fragment fn fs() -> @location(0) vec4f {{ return vec4f(1.0); }}\n#endpass\n"
        ),
    )
    .unwrap();
    dir
}

/// One set of 60,000 options: about 10 s before (a quadratic duplicate check; 100,000 took
/// 28 s), well under a second now. The limit leaves room for a loaded machine; quadratic
/// would not fit it.
#[test]
fn a_set_of_sixty_thousand_options_lists_at_once() {
    let names: Vec<String> = (0..60_000).map(|i| format!("K{i}")).collect();
    let dir = tree(&format!("#pragma multi_compile _ {}\n", names.join(" ")));
    let start = Instant::now();
    let out = run_on_within(dir.path(), &["list"], Duration::from_secs(20));
    assert_clean_exit(&out, 0);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("60001 full space"),
        "{}",
        &stdout[..stdout.len().min(300)]
    );
    eprintln!("list of 60,000 options: {:?}", start.elapsed());
}

/// 100,000 options do not fit a variant's 16-bit option index: before, the count wrapped
/// (34465 variants, silently); now the set is refused with its size.
#[test]
fn a_set_past_sixty_five_thousand_options_is_refused_not_wrapped() {
    let names: Vec<String> = (0..100_000).map(|i| format!("K{i}")).collect();
    let dir = tree(&format!("#pragma multi_compile _ {}\n", names.join(" ")));
    let out = run_on_within(dir.path(), &["list"], Duration::from_secs(20));
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("a keyword set has 100001 options, past the limit of 65535"),
        "{}",
        &stderr[..stderr.len().min(300)]
    );
}

/// 202 two-option sets at t = 4: over a billion combinations to cover. Refused at once with
/// the count, the limit and what t = 3 would cover, instead of running for many minutes.
#[test]
fn a_covering_set_too_costly_to_generate_is_refused_with_its_size() {
    let sets: String = (0..202)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let dir = tree(&sets);
    let out = run_on_within(
        dir.path(),
        &["validate", "--cover", "4", "--no-cache"],
        Duration::from_secs(20),
    );
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .contains("must cover 1077306400 combinations of options, past the limit of 200000000")
            && stderr.contains("t = 3 covers 10827200"),
        "{stderr}"
    );
}

/// A covering set that takes seconds to generate is announced before it starts, with the
/// number of combinations and the time it will take.
#[test]
fn a_long_covering_generation_is_announced_with_its_size() {
    let sets: String = (0..200)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let dir = tree(&sets);
    let out = run_on_within(
        dir.path(),
        &["validate", "--cover", "3", "--no-cache"],
        Duration::from_secs(120),
    );
    assert_clean_exit(&out, 0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("note: s/P: a t = 3 covering set must cover 10507200 combinations of options; generating it takes about 4 s on 2 cores"),
        "{stderr}"
    );
}
