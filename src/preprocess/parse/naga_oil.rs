//! naga_oil's directives (Bevy's shader dialect), parsed into the same tree as ours so that
//! the import graph, its diagnostics and the audit's static walk work on naga_oil trees.
//!
//! The syntax is naga_oil 0.23's (its preprocessor's patterns, restated): a directive is a
//! line starting with `#`, blanks allowed after it; `#ifdef D`, `#ifndef D`,
//! `#if D OP VALUE` (`OP` one of `== != < <= > >=`, `VALUE` an integer or `true`/`false`),
//! `#else`, `#else ifdef D`, `#else ifndef D`, `#else if D OP VALUE`, `#endif`,
//! `#define D [VALUE]`, `#define_import_path a::b`, `#import …` (Rust-like paths, `{…}`
//! groups over several lines, `as` aliases) and `#version N` (GLSL; ignored). Composition is
//! naga_oil's own ([`crate::library`]); this tree only says which lines each def decides.

use crate::diagnostic::Span;

use super::super::error::ParseError;
use super::super::expr::{BinOp, Expr};
use super::super::lines::Line;
use super::super::tree::{ImportRef, Node};
use super::{ModuleParser, is_name};

impl ModuleParser<'_> {
    /// One naga_oil directive line; `range` is the text after `#`.
    pub(super) fn naga_oil_directive(&mut self, range: std::ops::Range<usize>) {
        let raw = &self.text[range.clone()];
        // naga_oil allows blanks between `#` and the directive's name.
        let start = range.start + (raw.len() - raw.trim_start().len());
        let (name, name_span, args, args_start, args_span) = self.split_directive(&range, start);
        let result = match name {
            "ifdef" | "ifndef" | "if" => {
                let directive = match name {
                    "ifdef" => "ifdef",
                    "ifndef" => "ifndef",
                    _ => "if",
                };
                let result = self.condition(directive, args, args_span);
                let cond = result.clone().unwrap_or(Expr::Int(0));
                self.open(directive, name_span, cond);
                result.map(|_| ())
            }
            "else" if args.is_empty() => {
                self.else_(name_span);
                Ok(())
            }
            "else" => {
                let (kind, rest) = args.split_at(
                    args.find(|c: char| !c.is_ascii_alphabetic())
                        .unwrap_or(args.len()),
                );
                let directive = match kind {
                    "ifdef" => "else ifdef",
                    "ifndef" => "else ifndef",
                    "if" => "else if",
                    _ => {
                        return self.errors.push(ParseError::Malformed {
                            directive: "else",
                            message: format!(
                                "expected nothing, `ifdef D`, `ifndef D` or `if D OP VALUE` after `#else`, found `{args}`"
                            ),
                            span: args_span,
                        });
                    }
                };
                let rest = rest.trim_start();
                let rest_span =
                    self.span(args_start + args.len() - rest.len()..args_start + args.len());
                let result = self.condition(&directive[5..], rest, rest_span);
                let cond = result.clone().unwrap_or(Expr::Int(0));
                self.elif(directive, name_span, cond);
                result.map(|_| ())
            }
            "endif" => self
                .no_args("endif", args, args_span)
                .map(|_| self.endif(name_span)),
            "define" => {
                let mapped = match args.split_whitespace().collect::<Vec<_>>()[..] {
                    [n, "true"] => format!("{n} 1"),
                    [n, "false"] => format!("{n} 0"),
                    _ => args.to_string(),
                };
                self.define(&mapped, args_span)
            }
            "define_import_path" => self.define_import_path(args, name_span, args_span),
            "import" => {
                self.seen_code = true;
                self.open_import = Some((args.to_string(), self.span(range.start - 1..range.end)));
                self.close_import_if_complete();
                Ok(())
            }
            "version" => Ok(()),
            _ => Err(self.unknown_directive(name, &range, name_span)),
        };
        if let Err(e) = result {
            self.errors.push(e);
        }
    }

    /// The condition of `#ifdef D`, `#ifndef D` or `#if D OP VALUE`.
    fn condition(
        &self,
        directive: &'static str,
        args: &str,
        span: Span,
    ) -> Result<Expr, ParseError> {
        match directive {
            "ifdef" | "ifndef" => {
                // naga_oil reads the first word (letters, digits, `_`; `#ifdef 0` is a def
                // never set) and ignores the rest of the line.
                let def = args.split_whitespace().next().unwrap_or("");
                if def.is_empty() || !def.chars().all(|c| c.is_alphanumeric() || c == '_') {
                    return Err(ParseError::Malformed {
                        directive,
                        message: if def.is_empty() {
                            "expected a name".to_string()
                        } else {
                            format!("expected one name, found `{args}`")
                        },
                        span,
                    });
                }
                let defined = Expr::Defined(def.into());
                Ok(if directive == "ifdef" {
                    defined
                } else {
                    Expr::Not(Box::new(defined))
                })
            }
            _ => parse_comparison(args).ok_or_else(|| ParseError::Malformed {
                directive: "if",
                message: format!(
                    "expected `D OP VALUE` (OP one of == != < <= > >=, VALUE an integer, `true` or `false`), found `{args}`"
                ),
                span,
            }),
        }
    }

    fn define_import_path(
        &mut self,
        args: &str,
        name_span: Span,
        args_span: Span,
    ) -> Result<(), ParseError> {
        if self.import_name.is_some() {
            return Err(ParseError::Misplaced {
                directive: "define_import_path",
                message: "is written twice in one module",
                span: name_span,
            });
        }
        let path = args.split_whitespace().next().unwrap_or("");
        if path.is_empty() || !path.split("::").all(is_name) {
            return Err(ParseError::Malformed {
                directive: "define_import_path",
                message: format!(
                    "expected a module name such as `my_lib::lighting`, found `{args}`"
                ),
                span: args_span,
            });
        }
        self.import_name = Some((path.to_string(), args_span));
        Ok(())
    }

    /// A line of an `#import` whose `{` group is still open.
    pub(super) fn continue_import(&mut self, line: &Line) {
        let text = &self.text[line.range.clone()];
        if let Some((args, span)) = self.open_import.as_mut() {
            args.push('\n');
            args.push_str(text.split("//").next().unwrap_or(""));
            *span = Span::new(span.file, span.range().start..line.range.end);
        }
        self.close_import_if_complete();
    }

    /// Records the open import once its braces balance.
    fn close_import_if_complete(&mut self) {
        let Some((args, span)) = &self.open_import else {
            return;
        };
        if args.matches('{').count() > args.matches('}').count() {
            return;
        }
        let (args, span) = (args.clone(), *span);
        self.open_import = None;
        match import_paths(&args) {
            Ok(paths) => {
                for path in paths {
                    let index = self.imports.len();
                    self.imports.push(ImportRef { path, span });
                    self.container().push(Node::Import(index));
                }
            }
            Err(message) => self.errors.push(ParseError::Malformed {
                directive: "import",
                message,
                span,
            }),
        }
    }

    /// An `#import` still open at the end of the file.
    pub(super) fn finish_open_import(&mut self) {
        if let Some((_, span)) = self.open_import.take() {
            self.errors.push(ParseError::Malformed {
                directive: "import",
                message: "its `{` is never closed".into(),
                span,
            });
        }
    }
}

/// `D OP VALUE` as an expression; `true`/`false` are 1/0, as the composition's defines hold
/// booleans.
fn parse_comparison(args: &str) -> Option<Expr> {
    let name_len = args
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(args.len());
    let (name, rest) = args.split_at(name_len);
    if !is_name(name) {
        return None;
    }
    let rest = rest.trim_start();
    let op_len = rest
        .find(|c: char| !"=!<>".contains(c))
        .unwrap_or(rest.len());
    let op = match &rest[..op_len] {
        "==" => BinOp::Eq,
        "!=" => BinOp::Ne,
        "<" => BinOp::Lt,
        "<=" => BinOp::Le,
        ">" => BinOp::Gt,
        ">=" => BinOp::Ge,
        _ => return None,
    };
    let value = rest[op_len..].split_whitespace().next()?;
    let value = match value {
        "true" => 1,
        "false" => 0,
        v => v.parse::<i64>().ok()?,
    };
    Some(Expr::Binary(
        op,
        Box::new(Expr::Name(name.into())),
        Box::new(Expr::Int(value)),
    ))
}

/// The full paths an `#import` names, `{…}` groups expanded: `a::{b, c::{d as e}}` gives
/// `a::b` and `a::c::d`. Aliases and a final `;` are accepted and dropped.
///
/// ```text
/// list  := entry (',' entry)* ','?
/// entry := path ('::' '{' list '}')? ('as' name)?
/// path  := segment ('::' segment)*        segment: a name or a "quoted" asset path
/// ```
fn import_paths(args: &str) -> Result<Vec<String>, String> {
    let tokens = tokenize(args)?;
    let mut out = Vec::new();
    let mut at = 0;
    list(&tokens, &mut at, "", &mut out)?;
    if at != tokens.len() {
        return Err(format!("unexpected `{}`", tokens[at]));
    }
    if out.is_empty() {
        return Err("expected a module path, e.g. `#import my_lib::lighting`".into());
    }
    Ok(out)
}

fn tokenize(args: &str) -> Result<Vec<String>, String> {
    let mut tokens = Vec::new();
    let mut chars = args.trim().trim_end_matches(';').chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            c if c.is_whitespace() => {}
            '{' | '}' | ',' => tokens.push(c.to_string()),
            ':' if chars.peek() == Some(&':') => {
                chars.next();
                tokens.push("::".into());
            }
            '"' => {
                let mut s = String::from('"');
                loop {
                    match chars.next() {
                        Some('"') => break,
                        Some(c) => s.push(c),
                        None => return Err("a quoted path is never closed".into()),
                    }
                }
                s.push('"');
                tokens.push(s);
            }
            c if c.is_alphanumeric() || c == '_' => {
                let mut s = String::from(c);
                while let Some(&n) = chars.peek() {
                    if n.is_alphanumeric() || n == '_' {
                        s.push(n);
                        chars.next();
                    } else {
                        break;
                    }
                }
                tokens.push(s);
            }
            c => return Err(format!("unexpected `{c}`")),
        }
    }
    Ok(tokens)
}

fn list(
    tokens: &[String],
    at: &mut usize,
    prefix: &str,
    out: &mut Vec<String>,
) -> Result<(), String> {
    loop {
        entry(tokens, at, prefix, out)?;
        if tokens.get(*at).map(String::as_str) == Some(",") {
            *at += 1;
            if matches!(tokens.get(*at).map(String::as_str), None | Some("}")) {
                return Ok(());
            }
        } else {
            return Ok(());
        }
    }
}

fn entry(
    tokens: &[String],
    at: &mut usize,
    prefix: &str,
    out: &mut Vec<String>,
) -> Result<(), String> {
    let segment = |t: Option<&String>| {
        t.filter(|t| t.starts_with('"') || is_name(t))
            .cloned()
            .ok_or_else(|| match t {
                Some(t) => format!("expected a name, found `{t}`"),
                None => "expected a name".to_string(),
            })
    };
    let mut path = prefix.to_string();
    loop {
        let s = segment(tokens.get(*at))?;
        *at += 1;
        if !path.is_empty() {
            path.push_str("::");
        }
        path.push_str(&s);
        if tokens.get(*at).map(String::as_str) != Some("::") {
            break;
        }
        *at += 1;
        if tokens.get(*at).map(String::as_str) == Some("{") {
            *at += 1;
            list(tokens, at, &path, out)?;
            if tokens.get(*at).map(String::as_str) != Some("}") {
                return Err("expected `}`".into());
            }
            *at += 1;
            return Ok(());
        }
    }
    if tokens.get(*at).map(String::as_str) == Some("as") {
        *at += 1;
        segment(tokens.get(*at))?;
        *at += 1;
    }
    out.push(path);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preprocess::parse::{Dialect, ParseLimits, parse_module_in};

    #[test]
    fn import_groups_expand() {
        assert_eq!(
            import_paths("a::{b, c::{d as e, f},}").unwrap(),
            ["a::b", "a::c::d", "a::c::f"]
        );
        assert_eq!(import_paths("my_module as m;").unwrap(), ["my_module"]);
        assert!(import_paths("a::{b").is_err());
        assert!(import_paths("a::*").is_err());
    }

    #[test]
    fn comparisons() {
        assert_eq!(
            parse_comparison("N >= 3"),
            Some(Expr::Binary(
                BinOp::Ge,
                Box::new(Expr::Name("N".into())),
                Box::new(Expr::Int(3))
            ))
        );
        assert!(parse_comparison("N").is_none());
        assert!(parse_comparison("N == x").is_none());
    }

    #[test]
    fn module_with_else_ifdef_and_multi_line_import() {
        let text = "#define_import_path my::lib\n#import my::{\n  a,\n  b::c\n}\n# ifdef A\nx\n#else ifdef B\ny\n#else\nz\n#endif\n";
        let m = parse_module_in(Dialect::NagaOil, 0, text, ParseLimits::default()).unwrap();
        assert_eq!(m.import_name.as_ref().unwrap().0, "my::lib");
        let paths: Vec<_> = m.imports.iter().map(|i| i.path.as_str()).collect();
        assert_eq!(paths, ["my::a", "my::b::c"]);
        let Node::If(cond) = &m.body[2] else {
            panic!("{:?}", m.body)
        };
        assert_eq!(cond.branches.len(), 2);
        assert_eq!(cond.branches[1].0, Expr::Defined("B".into()));
        assert!(!cond.otherwise.is_empty());
    }

    #[test]
    fn bad_directives_are_located() {
        let errors = parse_module_in(
            Dialect::NagaOil,
            0,
            "#ifdef\n#else whatever\n#import a::{b\n",
            ParseLimits::default(),
        )
        .unwrap_err();
        let messages: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
        assert!(
            messages.iter().any(|m| m.contains("`#ifdef`")),
            "{messages:?}"
        );
        assert!(
            messages.iter().any(|m| m.contains("`#else`")),
            "{messages:?}"
        );
        assert!(
            messages.iter().any(|m| m.contains("never closed")),
            "{messages:?}"
        );
    }
}
