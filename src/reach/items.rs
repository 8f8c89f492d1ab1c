//! Splitting WGSL into its top-level items, fed one line at a time.
//!
//! A conservative lexer, not a parser: it tracks `{}` and `()`/`[]` depth, comments (nested
//! block comments included) and the previous significant character, which is all it takes to
//! find where each top-level item (`fn`, `struct`, `const`, `override`, `alias`, `var`,
//! `const_assert` and the global directives) starts and ends, the name it declares, and every
//! identifier it mentions. Identifiers after `.` (members, swizzles) and `@` (attribute names)
//! are not references; everything else is, shadowing locals and member names included — an
//! over-approximation, which can only keep more than needed.

use crate::preprocess::lines::comment_step;

/// What kind of top-level item a run of text is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Not known yet (attributes only so far).
    Pending,
    /// `fn`.
    Function,
    /// `struct`.
    Struct,
    /// `const`, `alias` or a module-scope `var` (bindings included).
    Declaration,
    /// `override`: part of a pipeline's interface, so always kept.
    Override,
    /// `const_assert`, `enable`, `requires` or `diagnostic`: always kept.
    Directive,
    /// Anything else: kept, so that naga sees (and reports) it.
    Unknown,
}

/// One top-level item.
#[derive(Clone, Debug)]
pub(crate) struct Item<'t> {
    /// Its kind.
    pub kind: Kind,
    /// The name it declares (`None` for directives and unknown text).
    pub name: Option<&'t str>,
    /// Every identifier it mentions (not its own name), in order, with repeats.
    pub refs: Vec<&'t str>,
    /// The identifiers among [`Item::refs`] that a caller said are conditional (mentioned at
    /// a deeper [`Splitter::level`] than the item's first token).
    pub cond_refs: Vec<&'t str>,
    /// [`Splitter::level`] at the item's first token.
    pub level: u32,
    /// An entry point (`@vertex`, `@fragment` or `@compute`).
    pub entry: bool,
    /// An entry point's stage attribute (`vertex`, `fragment`, `compute`).
    pub stage: Option<&'t str>,
    /// The line its first token is on.
    pub first_line: u32,
    /// The line its last token is on, or where a block comment that opens after that token
    /// closes.
    pub last_line: u32,
}

impl Item<'_> {
    /// Whether the item is kept whatever references it: entry points, overrides, directives
    /// and text the splitter does not know.
    pub fn is_root(&self) -> bool {
        self.entry || matches!(self.kind, Kind::Override | Kind::Directive | Kind::Unknown)
    }
}

/// The lexer state between lines (cloneable, so that a caller can re-scan from a point, as
/// the all-branches scan of a module with `#if` does).
#[derive(Clone, Debug, Default)]
pub(crate) struct State {
    /// `{}` depth.
    depth: i32,
    /// `()` / `[]` depth at brace depth 0 (attribute arguments, `const` initialisers).
    paren: i32,
    /// Block-comment nesting.
    comment: u32,
    /// The previous significant character (`.`, `@`, or `a` after an identifier).
    prev: char,
    /// The item being read, as an index into [`Splitter::items`].
    open: Option<usize>,
    /// The next identifier is the open item's name.
    expect_name: bool,
    /// Inside the `<…>` of `var<…>`.
    in_template: bool,
    /// An item that ended before a block comment that is still open: its lines go on to
    /// the comment's end.
    extend: Option<usize>,
    /// Brace depth went below zero, or a token came where no item can be.
    broken: bool,
}

impl State {
    /// The item being read, if one is open.
    pub fn open(&self) -> Option<usize> {
        self.open
    }
}

/// Splits text into items, line by line.
#[derive(Default, Debug)]
pub(crate) struct Splitter<'t> {
    /// The state after the last line.
    pub state: State,
    /// The items so far, in order.
    pub items: Vec<Item<'t>>,
    /// The caller's nesting level (the all-branches scan counts `#if` levels): references
    /// made deeper than their item's first token are also listed in [`Item::cond_refs`].
    pub level: u32,
}

impl<'t> Splitter<'t> {
    /// Splits a whole text (lines end at `\n`, as a composed variant's do); `None` when the
    /// text is not well-formed enough to split (naga will report why).
    pub fn split(text: &'t str) -> Option<Vec<Item<'t>>> {
        let mut splitter = Splitter::default();
        for (n, line) in text.split_terminator('\n').enumerate() {
            splitter.line(n as u32, line);
        }
        splitter.finish()
    }

    /// The items, when every one of them ended and nothing was malformed.
    pub fn finish(self) -> Option<Vec<Item<'t>>> {
        let s = &self.state;
        (!s.broken && s.depth == 0 && s.paren == 0 && s.comment == 0 && s.open.is_none())
            .then_some(self.items)
    }

    /// Reads line number `n`.
    pub fn line(&mut self, n: u32, line: &'t str) {
        // Byte by byte: this runs over every line of every variant. Comments start with `/`;
        // every non-ASCII character is taken as a letter, so identifiers end at ASCII bytes
        // (char boundaries).
        let bytes = line.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let b = bytes[i];
            if (self.state.comment > 0 || b == b'/')
                && let Some(skip) = comment_step(&line[i..], &mut self.state.comment)
            {
                i += skip;
                continue;
            }
            if is_ident_start(b) {
                let start = i;
                i += 1;
                while i < bytes.len() && is_ident_continue(bytes[i]) {
                    i += 1;
                }
                self.ident(n, &line[start..i]);
                continue;
            }
            if b.is_ascii_digit() {
                // A number with its suffix or exponent letters: not an identifier.
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'.') {
                    i += 1;
                }
                self.state.prev = '0';
                continue;
            }
            // ASCII here: non-ASCII bytes start identifiers.
            if !crate::preprocess::lines::is_blank(char::from(b)) {
                self.punct(n, char::from(b));
            }
            i += 1;
        }
        let s = &mut self.state;
        if let Some(i) = s.extend {
            self.items[i].last_line = n;
            if s.comment == 0 {
                s.extend = None;
            }
        } else if s.comment > 0
            && s.open.is_none()
            && self.items.last().is_some_and(|l| l.last_line == n)
        {
            // `} /* …` on an item's last line: the comment belongs to that item's lines.
            s.extend = Some(self.items.len() - 1);
        }
    }

    /// Starts an item at line `n` unless one is open.
    fn open(&mut self, n: u32) -> usize {
        if let Some(open) = self.state.open {
            return open;
        }
        self.items.push(Item {
            kind: Kind::Pending,
            name: None,
            refs: Vec::new(),
            cond_refs: Vec::new(),
            level: self.level,
            entry: false,
            stage: None,
            first_line: n,
            last_line: n,
        });
        let open = self.items.len() - 1;
        self.state.open = Some(open);
        open
    }

    fn close(&mut self, n: u32) {
        if let Some(open) = self.state.open.take() {
            let item = &mut self.items[open];
            item.last_line = n;
            if item.kind == Kind::Pending {
                item.kind = Kind::Unknown;
            }
        }
        self.state.expect_name = false;
        self.state.in_template = false;
    }

    fn punct(&mut self, n: u32, c: char) {
        let top = self.state.depth == 0;
        if top && c != ';' && c != '}' {
            self.open(n);
        }
        let s = &mut self.state;
        s.prev = c;
        match c {
            '{' => s.depth += 1,
            '}' => {
                s.depth -= 1;
                if s.depth < 0 {
                    s.broken = true;
                    s.depth = 0;
                } else if s.depth == 0 && s.paren == 0 {
                    self.close(n);
                }
            }
            '(' | '[' if top => s.paren += 1,
            ')' | ']' if top => s.paren -= 1,
            '<' if top && s.expect_name => s.in_template = true,
            '>' if top && s.in_template => s.in_template = false,
            // A stray `;` between items (no item open) is an empty declaration: nothing to keep.
            ';' if top && s.paren == 0 && s.open.is_some() => self.close(n),
            _ => {}
        }
    }

    fn ident(&mut self, n: u32, word: &'t str) {
        let prev = std::mem::replace(&mut self.state.prev, 'a');
        let open = if self.state.depth == 0 {
            self.open(n)
        } else {
            match self.state.open {
                Some(open) => open,
                None => {
                    self.state.broken = true;
                    return;
                }
            }
        };
        let s = &mut self.state;
        let item = &mut self.items[open];
        if prev == '@' {
            if s.depth == 0 && matches!(word, "vertex" | "fragment" | "compute") {
                item.entry = true;
                item.stage = Some(word);
            }
            return;
        }
        if prev == '.' || s.in_template {
            return;
        }
        if s.expect_name {
            s.expect_name = false;
            item.name = Some(word);
            return;
        }
        if s.depth == 0 && s.paren == 0 && item.kind == Kind::Pending {
            item.kind = match word {
                "fn" => Kind::Function,
                "struct" => Kind::Struct,
                "const" | "alias" | "var" => Kind::Declaration,
                "override" => Kind::Override,
                "const_assert" | "enable" | "requires" | "diagnostic" => Kind::Directive,
                _ => Kind::Unknown,
            };
            s.expect_name = !matches!(item.kind, Kind::Directive | Kind::Unknown);
            return;
        }
        item.refs.push(word);
        if self.level > item.level {
            item.cond_refs.push(word);
        }
    }
}

/// WGSL identifiers start with a letter (XID_Start) or `_`; anything non-ASCII (any byte of
/// it) is taken as a letter, so an identifier is never split.
fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_' || !b.is_ascii()
}

fn is_ident_continue(b: u8) -> bool {
    is_ident_start(b) || b.is_ascii_digit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(text: &str) -> Vec<(Kind, Option<&str>, bool, u32, u32)> {
        Splitter::split(text)
            .unwrap()
            .into_iter()
            .map(|i| (i.kind, i.name, i.entry, i.first_line, i.last_line))
            .collect()
    }

    #[test]
    fn items_are_found_with_their_lines() {
        let text = "enable f16;\n\
                    struct S {\n  a: f32,\n}\n\
                    @group(0) @binding(1)\nvar<uniform> u: S;\n\
                    const K = array<f32, 2>(1.0, 2.5e-3);\n\
                    // a comment\n\
                    fn f(x: f32) -> f32 { return x * K[0]; }\n\
                    @fragment fn main() -> @location(0) vec4f {\n  return vec4f(f(u.a));\n}\n";
        assert_eq!(
            names(text),
            [
                (Kind::Directive, None, false, 0, 0),
                (Kind::Struct, Some("S"), false, 1, 3),
                (Kind::Declaration, Some("u"), false, 4, 5),
                (Kind::Declaration, Some("K"), false, 6, 6),
                (Kind::Function, Some("f"), false, 8, 8),
                (Kind::Function, Some("main"), true, 9, 11),
            ]
        );
    }

    #[test]
    fn members_and_attributes_are_not_references() {
        let items =
            Splitter::split("fn g() { let v = a.b; }\n@compute @workgroup_size(W) fn c() {}\n")
                .unwrap();
        assert_eq!(items[0].refs, ["let", "v", "a"]);
        assert_eq!(items[1].refs, ["W"]);
        assert!(items[1].entry);
    }

    #[test]
    fn a_block_comment_after_an_item_belongs_to_its_lines() {
        let items = Splitter::split("const a = 1; /* x\n y\n z */ const b = 2;\n").unwrap();
        assert_eq!((items[0].first_line, items[0].last_line), (0, 2));
        assert_eq!((items[1].first_line, items[1].last_line), (2, 2));
    }

    #[test]
    fn malformed_text_does_not_split() {
        for text in [
            "fn f() {\n",
            "}\n",
            "const a = 1\n",
            "/* open\n",
            "fn f() { } }\n",
        ] {
            assert!(Splitter::split(text).is_none(), "{text:?}");
        }
    }
}
