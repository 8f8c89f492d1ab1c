#!/usr/bin/env python3
"""The README's Bevy figures cannot go stale: the Markdown table that follows the line
`<!-- figures: bevy VERSION -->` in README.md is made from the summary lines that
scripts/bevy.sh --check compares with the example's expected.txt (one row per device profile:
passes, full space, variants built, distinct, valid, invalid).

    python3 scripts/bevy-figures.py check VERSION EXPECTED README    exit 1 with the difference
    python3 scripts/bevy-figures.py update VERSION EXPECTED README   rewrite the table

A README without the marker line for VERSION has no table to check (Bevy 0.19.1's figures are
in docs/guide/naga-oil-trees.md). scripts/bevy.sh calls it after its own comparison.
"""
import difflib
import re
import sys

PASS = re.compile(
    r"^(?P<pass>[a-z_]+/[A-Za-z]+): (?P<built>\d+) built \((?P<space>\d+) full space\), "
    r"(?P<distinct>\d+) distinct, (?P<valid>\d+) valid(?: on every profile)?, "
    r"(?P<invalid>\d+) invalid(?: on some)?$"
)
PROFILE = re.compile(r"^  (?P<profile>[a-z0-9_,]+): (?P<valid>\d+) valid, (?P<invalid>\d+) invalid$")
TOTAL = re.compile(
    r"^total: (?P<passes>\d+) passes, (?P<built>\d+) variants built, (?P<distinct>\d+) distinct, "
)
HEADER = [
    "| profile | passes | full space | built | distinct | valid | invalid |",
    "|---|---:|---:|---:|---:|---:|---:|",
]


def n(x):
    return f"{int(x):,}"


def table(expected):
    """The table's lines, from the summary lines of expected.txt."""
    space = 0
    total = None
    single = None  # (valid, invalid) of a one-profile run
    per_profile = {}  # profile -> [valid, invalid], summed over the passes, in order
    with open(expected, encoding="utf-8") as f:
        for line in f.read().split("\n"):
            m = PASS.match(line)
            if m:
                space += int(m["space"])
                continue
            m = PROFILE.match(line)
            if m:
                counts = per_profile.setdefault(m["profile"], [0, 0])
                counts[0] += int(m["valid"])
                counts[1] += int(m["invalid"])
                continue
            m = TOTAL.match(line)
            if m:
                total = m
                v = re.search(r"(\d+) valid(?: on every profile)?, (\d+) invalid", line)
                single = (v[1], v[2])
    if total is None:
        sys.exit(f"bevy-figures: {expected} has no `total:` line")
    rows = per_profile.items() if per_profile else [("webgpu", single)]
    out = list(HEADER)
    for profile, (valid, invalid) in rows:
        out.append(
            f"| `{profile}` | {total['passes']} | {n(space)} | {n(total['built'])} | "
            f"{n(total['distinct'])} | {n(valid)} | {n(invalid)} |"
        )
    return out


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("check", "update"):
        sys.exit("usage: python3 scripts/bevy-figures.py check|update VERSION EXPECTED README")
    mode, version, expected, readme = sys.argv[1:]
    marker = f"<!-- figures: bevy {version} -->"
    with open(readme, encoding="utf-8") as f:
        lines = f.read().split("\n")
    if marker not in lines:
        print(f"bevy-figures: {readme} has no `{marker}` table")
        return
    at = lines.index(marker)
    start = at + 1
    end = start
    while end < len(lines) and lines[end].startswith("|"):
        end += 1
    want = table(expected)
    have = lines[start:end]
    if have == want:
        print(f"bevy-figures: {readme}'s Bevy {version} table matches {expected}")
        return
    if mode == "update":
        lines[start:end] = want
        with open(readme, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        print(f"bevy-figures: {readme}:{start + 1}: the table now holds the figures of {expected}")
        return
    sys.stdout.writelines(
        l + "\n"
        for l in difflib.unified_diff(
            have, want, f"{readme} (the table after line {at + 1})", expected, lineterm=""
        )
    )
    print(
        f"bevy-figures: {readme}'s Bevy {version} table differs from {expected}.\n"
        f"If the change is intended: bash scripts/bevy.sh --bevy {version} --update",
        file=sys.stderr,
    )
    sys.exit(1)


main()
