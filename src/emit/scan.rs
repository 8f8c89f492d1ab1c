//! Which names each module declares at top level and which it uses (every `#if` branch
//! scanned): what the dialect exports ([`super::naga_oil`], [`super::wesl`]) need to write
//! item imports, since our `#import` is textual and theirs name items.

use std::collections::BTreeSet;

use crate::library::Library;
use crate::preprocess::lines::comment_step;
use crate::preprocess::tree::Node;

/// What a module declares at top level and which identifiers it uses (all branches).
#[derive(Default, Debug)]
pub(crate) struct Scan {
    pub(crate) declared: BTreeSet<String>,
    pub(crate) used: BTreeSet<String>,
    /// Struct member names declared.
    pub(crate) members: BTreeSet<String>,
}

/// What `nodes` (a pass's body, say) declare and use.
pub(crate) fn scan_nodes(nodes: &[Node], text: &str, lines: &[std::ops::Range<u32>]) -> Scan {
    let mut scanner = Scanner::default();
    scanner.nodes(nodes, text, lines);
    scanner.scan
}

pub(crate) fn scan_library(lib: &Library) -> Vec<Scan> {
    let graph = lib.module_graph();
    graph
        .modules
        .iter()
        .map(|m| {
            let text = graph.files.text(m.file);
            let mut scanner = Scanner::default();
            scanner.nodes(&m.body, text, &m.lines);
            scanner.scan
        })
        .collect()
}

#[derive(Default)]
struct Scanner {
    scan: Scan,
    depth: i32,
    in_block_comment: u32,
    /// The previous significant character (`.` and `@` make the next identifier a member or
    /// an attribute).
    prev: char,
    /// Waiting for the name after `fn`, `struct`, `const`, `override`, `alias` or `var`.
    expect_decl: bool,
    /// Inside the `<…>` of `var<…>`.
    in_var_template: bool,
    /// 1: the last declaration keyword was `struct`; 2: inside that struct's body.
    struct_state: u8,
    /// An identifier in a struct body that a `:` makes a member name.
    pending_member: Option<String>,
}

impl Scanner {
    fn nodes(&mut self, nodes: &[Node], text: &str, lines: &[std::ops::Range<u32>]) {
        for node in nodes {
            match node {
                Node::Text(run) => {
                    for line in &lines[run.start as usize..run.end as usize] {
                        self.line(&text[line.start as usize..line.end as usize]);
                    }
                }
                Node::If(cond) => {
                    // Every branch starts at the same depth; continue with the first's end.
                    let start = self.depth;
                    let mut end = None;
                    for body in cond
                        .branches
                        .iter()
                        .map(|(_, b)| b)
                        .chain(std::iter::once(&cond.otherwise))
                    {
                        self.depth = start;
                        self.nodes(body, text, lines);
                        end.get_or_insert(self.depth);
                    }
                    self.depth = end.unwrap_or(start);
                }
                _ => {}
            }
        }
    }

    fn line(&mut self, line: &str) {
        let bytes = line.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            if let Some(skip) = comment_step(&line[i..], &mut self.in_block_comment) {
                i += skip;
                if line[i - skip..].starts_with("//") {
                    return;
                }
                continue;
            }
            let c = line[i..].chars().next().unwrap_or(' ');
            if c.is_ascii_alphabetic() || c == '_' {
                let start = i;
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                self.ident(&line[start..i]);
                continue;
            }
            if c.is_ascii_digit() {
                // A number (with its suffix) is not an identifier.
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'.') {
                    i += 1;
                }
                self.prev = '0';
                continue;
            }
            if !c.is_whitespace() {
                if c == ':'
                    && let Some(member) = self.pending_member.take()
                {
                    self.scan.members.insert(member);
                }
                self.pending_member = None;
                match c {
                    '{' => {
                        self.depth += 1;
                        if self.struct_state == 1 && self.depth == 1 {
                            self.struct_state = 2;
                        }
                    }
                    '}' => {
                        self.depth -= 1;
                        if self.depth == 0 {
                            self.struct_state = 0;
                        }
                    }
                    '<' if self.expect_decl => self.in_var_template = true,
                    '>' if self.in_var_template => self.in_var_template = false,
                    _ => {}
                }
                self.prev = c;
            }
            i += c.len_utf8();
        }
    }

    fn ident(&mut self, word: &str) {
        let after_member = self.prev == '.' || self.prev == '@';
        self.prev = 'a';
        if after_member || self.in_var_template {
            return;
        }
        if self.struct_state == 2 && self.depth == 1 {
            self.pending_member = Some(word.to_string());
        }
        if self.expect_decl {
            self.expect_decl = false;
            if self.depth == 0 {
                self.scan.declared.insert(word.to_string());
            }
            return;
        }
        if self.depth == 0
            && matches!(
                word,
                "fn" | "struct" | "const" | "override" | "alias" | "var"
            )
        {
            self.expect_decl = true;
            if word == "struct" {
                self.struct_state = 1;
            }
            return;
        }
        self.scan.used.insert(word.to_string());
    }
}
