#![allow(dead_code)] // each fuzz binary uses one of these
//! The properties each fuzz target checks, shared with `tests/fuzz_regressions.rs` so every
//! saved input is replayed through exactly the same code.

use wgsl_variants::preprocess::expr::parse;
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
    if let Ok(e) = parse(text, 0, 0, 256) {
        let _ = e.eval(&|n: &str| match n.len() % 3 {
            0 => None,
            1 => Some(i64::MIN),
            _ => Some(n.len() as i64),
        });
    }
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

/// Several modules with imports between them (cycles, diamonds, missing and escaping paths):
/// the input is split into files at `\0`, named m0..mN. Loading never panics or hangs.
pub fn loader(data: &[u8]) {
    let files: Vec<(String, String)> = data
        .split(|&b| b == 0)
        .take(64)
        .enumerate()
        .map(|(i, bytes)| {
            (
                format!("m{i}.wgsl"),
                String::from_utf8_lossy(bytes).into_owned(),
            )
        })
        .collect();
    if let Ok(lib) = Library::from_sources(files) {
        for pass in lib.passes() {
            if let Ok(v) = lib.variant(&pass.shader, &pass.name, &[] as &[&str]) {
                let _ = lib.wgsl(&v);
            }
        }
    }
}
