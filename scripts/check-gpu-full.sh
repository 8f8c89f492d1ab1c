#!/usr/bin/env bash
# Every variant of the selected passes proven on the GPU (`check-gpu --full`), run as N
# processes one after another (`--shard K/N`) and merged (`wgsl-variants merge`) into the
# report one run would give.
#
#   bash scripts/check-gpu-full.sh [-n N] [-o FILE] CHECK-GPU-OPTIONS...
#   bash scripts/check-gpu-full.sh -n 16 --shader standard --pass ForwardBase
#
# Why processes: under Mesa's lavapipe a process keeps most of a megabyte for every pipeline
# it compiled, a new device or not (docs/guide/gpu-proof.md, "Whole spaces"): one process over
# standard/ForwardBase's 55,296 variants grew past 18 GB in 8 minutes; a shard of 3,456
# variants peaks near 2.5 GB. Each shard prints its time on stderr; the merged JSON
# report goes to FILE (default: target/check-gpu-full.json) and its summary to stdout.
# The exit status is merge's: 0 when every shard passed, 1 on a mismatch, 2 on bad usage.
# The binary is $WGSL_VARIANTS (default: target/release/wgsl-variants; build it first with
# `cargo build --release`).
set -euo pipefail

n=16
out=target/check-gpu-full.json
while [ $# -gt 0 ]; do
    case "$1" in
    -n) n="${2:-}"; shift 2 || shift ;;
    -o) out="${2:-}"; shift 2 || shift ;;
    -h | --help) sed -n '2,17p' "$0"; exit 0 ;;
    *) break ;;
    esac
done
case "$n" in '' | *[!0-9]* | 0) echo "check-gpu-full: -n needs a positive number, not '$n'" >&2; exit 2 ;; esac
bin="${WGSL_VARIANTS:-target/release/wgsl-variants}"
[ -x "$bin" ] || { echo "check-gpu-full: no $bin; run cargo build --release first (or set WGSL_VARIANTS)" >&2; exit 2; }

dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
start=$(date +%s)
for k in $(seq 1 "$n"); do
    t=$(date +%s)
    status=0
    "$bin" check-gpu --json --full --shard "$k/$n" "$@" > "$dir/shard-$k.json" 2> "$dir/shard-$k.err" || status=$?
    # Exit 1 with a report is a mismatch, which merge counts; anything else is an error.
    if [ "$status" -ne 0 ] && ! [ -s "$dir/shard-$k.json" ]; then
        echo "check-gpu-full: shard $k/$n failed (exit $status):" >&2
        cat "$dir/shard-$k.err" >&2
        exit "$status"
    fi
    echo "shard $k/$n: $(($(date +%s) - t)) s (exit $status; $(($(date +%s) - start)) s in all)" >&2
done
mkdir -p "$(dirname "$out")"
status=0
"$bin" merge "$dir"/shard-*.json > "$out" || status=$?
[ "$status" -le 1 ] || { cat "$out" >&2; exit "$status"; }
python3 - "$out" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for p in r.get("passes", []):
    print(f"{p['shader']}/{p['pass']}: {p['variants_run']} variants ({p['distinct_shaders']} distinct), "
          f"{p['pixels_compared']} texels, {p['mismatches']} mismatches")
print(f"adapter: {r.get('adapter')}")
PY
echo "merged report: $out ($(($(date +%s) - start)) s in all)"
exit "$status"
