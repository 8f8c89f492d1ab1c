#!/usr/bin/env bash
# Fuzz every target for a fixed budget: `bash scripts/fuzz.sh [SECONDS_PER_TARGET]` (default 60).
#
# Targets (fuzz/fuzz_targets/, properties in crates/fuzz-checks): preprocess (directives of any
# module text), expr (#if expressions), pragmas (pass bodies), loader (several modules with
# imports), lean (naga gives the lean and the emitted text of every variant the same outcome),
# naga_oil (naga_oil-dialect trees, loaded and composed through naga_oil), wesl (WESL trees,
# their `@if` tree read and every variant composed through the wesl crate; rustc >= 1.97.1), declaration (any
# wgsl-variants.toml over a fixed tree), merge (shard reports, edited or not: merged totals
# always add up) and cache (segment bytes: nothing untrusted is ever trusted).
# Each input is bounded in time (-timeout) and memory (-rss_limit_mb). A crash is
# saved under fuzz/artifacts/<target>/; copy it to fuzz/regressions/<target>/ and fix the bug:
# `cargo test --test fuzz_regressions` replays every saved input.
#
# cargo-fuzz needs nightly compiler flags; RUSTC_BOOTSTRAP=1 lets the stable toolchain take them.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
export RUSTC_BOOTSTRAP=1
summary=""
# The `wesl` target needs the fuzz crate's `wesl` feature (the `wesl` crate 0.6, which declares
# Rust 1.97.1); cargo-fuzz cannot pass `--ignore-rust-version`, so on older rustc the target is
# skipped, loudly (the saved inputs still run through `cargo test --test fuzz_regressions`).
features=()
targets=(preprocess expr pragmas loader lean naga_oil declaration merge cache)
rustc_version=$(rustc --version | grep -Eo '[0-9]+\.[0-9]+\.[0-9]+' | head -1)
if [ "$(printf '%s\n1.97.1\n' "$rustc_version" | sort -V | head -1)" = 1.97.1 ]; then
    features=(--features wesl)
    targets+=(wesl)
else
    echo "== fuzz target wesl SKIPPED: rustc $rustc_version is older than 1.97.1, which wesl 0.6 declares (cargo-fuzz cannot pass --ignore-rust-version)"
    summary+="fuzz wesl: SKIPPED (rustc $rustc_version < 1.97.1)"$'\n'
fi
for target in "${targets[@]}"; do
    corpus="fuzz/corpus/$target"
    mkdir -p "$corpus"
    cp -n fuzz/initial/"$target"/* "$corpus"/ 2>/dev/null || true
    if [ "$target" = preprocess ] || [ "$target" = lean ]; then
        # The bundled modules are initial inputs too (shader files are pass bodies, not modules).
        for m in $(grep -rL '^#shader' crates/wgsl-variants-shaders/wgsl --include='*.wgsl'); do cp -n "$m" "$corpus/$(echo "$m" | tr / _)"; done
    fi
    log="$(mktemp)"
    cargo fuzz run --release --sanitizer address "${features[@]}" "$target" "$corpus" -- \
        -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 2>&1 | tee "$log" | grep -E "^(Done|==|SUMMARY|#[0-9]+ +(INITED|DONE))" || true
    status=${PIPESTATUS[0]}
    runs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || echo 0)
    summary+="fuzz $target: $runs executions in ${seconds}s, exit $status"$'\n'
    rm -f "$log"
    if [ "$status" != 0 ]; then
        printf '%s' "$summary"
        echo "fuzz target $target failed: see fuzz/artifacts/$target/" >&2
        exit 1
    fi
done
printf '%s' "$summary"
