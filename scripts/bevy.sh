#!/usr/bin/env bash
# Validates Bevy 0.19.1's PBR shaders (a tree no one here wrote) with the declaration file
# examples/bevy_pbr/wgsl-variants.toml: `bash scripts/bevy.sh [validate options]`
# (default `--cover 2`). `bash scripts/bevy.sh --check` (CI) runs the default and compares its
# summary lines with examples/bevy_pbr/expected.txt: the figures the README reports.
#
# The WGSL is fetched at run time by cargo itself (a throwaway manifest that depends on the
# published crates bevy_pbr, bevy_render and bevy_core_pipeline 0.19.1, then `cargo fetch`:
# checksums and mirrors come from cargo), never committed: only the declaration file is ours.
# The tree is assembled under target/bevy-0.19.1/<crate>/src/…, so diagnostics name Bevy's own
# paths.
set -euo pipefail
cd "$(dirname "$0")/.."
version=0.19.1
tree="target/bevy-$version"
fetch="target/bevy-fetch"
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

[workspace]
MANIFEST
touch "$fetch/lib.rs"
echo "== cargo fetch: bevy_pbr, bevy_render, bevy_core_pipeline $version"
cargo fetch -q --manifest-path "$fetch/Cargo.toml"
# Where cargo unpacked each crate: its manifest's folder, from `cargo metadata`.
cargo metadata -q --format-version 1 --manifest-path "$fetch/Cargo.toml" |
    python3 -c '
import json, sys
for p in json.load(sys.stdin)["packages"]:
    if p["name"] in ("bevy_pbr", "bevy_render", "bevy_core_pipeline") and p["version"] == sys.argv[1]:
        print(p["name"], p["manifest_path"].rsplit("/", 1)[0])
' "$version" |
    while read -r crate unpacked; do
        (cd "$unpacked" && find src -name '*.wgsl' -print0) |
            while IFS= read -r -d '' f; do
                mkdir -p "$tree/$crate/$(dirname "$f")"
                cp "$unpacked/$f" "$tree/$crate/$f"
            done
    done
cp examples/bevy_pbr/wgsl-variants.toml "$tree/"
echo "== $(find "$tree" -name '*.wgsl' | wc -l) WGSL files in $tree"
# WGSL_VARIANTS_BIN: a binary already built (CI passes the test build's, see .ci/run).
bin="${WGSL_VARIANTS_BIN:-}"
if [ -z "$bin" ]; then
    cargo build --release -q -p wgsl-variants-cli
    bin=target/release/wgsl-variants
fi
"$bin" --root "$tree" list
check=false
if [ "${1:-}" = --check ]; then check=true; shift; fi
args=("$@")
if [ ${#args[@]} -eq 0 ]; then args=(--cover 2); fi
start=$(date +%s%N)
status=0
"$bin" --root "$tree" --color never validate "${args[@]}" --no-cache > target/bevy-validate.txt || status=$?
end=$(date +%s%N)
cat target/bevy-validate.txt
echo "== validate ${args[*]}: $(( (end - start) / 1000000 )) ms (exit $status: 1 means some variants failed)"
if $check; then
    # The summary lines (built, distinct, valid, invalid per pass and in total) are
    # deterministic: any change is a change in this tool or in the declaration.
    grep -E '^([a-z_]+/[A-Za-z]+: [0-9]+ built|total:)' target/bevy-validate.txt > target/bevy-summary.txt
    diff -u examples/bevy_pbr/expected.txt target/bevy-summary.txt
    echo "== the figures match examples/bevy_pbr/expected.txt"
    exit 0
fi
exit "$status"
