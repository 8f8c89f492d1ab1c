#!/usr/bin/env python3
"""The documentation's Bevy figures cannot go stale: the Markdown table that follows a line
`<!-- figures: bevy VERSION -->` (one row per device profile: passes, full space, variants
built, distinct, valid, invalid) or `<!-- figures: bevy VERSION per pass -->` (one row per pass:
full space, built, distinct, valid / invalid per profile) in any of the FILES is made from the
summary lines that scripts/bevy.sh --check compares with the example's expected.txt.

    python3 scripts/bevy-figures.py check VERSION EXPECTED FILE...    exit 1 with the difference
    python3 scripts/bevy-figures.py update VERSION EXPECTED FILE...   rewrite the tables

A file without a marker line for VERSION has no table to check (Bevy 0.19.1's figures are in
docs/guide/naga-oil-trees.md). scripts/bevy.sh calls it after its own comparison, with
README.md and docs/guide/wesl-trees.md.
"""
import difflib
import re
import sys

PASS = re.compile(
    r"^(?P<pass>[a-z0-9_]+/[A-Za-z/]+): (?P<built>\d+) built \((?P<space>\d+) full space\), "
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


def summary(expected):
    """(passes, totals, per-profile totals) of expected.txt's summary lines."""
    passes = []  # [name, space, built, distinct, valid, invalid, {profile: (valid, invalid)}]
    total = None
    single = None  # (valid, invalid) of a one-profile run
    per_profile = {}  # profile -> [valid, invalid], summed over the passes, in order
    with open(expected, encoding="utf-8") as f:
        for line in f.read().split("\n"):
            m = PASS.match(line)
            if m:
                passes.append([m["pass"], m["space"], m["built"], m["distinct"],
                               m["valid"], m["invalid"], {}])
                continue
            m = PROFILE.match(line)
            if m and passes:
                passes[-1][6][m["profile"]] = (m["valid"], m["invalid"])
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
    return passes, total, per_profile or {"webgpu": single}


def table(expected):
    """The per-profile table's lines."""
    passes, total, per_profile = summary(expected)
    space = sum(int(p[1]) for p in passes)
    out = list(HEADER)
    for profile, (valid, invalid) in per_profile.items():
        out.append(
            f"| `{profile}` | {total['passes']} | {n(space)} | {n(total['built'])} | "
            f"{n(total['distinct'])} | {n(valid)} | {n(invalid)} |"
        )
    return out


def per_pass_table(expected):
    """The per-pass table's lines."""
    passes, total, per_profile = summary(expected)
    profiles = list(per_profile)
    out = [
        "| shader/pass | full space | built | distinct | "
        + " | ".join(f"`{p}` valid / invalid" for p in profiles) + " |",
        "|---|---:|---:|---:|" + "---:|" * len(profiles),
    ]
    for name, space, built, distinct, valid, invalid, by_profile in passes:
        cells = [
            f"{n(by_profile[p][0])} / {n(by_profile[p][1])}" if by_profile
            else f"{n(valid)} / {n(invalid)}"
            for p in profiles
        ]
        out.append(f"| `{name}` | {n(space)} | {n(built)} | {n(distinct)} | " + " | ".join(cells) + " |")
    cells = [f"{n(v)} / {n(i)}" for v, i in per_profile.values()]
    out.append(
        f"| total ({total['passes']} passes) | {n(sum(int(p[1]) for p in passes))} | "
        f"{n(total['built'])} | {n(total['distinct'])} | " + " | ".join(cells) + " |"
    )
    return out


def main():
    if len(sys.argv) < 5 or sys.argv[1] not in ("check", "update"):
        sys.exit("usage: python3 scripts/bevy-figures.py check|update VERSION EXPECTED FILE...")
    mode, version, expected = sys.argv[1:4]
    tables = {
        f"<!-- figures: bevy {version} -->": table,
        f"<!-- figures: bevy {version} per pass -->": per_pass_table,
    }
    failed = False
    for path in sys.argv[4:]:
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        changed = False
        for marker, make in tables.items():
            if marker not in lines:
                continue
            start = lines.index(marker) + 1
            end = start
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            want = make(expected)
            have = lines[start:end]
            if have == want:
                print(f"bevy-figures: {path}:{start + 1}: the table matches {expected}")
            elif mode == "update":
                lines[start:end] = want
                changed = True
                print(f"bevy-figures: {path}:{start + 1}: the table now holds the figures of {expected}")
            else:
                failed = True
                sys.stdout.writelines(
                    l + "\n"
                    for l in difflib.unified_diff(
                        have, want, f"{path} (the table after line {start})", expected, lineterm=""
                    )
                )
        if changed:
            with open(path, "w", encoding="utf-8") as f:
                f.write("\n".join(lines))
    if failed:
        print(
            f"bevy-figures: the Bevy {version} tables differ from {expected}.\n"
            f"If the change is intended: bash scripts/bevy.sh --bevy {version} --update",
            file=sys.stderr,
        )
        sys.exit(1)


main()
