#!/usr/bin/env bash
# Checks the documentation (CI runs it, .ci/run):
#
# - every relative Markdown link in README.md and docs/**/*.md resolves: the target file or
#   folder exists (relative to the linking file) and, for `file.md#anchor` or `#anchor`, the
#   anchor is a heading of the target (GitHub's anchors: lowercase, spaces to `-`, punctuation
#   dropped, `-1`, `-2`, … for repeated headings) or an explicit `<a id="…">` / `<a name="…">`;
# - README.md is a front door: at most 250 lines (the rest belongs in docs/guide/).
#
# Links inside fenced code blocks and inline code are not links. Web addresses (https:, mailto:
# and other schemes) are not checked. Prints `file:line: …` for each problem and exits 1.
#
# Usage: bash scripts/check-docs.sh
set -euo pipefail
cd "$(dirname "$0")/.."

python3 - <<'PY'
import os
import re
import sys
import unicodedata
from urllib.parse import unquote

README_MAX_LINES = 250

files = ["README.md"]
for root, dirs, names in os.walk("docs"):
    dirs.sort()
    for name in sorted(names):
        if name.endswith(".md"):
            files.append(os.path.join(root, name))

FENCE = re.compile(r"^ {0,3}(?:[-*+] +|\d+[.)] +)?\s*(`{3,}|~{3,})")


def blank_code(text):
    """The text with fenced code blocks and inline code spans replaced by spaces (newlines
    kept, so offsets and line numbers stay those of the file)."""
    lines = text.split("\n")
    out = []
    fence = None
    for line in lines:
        m = FENCE.match(line)
        if fence is None:
            if m:
                fence = m.group(1)
                out.append(" " * len(line))
                continue
            out.append(line)
        else:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence) \
                    and line.strip() == m.group(1):
                fence = None
            out.append(" " * len(line))
    text = "\n".join(out)
    # Inline code: a run of backticks up to the same run (may span lines within a paragraph).
    def spaces(m):
        return re.sub(r"[^\n]", " ", m.group(0))
    return re.sub(r"(`+)(?:(?!\1).)+?\1", spaces, text, flags=re.S)


def slug(heading):
    """GitHub's anchor for a heading's text."""
    h = re.sub(r"!\[([^\]]*)\]\([^)]*\)", r"\1", heading)   # images: their alt text
    h = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", h)          # links: their text
    h = re.sub(r"<[^>]+>", "", h)                          # HTML tags
    h = h.replace("`", "").replace("*", "")
    h = h.strip().lower()
    kept = []
    for c in h:
        cat = unicodedata.category(c)
        if c in " -_" or cat[0] in "LNM":
            kept.append(c)
    return "".join(kept).replace(" ", "-")


anchors_cache = {}


def anchors(path):
    """Every anchor a Markdown file defines."""
    if path in anchors_cache:
        return anchors_cache[path]
    with open(path, encoding="utf-8") as f:
        raw = f.read()
    # Headings are read from the raw text with fenced blocks blanked (inline code counts: a
    # heading's `code` is part of its anchor).
    lines = raw.split("\n")
    fence = None
    visible = []
    for line in lines:
        m = FENCE.match(line)
        if fence is None:
            if m:
                fence = m.group(1)
                visible.append("")
                continue
            visible.append(line)
        else:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence) \
                    and line.strip() == m.group(1):
                fence = None
            visible.append("")
    found = set()
    seen = {}

    def add(text):
        s = slug(text)
        n = seen.get(s, 0)
        seen[s] = n + 1
        found.add(s if n == 0 else f"{s}-{n}")

    for i, line in enumerate(visible):
        m = re.match(r"^ {0,3}(#{1,6})\s+(.*?)\s*(?:\s#+\s*)?$", line)
        if m:
            add(m.group(2))
            continue
        # Setext headings: a paragraph line underlined with === or ---.
        if i + 1 < len(visible) and line.strip() and not line.lstrip().startswith(("|", "-", "*", ">")):
            if re.match(r"^ {0,3}(=+|-+)\s*$", visible[i + 1]):
                add(line.strip())
    for m in re.finditer(r"<a\s+(?:[^>]*\s)?(?:id|name)\s*=\s*\"([^\"]+)\"", raw):
        found.add(m.group(1))
    anchors_cache[path] = found
    return found


LINK = re.compile(
    r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]"        # [text], one level of nested brackets
    r"\(\s*(<[^>\n]*>|[^()\s]*(?:\([^()\s]*\)[^()\s]*)*)"  # (target
    r"(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)"     # "title")
)
# A reference definition `[label]: target` starts a block (it cannot interrupt a paragraph).
REFDEF = re.compile(r"(?:\A|\n[ \t]*\n) {0,3}\[[^\]\n]+\]:[ \t]*(<[^>\n]*>|\S+)")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")

problems = []


def check(src, line, target):
    if target.startswith("<") and target.endswith(">"):
        target = target[1:-1]
    if not target:
        problems.append(f"{src}:{line}: empty link target")
        return
    if SCHEME.match(target) or target.startswith("//"):
        return
    path, _, anchor = target.partition("#")
    path = unquote(path)
    if path:
        if path.startswith("/"):
            dest = os.path.normpath(path.lstrip("/"))
        else:
            dest = os.path.normpath(os.path.join(os.path.dirname(src), path))
        if not os.path.exists(dest):
            problems.append(f"{src}:{line}: broken link `{target}`: {dest} does not exist")
            return
    else:
        dest = src
    if anchor:
        if os.path.isdir(dest) or not dest.endswith(".md"):
            return  # anchors of other files (e.g. GitHub's #L12 line anchors) are not checked
        if unquote(anchor) not in anchors(dest):
            problems.append(f"{src}:{line}: broken link `{target}`: no heading `#{anchor}` in {dest}")


for src in files:
    with open(src, encoding="utf-8") as f:
        text = f.read()
    visible = blank_code(text)
    for m in LINK.finditer(visible):
        line = visible.count("\n", 0, m.start(1)) + 1
        check(src, line, m.group(1))
    for m in REFDEF.finditer(visible):
        line = visible.count("\n", 0, m.start(1)) + 1
        check(src, line, m.group(1))

with open("README.md", encoding="utf-8") as f:
    readme_lines = f.read().count("\n")
if readme_lines > README_MAX_LINES:
    problems.append(
        f"README.md:{README_MAX_LINES + 1}: the README has {readme_lines} lines, more than "
        f"{README_MAX_LINES}: it is the front door; move the details into docs/guide/"
    )

for p in problems:
    print(p)
if problems:
    print(f"check-docs: {len(problems)} problem(s) in {len(files)} Markdown files", file=sys.stderr)
    sys.exit(1)
print(f"check-docs: {len(files)} Markdown files, every relative link resolves; "
      f"README.md has {readme_lines} lines (at most {README_MAX_LINES})")
PY
