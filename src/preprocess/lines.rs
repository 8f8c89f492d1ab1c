//! Splitting a module into lines and finding its directive lines.
//!
//! Lines are WGSL's: a line break is LF, VT, FF, CR, CR LF (one break), NEL (U+0085), LS
//! (U+2028) or PS (U+2029), and blank is WGSL blankspace — exactly what naga's lexer uses, so a
//! `//` comment ends where naga ends it. A directive is a line whose first non-blank character
//! is `#`, outside a `/* */` block comment (WGSL block comments nest). WGSL itself has no `#`
//! token, so nothing else is taken.

use std::ops::Range;

/// WGSL blankspace (Unicode Pattern_White_Space): space, tab, the line breaks, and the
/// left-to-right / right-to-left marks. Unlike [`char::is_whitespace`], NBSP (U+00A0) and the
/// other Unicode spaces are *not* blank: naga rejects them.
pub(crate) fn is_blank(c: char) -> bool {
    matches!(
        c,
        ' ' | '\t' | '\u{000a}'
            ..='\u{000d}' | '\u{0085}' | '\u{200e}' | '\u{200f}' | '\u{2028}' | '\u{2029}'
    )
}

/// `s` without leading WGSL blankspace.
pub(crate) fn trim_blank_start(s: &str) -> &str {
    s.trim_start_matches(is_blank)
}

/// `s` without trailing WGSL blankspace.
pub(crate) fn trim_blank_end(s: &str) -> &str {
    s.trim_end_matches(is_blank)
}

/// The first line break at or after byte `from`: its byte range (two bytes for CR LF).
pub(crate) fn next_break(text: &str, from: usize) -> Option<Range<usize>> {
    let bytes = text.as_bytes();
    let mut i = from;
    while i < bytes.len() {
        // Every break starts with one of these bytes; UTF-8 continuation bytes never match.
        match bytes[i] {
            b'\r' if bytes.get(i + 1) == Some(&b'\n') => return Some(i..i + 2),
            0x0a..=0x0d => return Some(i..i + 1),
            0xc2 if bytes.get(i + 1) == Some(&0x85) => return Some(i..i + 2),
            0xe2 if bytes.get(i + 1) == Some(&0x80)
                && matches!(bytes.get(i + 2), Some(0xa8 | 0xa9)) =>
            {
                return Some(i..i + 3);
            }
            _ => i += 1,
        }
    }
    None
}

/// The lines of `text`: for each, the byte range of its content and of its line break (empty
/// for a last line without one). A final break does not start another line; empty text has
/// no lines.
pub(crate) fn split(text: &str) -> impl Iterator<Item = (Range<usize>, Range<usize>)> + '_ {
    let mut start = 0;
    std::iter::from_fn(move || {
        if start >= text.len() {
            return None;
        }
        let brk = next_break(text, start).unwrap_or(text.len()..text.len());
        let line = (start..brk.start, brk.clone());
        start = brk.end;
        Some(line)
    })
}

/// The byte offset where each line starts, as an editor numbers lines: 0, then the end of
/// every line break (so text ending in a break has an empty last line).
pub(crate) fn line_starts(text: &str) -> Vec<usize> {
    let mut starts = vec![0];
    let mut at = 0;
    while let Some(brk) = next_break(text, at) {
        starts.push(brk.end);
        at = brk.end;
    }
    starts
}

/// One line of a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Line {
    /// Byte range of the line in the file, without its line break.
    pub range: Range<usize>,
    /// For a directive line: byte range of the directive text after `#`, without a trailing
    /// `//` comment or blanks.
    pub directive: Option<Range<usize>>,
    /// A WGSL line that holds nothing but blankspace or a `//` comment (outside block
    /// comments): dropping it, with its line break, changes no program.
    pub comment_only: bool,
}

/// Splits `text` into lines and classifies each one.
pub(crate) fn scan(text: &str) -> Vec<Line> {
    let mut lines = Vec::new();
    let mut depth = 0usize; // block-comment nesting at the start of the current line
    for (range, _) in split(text) {
        let line = &text[range.clone()];
        let trimmed = trim_blank_start(line);
        let comment_only = trimmed.is_empty() || (depth == 0 && trimmed.starts_with("//"));
        let directive = if depth == 0 && trimmed.starts_with('#') {
            let body_start = range.end - trimmed.len() + 1;
            let body = &text[body_start..range.end];
            let body = body.find("//").map_or(body, |i| &body[..i]);
            Some(body_start..body_start + trim_blank_end(body).len())
        } else {
            depth = comment_depth_after(line, depth);
            None
        };
        lines.push(Line {
            range,
            comment_only: comment_only && directive.is_none(),
            directive,
        });
    }
    lines
}

/// Block-comment nesting after scanning `line`, starting at nesting `depth`.
///
/// Two-byte tokens are matched left to right without overlap, as naga's lexer matches them:
/// `/*/` opens one comment, `*/*` closes one, and `//` outside a comment hides the rest of
/// the line (which is where naga ends that comment too, since lines end at WGSL breaks).
fn comment_depth_after(line: &str, mut depth: usize) -> usize {
    let bytes = line.as_bytes();
    let mut i = 0;
    while i + 1 < bytes.len() {
        match (bytes[i], bytes[i + 1]) {
            (b'/', b'*') => {
                depth += 1;
                i += 2;
            }
            (b'*', b'/') if depth > 0 => {
                depth -= 1;
                i += 2;
            }
            (b'/', b'/') if depth == 0 => break,
            _ => i += 1,
        }
    }
    depth
}

/// Inside a comment or at its start: the bytes to skip (a whole `//` comment, a `/*` or `*/`,
/// or one character of a block comment), updating the block-comment nesting `depth`; `None`
/// at code. Steps whole characters, so comments may hold any text.
pub(crate) fn comment_step(rest: &str, depth: &mut u32) -> Option<usize> {
    if rest.starts_with("/*") {
        *depth += 1;
        return Some(2);
    }
    if *depth > 0 {
        if rest.starts_with("*/") {
            *depth -= 1;
            return Some(2);
        }
        return Some(rest.chars().next().map_or(1, char::len_utf8));
    }
    rest.starts_with("//")
        .then(|| rest.find('\n').unwrap_or(rest.len()))
}

/// Where nesting first passes `limit`, outside comments: brackets (`(`, `[`, `{`) plus the
/// run of prefix operators (`!`, `~`, `-`, `*`, `&`) at that point. `None` when it never does.
///
/// Parsers that build a tree recursively (wgsl-parse, read for WESL trees) overflow the stack
/// on deep enough nesting, and a stack overflow aborts the process; this scan runs first, in
/// constant stack, so such text is refused with a location instead.
#[cfg_attr(not(feature = "wesl"), allow(dead_code))]
pub(crate) fn nesting_past(text: &str, limit: usize) -> Option<usize> {
    let mut depth = 0usize;
    let mut run = 0usize;
    let mut comment = 0u32;
    let mut i = 0;
    while i < text.len() {
        if let Some(skip) = comment_step(&text[i..], &mut comment) {
            i += skip;
            continue;
        }
        let b = text.as_bytes()[i];
        match b {
            b'(' | b'[' | b'{' => {
                depth += 1;
                run = 0;
            }
            b')' | b']' | b'}' => {
                depth = depth.saturating_sub(1);
                run = 0;
            }
            b'!' | b'~' | b'-' | b'*' | b'&' => run += 1,
            b' ' | b'\t' | b'\n' | b'\r' => {}
            _ => run = 0,
        }
        if depth + run > limit {
            return Some(i);
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn directives(text: &str) -> Vec<&str> {
        scan(text)
            .into_iter()
            .filter_map(|l| l.directive.map(|r| &text[r]))
            .collect()
    }

    #[test]
    fn nesting_is_measured_outside_comments() {
        assert_eq!(nesting_past("f((a));", 2), None);
        assert_eq!(nesting_past("f(((a)));", 2), Some(3));
        assert_eq!(nesting_past("// ((((\n/* (((( */ f(a);", 2), None);
        assert_eq!(nesting_past("x = - - -a;", 2), Some(8));
        assert_eq!(nesting_past("x = a - b - c - d;", 2), None);
    }

    #[test]
    fn finds_directives_and_strips_comments() {
        let text = "  #if A // note\nlet x = 1;\n#endif\n";
        assert_eq!(directives(text), vec!["if A", "endif"]);
    }

    #[test]
    fn ignores_hash_in_comments() {
        let text = "// #if A\n/* start\n#if B\n /* nested */\n#endif\n*/\n#define C\n";
        assert_eq!(directives(text), vec!["define C"]);
    }

    #[test]
    fn line_comment_hides_block_opener() {
        let text = "let a = 1; // /* not a comment\n#define X\n";
        assert_eq!(directives(text), vec!["define X"]);
    }

    #[test]
    fn every_wgsl_break_ends_a_line_and_crlf_is_one() {
        let text = "a\nb\rc\r\nd\u{b}e\u{c}f\u{85}g\u{2028}h\u{2029}i";
        let lines: Vec<&str> = scan(text).iter().map(|l| &text[l.range.clone()]).collect();
        assert_eq!(lines, ["a", "b", "c", "d", "e", "f", "g", "h", "i"]);
        assert_eq!(line_starts("a\r\nb\r").len(), 3);
        assert_eq!(scan("a\u{2028}").len(), 1);
        assert!(scan("").is_empty());
    }

    #[test]
    fn line_comment_ends_at_any_break() {
        for brk in ["\r", "\u{b}", "\u{c}", "\u{85}", "\u{2028}", "\u{2029}"] {
            let text = format!("// note{brk}fn f() {{}}{brk}#define X{brk}/*{brk}#if 0{brk}*/");
            let lines = scan(&text);
            assert!(lines[0].comment_only);
            assert!(!lines[1].comment_only, "{brk:?}");
            assert_eq!(directives(&text), vec!["define X"], "{brk:?}");
        }
    }

    #[test]
    fn blank_is_wgsl_blankspace_not_unicode_white_space() {
        assert!(scan("\u{200e}\u{200f} \t").iter().all(|l| l.comment_only));
        assert!(!scan("\u{a0}").iter().any(|l| l.comment_only));
        assert!(!scan("\u{3000}// x").iter().any(|l| l.comment_only));
        assert_eq!(directives("\u{200e}#define X\u{200f}"), vec!["define X"]);
        assert!(directives("\u{a0}#define X").is_empty());
    }

    #[test]
    fn ranges_exclude_newline() {
        let lines = scan("ab\ncd");
        assert_eq!(lines[0].range, 0..2);
        assert_eq!(lines[1].range, 3..5);
    }
}
