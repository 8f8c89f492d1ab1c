#!/usr/bin/env bash
# Validates Bevy's PBR shaders (trees no one here wrote) with our declaration files:
#   bash scripts/bevy.sh [--bevy 0.19.1|0.20.1] [--check] [validate options]   (default `--cover 2`)
# - 0.19.1 (default): naga_oil's dialect, examples/bevy_pbr/wgsl-variants.toml.
# - 0.20.1: WESL 0.6 across three packages (bevy_pbr, bevy_render, bevy_core_pipeline),
#   examples/bevy-0.20/wgsl-variants.toml.
# The default validation: `--cover 2` for 0.19.1; for 0.20.1 `--cover 2 --cover-above 1000
# --profile desktop --profile webgpu` (passes of at most 1,000 variants are built whole, the others
# as 2-wise covering sets; one verdict per device profile in one run).
# `--check` (CI) runs the default and compares its summary lines (per pass and in total, and per
# profile when there are several) with the example's expected.txt; where README.md or
# docs/guide/wesl-trees.md has a `<!-- figures: bevy VERSION … -->` line, the table after it
# must be the one these figures give (scripts/bevy-figures.py; `--update` rewrites expected.txt
# and those tables instead of comparing). The audit's findings of defs pushed to another stage
# only are part of the figures.
#
# The shaders are fetched at run time by cargo itself (a throwaway manifest that depends on the
# published crates bevy_pbr, bevy_render, bevy_core_pipeline and bevy_gizmos_render, then `cargo fetch`: checksums
# and mirrors come from cargo), never committed: only the declaration files are ours. The tree
# is assembled under target/bevy-<version>/<crate>/src/…, so diagnostics name Bevy's own paths.
set -euo pipefail
cd "$(dirname "$0")/.."
version=0.19.1
if [ "${1:-}" = --bevy ]; then version="$2"; shift 2; fi
case "$version" in
    0.19.1) example=examples/bevy_pbr; ext=wgsl; default_args=(--cover 2) ;;
    0.20.1) example=examples/bevy-0.20; ext=wesl
        default_args=(--cover 2 --cover-above 1000 --profile desktop --profile webgpu) ;;
    *) echo "scripts/bevy.sh: no declaration for Bevy $version (0.19.1 or 0.20.1)" >&2; exit 2 ;;
esac
tree="target/bevy-$version"
fetch="target/bevy-fetch-$version"
mkdir -p "$fetch"
rm -rf "$tree"
mkdir -p "$tree"
cat > "$fetch/Cargo.toml" <<MANIFEST
[package]
name = "bevy-shaders-fetch"
version = "0.0.0"
edition = "2021"
publish = false

[lib]
path = "lib.rs"

[dependencies]
bevy_pbr = { version = "=$version", default-features = false }
bevy_render = { version = "=$version", default-features = false }
bevy_core_pipeline = { version = "=$version", default-features = false }
bevy_gizmos_render = { version = "=$version", default-features = false }

[workspace]
MANIFEST
touch "$fetch/lib.rs"
echo "== cargo fetch: bevy_pbr, bevy_render, bevy_core_pipeline, bevy_gizmos_render $version"
cargo fetch -q --manifest-path "$fetch/Cargo.toml"
# Where cargo unpacked each crate: its manifest's folder, from `cargo metadata`.
cargo metadata -q --format-version 1 --manifest-path "$fetch/Cargo.toml" |
    python3 -c '
import json, sys
for p in json.load(sys.stdin)["packages"]:
    if p["name"] in ("bevy_pbr", "bevy_render", "bevy_core_pipeline", "bevy_gizmos_render") and p["version"] == sys.argv[1]:
        print(p["name"], p["manifest_path"].rsplit("/", 1)[0])
' "$version" |
    while read -r crate unpacked; do
        (cd "$unpacked" && find src -name "*.$ext" -print0) |
            while IFS= read -r -d '' f; do
                mkdir -p "$tree/$crate/$(dirname "$f")"
                cp "$unpacked/$f" "$tree/$crate/$f"
            done
    done
cp "$example/wgsl-variants.toml" "$tree/"
echo "== $(find "$tree" -name "*.$ext" | wc -l) .$ext files in $tree"
# WGSL_VARIANTS_BIN: a binary already built (CI passes the test build's, see .ci/run).
bin="${WGSL_VARIANTS_BIN:-}"
if [ -z "$bin" ]; then
    cargo build --release --ignore-rust-version -q -p wgsl-variants-cli
    bin=target/release/wgsl-variants
fi
"$bin" --root "$tree" list
check=false
update=false
if [ "${1:-}" = --check ]; then check=true; shift; fi
if [ "${1:-}" = --update ]; then check=true; update=true; shift; fi
args=("$@")
if [ ${#args[@]} -eq 0 ]; then args=("${default_args[@]}"); fi
start=$(date +%s%N)
status=0
"$bin" --root "$tree" --color never validate "${args[@]}" --no-cache > "target/bevy-validate-$version.txt" || status=$?
end=$(date +%s%N)
cat "target/bevy-validate-$version.txt"
echo "== validate ${args[*]}: $(( (end - start) / 1000000 )) ms (exit $status: 1 means some variants failed)"
if $check; then
    # The summary lines (built, distinct, valid, invalid per pass and in total; with several
    # profiles also each profile's valid and invalid) are deterministic: any change is a change
    # in this tool or in the declaration.
    grep -E '^([a-z0-9_]+/[A-Za-z/]+: [0-9]+ built|total:|total [a-z0-9_,]+: [0-9]+ valid|  [a-z0-9_,]+: [0-9]+ valid, [0-9]+ invalid$)' \
        "target/bevy-validate-$version.txt" > "target/bevy-summary-$version.txt"
    # And the audit's per-stage findings: defs a stage reads but its pipeline never pushes there.
    # (It exits 1: the forward pass's full space is over the audit's default budget.)
    "$bin" --root "$tree" --color never audit 2> /dev/null > "target/bevy-audit-$version.txt" || true
    grep -E '^  - .* is pushed to the .* stage only' "target/bevy-audit-$version.txt" >> "target/bevy-summary-$version.txt" || true
    if $update; then
        cp "target/bevy-summary-$version.txt" "$example/expected.txt"
        echo "== $example/expected.txt rewritten"
    fi
    diff -u "$example/expected.txt" "target/bevy-summary-$version.txt"
    echo "== the figures match $example/expected.txt"
    # The README's and the guide's tables of these figures (where they have one).
    if grep -qF -- "<!-- figures: bevy $version" README.md docs/guide/wesl-trees.md; then
        mode=check
        if $update; then mode=update; fi
        python3 scripts/bevy-figures.py "$mode" "$version" "$example/expected.txt" \
            README.md docs/guide/wesl-trees.md
    fi
    exit 0
fi
exit "$status"
