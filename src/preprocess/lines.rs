//! Splitting a module into lines and finding its directive lines.
//!
//! A directive is a line whose first non-blank character is `#`, outside a `/* */` block
//! comment (WGSL block comments nest). WGSL itself has no `#` token, so nothing else is taken.

use std::ops::Range;

/// One line of a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Line {
    /// Byte range of the line in the file, without its `\n`.
    pub range: Range<usize>,
    /// For a directive line: byte range of the directive text after `#`, without a trailing
    /// `//` comment or blanks.
    pub directive: Option<Range<usize>>,
    /// A WGSL line that holds nothing but blanks or a `//` comment (outside block comments):
    /// dropping it changes no program.
    pub comment_only: bool,
}

/// Splits `text` into lines and classifies each one.
pub fn scan(text: &str) -> Vec<Line> {
    let mut lines = Vec::new();
    let mut depth = 0usize; // block-comment nesting at the start of the current line
    let mut start = 0;
    for piece in text.split_inclusive('\n') {
        let end = start + piece.strip_suffix('\n').map_or(piece.len(), str::len);
        let line = &text[start..end];
        let trimmed = line.trim_start();
        let comment_only = trimmed.is_empty() || (depth == 0 && trimmed.starts_with("//"));
        let directive = if depth == 0 && trimmed.starts_with('#') {
            let body_start = end - trimmed.len() + 1;
            let body = &text[body_start..end];
            let body = body.find("//").map_or(body, |i| &body[..i]);
            Some(body_start..body_start + body.trim_end().len())
        } else {
            depth = comment_depth_after(line, depth);
            None
        };
        lines.push(Line {
            range: start..end,
            comment_only: comment_only && directive.is_none(),
            directive,
        });
        start += piece.len();
    }
    lines
}

/// Block-comment nesting after scanning `line`, starting at nesting `depth`.
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
    fn ranges_exclude_newline() {
        let lines = scan("ab\ncd");
        assert_eq!(lines[0].range, 0..2);
        assert_eq!(lines[1].range, 3..5);
    }
}
