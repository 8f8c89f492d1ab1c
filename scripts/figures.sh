#!/usr/bin/env bash
# The README's main-job figures cannot go stale: the fenced block that follows the marker line
# `<!-- figures: validate --all -->` in README.md is the output of the main job
# (`wgsl-variants validate --all`: one line per pass and a `total:` line).
#
#   bash scripts/figures.sh check FILE    compare the block with FILE, the main job's stdout;
#                                         exit 1 with the difference when they differ
#   bash scripts/figures.sh update FILE   rewrite the block from FILE
#
# Of FILE, the per-pass lines (`shader/pass: N built (…`) and the `total:` line are taken, in
# order; anything else the job may print is not part of the figures. CI (.ci/run) runs
# `target/release/wgsl-variants validate --all | tee target/main-job.txt` and then
# `bash scripts/figures.sh check target/main-job.txt`.
#
# `check` also holds the committed manifest summary (`snapshots/manifest.snap`, whose whole
# form is an ignored test: it compiles every distinct text) to the main job: every pass's
# variant and distinct counts must be the main job's, so a manifest left behind by a change
# that moves them fails CI.
set -euo pipefail

usage() {
    echo "usage: bash scripts/figures.sh check|update FILE" >&2
    exit 2
}
[ $# -eq 2 ] || usage
mode="$1"
file="$2"
case "$mode" in check | update) ;; *) usage ;; esac
[ -f "$file" ] || { echo "figures: $file: no such file" >&2; exit 2; }
root="$(cd "$(dirname "$0")/.." && pwd)"

python3 - "$mode" "$file" "$root/README.md" "$root/snapshots/manifest.snap" <<'PY'
import difflib
import re
import sys

mode, file, readme, manifest = sys.argv[1:5]
MARKER = "<!-- figures: validate --all -->"
FIGURE = re.compile(r"^[^\s:]+/[^\s:]+: \d+ built \(|^total: ")

with open(readme, encoding="utf-8") as f:
    lines = f.read().split("\n")
try:
    at = lines.index(MARKER)
except ValueError:
    sys.exit(f"figures: README.md has no line `{MARKER}`")
opening = at + 1
while opening < len(lines) and not lines[opening].strip():
    opening += 1
if opening >= len(lines) or not lines[opening].startswith("```"):
    sys.exit(f"figures: README.md:{at + 1}: the marker is not followed by a fenced block")
closing = opening + 1
while closing < len(lines) and lines[closing].strip() != "```":
    closing += 1
if closing >= len(lines):
    sys.exit(f"figures: README.md:{opening + 1}: the fenced block is not closed")
block = lines[opening + 1:closing]

with open(file, encoding="utf-8") as f:
    run = [l.rstrip("\r") for l in f.read().split("\n") if FIGURE.match(l)]
if not run or not run[-1].startswith("total: "):
    sys.exit(f"figures: {file} holds no main-job figures (per-pass lines and a `total:` line)")

if mode == "update":
    if block == run:
        print(f"figures: README.md already holds the figures of {file}")
    else:
        lines[opening + 1:closing] = run
        with open(readme, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        print(f"figures: README.md:{opening + 2}: the block now holds the figures of {file}")
    sys.exit(0)

# (shader/pass, variants, distinct) of the main job (built whole under --all) and of the
# committed manifest summary.
JOB = re.compile(r"^([^\s:]+/[^\s:]+): (\d+) built \((\d+) full space\), (\d+) distinct")
SNAP = re.compile(r"^([^\s:]+/[^\s:]+): (\d+) variants, (\d+) distinct, digest ")
job = [(m[1], m[3], m[4]) for m in map(JOB.match, run) if m]
with open(manifest, encoding="utf-8") as f:
    snap = [(m[1], m[2], m[3]) for m in map(SNAP.match, f.read().split("\n")) if m]
if job != snap:
    sys.stdout.writelines(
        l + "\n" for l in difflib.unified_diff(
            [f"{p}: {v} variants, {d} distinct" for p, v, d in snap],
            [f"{p}: {v} variants, {d} distinct" for p, v, d in job],
            "snapshots/manifest.snap", file, lineterm=""))
    print(
        "figures: snapshots/manifest.snap's counts differ from the main job's: review the whole\n"
        "manifest (cargo test --release --ignore-rust-version --test snapshots -- --ignored, then\n"
        "cargo insta review)",
        file=sys.stderr,
    )
    sys.exit(1)

if block == run:
    print(f"figures: README.md's main-job block matches {file} ({len(run)} lines); "
          f"snapshots/manifest.snap's counts match ({len(snap)} passes)")
    sys.exit(0)
sys.stdout.writelines(
    l + "\n" for l in difflib.unified_diff(
        block, run, f"README.md (the block after line {at + 1})", file, lineterm=""))
print(
    f"figures: README.md's main-job figures differ from {file}.\n"
    f"If the change is intended, rewrite the block: bash scripts/figures.sh update {file}",
    file=sys.stderr,
)
sys.exit(1)
PY
