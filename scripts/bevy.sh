#!/usr/bin/env bash
# Validates Bevy 0.19.1's PBR shaders (a tree no one here wrote) with the declaration file
# examples/bevy_pbr/wgsl-variants.toml: `bash scripts/bevy.sh [validate options]`
# (default `--cover 2`). `bash scripts/bevy.sh --check` (CI) runs the default and compares its
# summary lines with examples/bevy_pbr/expected.txt: the figures the README reports.
#
# The WGSL is fetched at run time from crates.io's static host (the published crates
# bevy_pbr, bevy_render and bevy_core_pipeline 0.19.1, checksums pinned below), never
# committed: only the declaration file is ours. The tree is assembled under
# target/bevy-0.19.1/<crate>/src/…, so diagnostics name Bevy's own paths.
set -euo pipefail
cd "$(dirname "$0")/.."
version=0.19.1
tree="target/bevy-$version"
downloads="target/bevy-downloads"
mkdir -p "$downloads"
rm -rf "$tree"
mkdir -p "$tree"
while read -r crate sha; do
    file="$downloads/$crate-$version.crate"
    if [ ! -f "$file" ] || ! echo "$sha  $file" | sha256sum -c --quiet 2>/dev/null; then
        echo "== fetching $crate $version"
        curl -sSfL "https://static.crates.io/crates/$crate/$crate-$version.crate" -o "$file"
        echo "$sha  $file" | sha256sum -c --quiet
    fi
    unpacked="$downloads/$crate-$version"
    rm -rf "$unpacked"
    tar xzf "$file" -C "$downloads"
    (cd "$unpacked" && find src -name '*.wgsl' -print0) |
        while IFS= read -r -d '' f; do
            mkdir -p "$tree/$crate/$(dirname "$f")"
            cp "$unpacked/$f" "$tree/$crate/$f"
        done
done <<'CRATES'
bevy_pbr 244ae7d618b51a59c913c36b0564a295cd85ea91a5e777b542bb7bdb846a23d6
bevy_render fc86a32b2eef9859e1e7d323c6d1a9150fe77aa17c30fd05abebc12f645929dc
bevy_core_pipeline 2564f1ba766532e8eeb20059133ff6703e8dd5c3864b92378d0d1c541096ef12
CRATES
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
