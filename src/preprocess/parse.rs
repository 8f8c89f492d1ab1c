//! Parsing a module's directives into a [`ParsedModule`].

use std::ops::Range;

use crate::diagnostic::{FileId, Span};
use crate::keywords::ConstraintKind;

use super::error::ParseError;
use super::expr::{self, Expr};
use super::lines::{self, Line};
use super::tree::{Conditional, ImportRef, Node, ParsedModule, PassDecl, Pragma, ShaderDecl};
use crate::keywords::SetKind;

mod naga_oil;
#[cfg(feature = "wesl")]
mod wesl;

/// The directive languages a module can be written in.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Dialect {
    /// This crate's own: `#shader`/`#pass` blocks with Unity's `#pragma` keyword sets,
    /// `#import path/of/file`, C-like `#if` expressions (README, "Directives").
    #[default]
    WgslVariants,
    /// naga_oil's (Bevy's): `#define_import_path`, `#import a::b::{c}`, `#ifdef`, `#ifndef`,
    /// `#if DEF op VALUE`, `#else ifdef …`, `#endif`, `#define`; keywords are declared in a
    /// [declaration file](crate::declaration), and variants are composed by naga_oil itself.
    NagaOil,
    /// WESL's (Bevy's main branch): `.wesl` modules with `import package::a::{b}` and
    /// `@if` / `@elif` / `@else` attributes on declarations, members and statements; keywords
    /// are WESL features declared in a [declaration file](crate::declaration), and variants
    /// are composed by the `wesl` crate itself.
    Wesl,
}

impl Dialect {
    /// The name used on the command line and in declaration files: `wgsl-variants`,
    /// `naga-oil`.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::WgslVariants => "wgsl-variants",
            Dialect::NagaOil => "naga-oil",
            Dialect::Wesl => "wesl",
        }
    }
}

/// Nesting limits applied while parsing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ParseLimits {
    /// Deepest `#if` nesting.
    pub if_depth: usize,
    /// Deepest expression nesting (parentheses and unary operators).
    pub expr_depth: usize,
}

impl Default for ParseLimits {
    fn default() -> Self {
        ParseLimits {
            if_depth: 256,
            expr_depth: 256,
        }
    }
}

/// Parses `text` (the contents of `file`). Returns every error found, not only the first.
#[cfg(test)]
pub(crate) fn parse_module(
    file: FileId,
    text: &str,
    limits: ParseLimits,
) -> Result<ParsedModule, Vec<ParseError>> {
    parse_module_in(Dialect::WgslVariants, file, text, limits)
}

/// Parses a module written in `dialect`. Returns every error found, not only the first.
pub(crate) fn parse_module_in(
    dialect: Dialect,
    file: FileId,
    text: &str,
    limits: ParseLimits,
) -> Result<ParsedModule, Vec<ParseError>> {
    if dialect == Dialect::Wesl {
        #[cfg(feature = "wesl")]
        return wesl::parse(file, text, limits);
        #[cfg(not(feature = "wesl"))]
        return Err(vec![ParseError::Syntax {
            message: "this build of wgsl-variants has no WESL support (cargo feature `wesl`)"
                .into(),
            span: Span::new(file, 0..0),
        }]);
    }
    let scanned = lines::scan(text);
    let mut p = ModuleParser {
        dialect,
        file,
        text,
        limits,
        import_name: None,
        open_import: None,
        errors: Vec::new(),
        frames: Vec::new(),
        root: Vec::new(),
        imports: Vec::new(),
        shader: None,
        pass: None,
        seen_code: false,
    };
    for (index, line) in scanned.iter().enumerate() {
        p.line(index as u32, line);
    }
    p.finish_open_import();
    p.finish_frames();
    if let Some(pass) = p.pass.take() {
        p.errors.push(ParseError::Unterminated {
            directive: "pass",
            span: pass.span,
        });
    }
    if !p.errors.is_empty() {
        return Err(p.errors);
    }
    let lines = scanned
        .iter()
        .map(|l| l.range.start as u32..l.range.end as u32)
        .collect();
    let comment_only = scanned.iter().map(|l| l.comment_only).collect();
    Ok(ParsedModule {
        file,
        lines,
        comment_only,
        body: p.root,
        imports: p.imports,
        shader: p.shader,
        import_name: p.import_name,
    })
}

struct Frame {
    directive: &'static str,
    span: Span,
    branches: Vec<(Expr, Vec<Node>)>,
    cond: Option<Expr>,
    else_span: Option<Span>,
    nodes: Vec<Node>,
}

struct ModuleParser<'a> {
    dialect: Dialect,
    file: FileId,
    text: &'a str,
    limits: ParseLimits,
    errors: Vec<ParseError>,
    frames: Vec<Frame>,
    root: Vec<Node>,
    imports: Vec<ImportRef>,
    shader: Option<ShaderDecl>,
    pass: Option<PassDecl>,
    /// Whether a WGSL or module directive line has been seen (a `#shader` must come first).
    seen_code: bool,
    /// naga_oil: the `#define_import_path` name.
    import_name: Option<(String, Span)>,
    /// naga_oil: an `#import` whose `{` … `}` continues on the next lines (text so far, span).
    open_import: Option<(String, Span)>,
}

/// The rule for shader and pass names, as the error states it.
const NAME_RULE: &str = "expected a name: `/`-separated parts of letters, digits, `_` and `-`, \
                         each starting with a letter or `_` (e.g. `Hidden/Internal-DeferredShading`)";

/// Shader and pass names follow one rule ([`NAME_RULE`]): they name folders and files of
/// `emit --out` and `bake`, so `.`, `..`, empty parts and leading `/` are never allowed.
fn is_shader_or_pass_name(s: &str) -> bool {
    !s.is_empty()
        && s.split('/').all(|part| {
            part.chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && part
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        })
}

fn is_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

impl<'a> ModuleParser<'a> {
    fn span(&self, range: Range<usize>) -> Span {
        Span::new(self.file, range)
    }

    /// Where new nodes go: the innermost open `#if`, else the pass body, else the module body.
    fn container(&mut self) -> &mut Vec<Node> {
        if let Some(frame) = self.frames.last_mut() {
            &mut frame.nodes
        } else if let Some(pass) = self.pass.as_mut() {
            &mut pass.body
        } else {
            &mut self.root
        }
    }

    fn line(&mut self, index: u32, line: &Line) {
        if self.open_import.is_some() {
            return self.continue_import(line);
        }
        match (&line.directive, self.dialect) {
            (None, _) => self.text_line(index, line),
            (Some(range), Dialect::WgslVariants) => self.directive(range.clone()),
            (Some(range), Dialect::NagaOil) => self.naga_oil_directive(range.clone()),
            // WESL modules are parsed whole (`parse_module_in`), never line by line.
            (Some(_), Dialect::Wesl) => self.text_line(index, line),
        }
    }

    fn text_line(&mut self, index: u32, line: &Line) {
        // WGSL blankspace, as naga would see it (a line of NBSP is code).
        let content =
            lines::trim_blank_start(lines::trim_blank_end(&self.text[line.range.clone()]));
        let is_comment = content.is_empty()
            || content.starts_with("//")
            || content.starts_with("/*")
            || content.starts_with('*');
        if self.shader.is_some() && self.pass.is_none() {
            if !is_comment {
                let start = line.range.start
                    + (self.text[line.range.clone()].len()
                        - lines::trim_blank_start(&self.text[line.range.clone()]).len());
                self.errors.push(ParseError::Misplaced {
                    directive: "shader",
                    message: "files hold only comments outside `#pass … #endpass` blocks; move this WGSL into a module and `#import` it",
                    span: self.span(start..line.range.end.max(start + 1)),
                });
            }
            return;
        }
        if !is_comment {
            self.seen_code = true;
        }
        let nodes = self.container();
        if let Some(Node::Text(run)) = nodes.last_mut()
            && run.end == index
        {
            run.end = index + 1;
            return;
        }
        nodes.push(Node::Text(index..index + 1));
    }

    /// A directive line's parts: its name (which starts at `start`, within `range`, the text
    /// after `#`), the name's span (from the `#`), its arguments, where they start, and their
    /// span (the name's when there are none).
    fn split_directive(
        &self,
        range: &Range<usize>,
        start: usize,
    ) -> (&'a str, Span, &'a str, usize, Span) {
        let text: &'a str = self.text;
        let body = &text[start..range.end];
        let name_len = body
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(body.len());
        let name = &body[..name_len];
        let name_span = self.span(range.start - 1..start + name_len);
        let args_start =
            start + name_len + (body[name_len..].len() - body[name_len..].trim_start().len());
        let args = text[args_start..range.end].trim_end();
        let args_span = if args.is_empty() {
            name_span
        } else {
            self.span(args_start..args_start + args.len())
        };
        (name, name_span, args, args_start, args_span)
    }

    fn directive(&mut self, range: Range<usize>) {
        let (name, name_span, args, args_start, args_span) =
            self.split_directive(&range, range.start);
        let result = match name {
            "if" | "elif" => {
                // A bad expression still opens its branch, so the `#endif` that follows is
                // not reported as unmatched too.
                let result = self.expr(args, args_start, name_span);
                let cond = result.clone().unwrap_or(Expr::Int(0));
                if name == "if" {
                    self.open("if", name_span, cond)
                } else {
                    self.elif("elif", name_span, cond)
                }
                result.map(|_| ())
            }
            "ifdef" | "ifndef" => self
                .single_name(
                    if name == "ifdef" { "ifdef" } else { "ifndef" },
                    args,
                    args_span,
                )
                .map(|n| {
                    let defined = Expr::Defined(n.into());
                    let cond = if name == "ifdef" {
                        defined
                    } else {
                        Expr::Not(Box::new(defined))
                    };
                    self.open(
                        if name == "ifdef" { "ifdef" } else { "ifndef" },
                        name_span,
                        cond,
                    )
                }),
            "else" => self
                .no_args("else", args, args_span)
                .map(|_| self.else_(name_span)),
            "endif" => self
                .no_args("endif", args, args_span)
                .map(|_| self.endif(name_span)),
            "define" => self.define(args, args_span),
            "undef" => self.single_name("undef", args, args_span).map(|n| {
                self.seen_code = true;
                self.container().push(Node::Undef { name: n.into() });
            }),
            "import" => self.import(args, args_span),
            "shader" => self.shader(args, name_span, args_span),
            "pass" => self.pass(args, name_span, args_span),
            "endpass" => self
                .no_args("endpass", args, args_span)
                .map(|_| self.endpass(name_span)),
            "tag" => self.tag(args, name_span, args_span),
            "pragma" => self.pragma(args, args_start, name_span),
            _ => Err(self.unknown_directive(name, &range, name_span)),
        };
        if let Err(e) = result {
            self.errors.push(e);
        }
    }

    /// `#name` is no directive of the dialect (`range`: the text after `#`).
    fn unknown_directive(&self, name: &str, range: &Range<usize>, name_span: Span) -> ParseError {
        ParseError::UnknownDirective {
            name: name.to_string(),
            span: if name.is_empty() {
                self.span(range.start - 1..range.start)
            } else {
                name_span
            },
        }
    }

    fn expr(&self, args: &str, start: usize, name_span: Span) -> Result<Expr, ParseError> {
        if args.is_empty() {
            return Err(ParseError::Expression {
                message: "expected an expression".into(),
                span: name_span,
            });
        }
        expr::parse(args, start, self.file, self.limits.expr_depth)
    }

    fn no_args(&self, directive: &'static str, args: &str, span: Span) -> Result<(), ParseError> {
        if args.is_empty() {
            Ok(())
        } else {
            Err(ParseError::Malformed {
                directive,
                message: "takes no arguments".into(),
                span,
            })
        }
    }

    fn single_name(
        &self,
        directive: &'static str,
        args: &'a str,
        span: Span,
    ) -> Result<&'a str, ParseError> {
        if is_name(args) {
            Ok(args)
        } else {
            let message = if args.is_empty() {
                "expected a name".to_string()
            } else {
                format!("expected one name, found `{args}`")
            };
            Err(ParseError::Malformed {
                directive,
                message,
                span,
            })
        }
    }

    fn open(&mut self, directive: &'static str, span: Span, cond: Expr) {
        self.seen_code = true;
        // Reported once, where the limit is first passed.
        if self.frames.len() == self.limits.if_depth {
            self.errors.push(ParseError::TooDeep {
                what: "`#if`",
                limit: self.limits.if_depth,
                span,
            });
        }
        self.frames.push(Frame {
            directive,
            span,
            branches: Vec::new(),
            cond: Some(cond),
            else_span: None,
            nodes: Vec::new(),
        });
    }

    /// `#elif` (or naga_oil's `#else ifdef` …, named `directive` in errors).
    fn elif(&mut self, directive: &'static str, span: Span, cond: Expr) {
        let Some(frame) = self.frames.last_mut() else {
            return self.errors.push(ParseError::Unmatched { directive, span });
        };
        if let Some(else_span) = frame.else_span {
            return self.errors.push(ParseError::AfterElse {
                directive,
                span,
                else_span,
            });
        }
        let nodes = std::mem::take(&mut frame.nodes);
        if let Some(prev) = frame.cond.replace(cond) {
            frame.branches.push((prev, nodes));
        }
    }

    fn else_(&mut self, span: Span) {
        let Some(frame) = self.frames.last_mut() else {
            return self.errors.push(ParseError::Unmatched {
                directive: "else",
                span,
            });
        };
        if let Some(else_span) = frame.else_span {
            return self.errors.push(ParseError::AfterElse {
                directive: "else",
                span,
                else_span,
            });
        }
        frame.else_span = Some(span);
        let nodes = std::mem::take(&mut frame.nodes);
        if let Some(prev) = frame.cond.take() {
            frame.branches.push((prev, nodes));
        }
    }

    fn endif(&mut self, span: Span) {
        let Some(mut frame) = self.frames.pop() else {
            return self.errors.push(ParseError::Unmatched {
                directive: "endif",
                span,
            });
        };
        let otherwise = if let Some(cond) = frame.cond.take() {
            frame
                .branches
                .push((cond, std::mem::take(&mut frame.nodes)));
            Vec::new()
        } else {
            frame.nodes
        };
        let node = Node::If(Box::new(Conditional {
            branches: frame.branches,
            otherwise,
        }));
        self.container().push(node);
    }

    /// Reports the outermost `#if` still open (end of file or `#endpass`) and closes them all:
    /// one error, however many are open.
    fn finish_frames(&mut self) {
        if let Some(frame) = self.frames.first() {
            self.errors.push(ParseError::Unterminated {
                directive: frame.directive,
                span: frame.span,
            });
        }
        self.frames.clear();
    }

    fn define(&mut self, args: &str, span: Span) -> Result<(), ParseError> {
        let mut parts = args.split_whitespace();
        let name = parts.next().unwrap_or("");
        if !is_name(name) || name == "defined" {
            let message = if name.is_empty() {
                "expected a name".to_string()
            } else {
                format!("`{name}` is not a valid name")
            };
            return Err(ParseError::Malformed {
                directive: "define",
                message,
                span,
            });
        }
        let value = match parts.next() {
            None => 1,
            Some(v) => {
                let (neg, digits) = v.strip_prefix('-').map_or((false, v), |d| (true, d));
                let parsed =
                    expr::parse_int(digits).map(|x| if neg { x.wrapping_neg() } else { x });
                match (parsed, parts.next()) {
                    (Some(x), None) => x,
                    _ => {
                        return Err(ParseError::Malformed {
                            directive: "define",
                            message: format!(
                                "the value of `{name}` must be one integer literal, found `{}`",
                                args[name.len()..].trim()
                            ),
                            span,
                        });
                    }
                }
            }
        };
        self.seen_code = true;
        self.container().push(Node::Define {
            name: name.into(),
            value,
        });
        Ok(())
    }

    fn import(&mut self, args: &str, span: Span) -> Result<(), ParseError> {
        let path = args.strip_suffix(".wgsl").unwrap_or(args);
        let malformed = |message: String| ParseError::Malformed {
            directive: "import",
            message,
            span,
        };
        if path.is_empty() {
            return Err(malformed(
                "expected a module path, e.g. `#import deferred/gbuffer`".into(),
            ));
        }
        if path.contains(char::is_whitespace) || path.contains('\\') || path.contains('"') {
            return Err(malformed(format!(
                "`{args}` is not a module path: write `/`-separated names relative to the library root, unquoted"
            )));
        }
        if path.starts_with('/')
            || path
                .split('/')
                .any(|c| c == ".." || c == "." || c.is_empty())
        {
            return Err(malformed(format!(
                "`{args}` leaves the library root: paths are relative to the root, without `.`, `..` or a leading `/`"
            )));
        }
        self.seen_code = true;
        let index = self.imports.len();
        self.imports.push(ImportRef {
            path: path.to_string(),
            span,
        });
        self.container().push(Node::Import(index));
        Ok(())
    }

    fn shader(&mut self, args: &str, name_span: Span, args_span: Span) -> Result<(), ParseError> {
        if self.shader.is_some() || self.seen_code {
            return Err(ParseError::Misplaced {
                directive: "shader",
                message: "must be the first directive of its file, and only once",
                span: name_span,
            });
        }
        // A malformed name is reported, and the shader is opened all the same, so that its
        // passes are not reported again as misplaced.
        if !is_shader_or_pass_name(args) {
            self.errors.push(ParseError::Malformed {
                directive: "shader",
                message: NAME_RULE.into(),
                span: args_span,
            });
        }
        self.shader = Some(ShaderDecl {
            name: args.to_string(),
            span: args_span,
            passes: Vec::new(),
        });
        Ok(())
    }

    fn pass(&mut self, args: &str, name_span: Span, args_span: Span) -> Result<(), ParseError> {
        if self.shader.is_none() {
            return Err(ParseError::Misplaced {
                directive: "pass",
                message: "is only allowed in a shader file (one that starts with `#shader NAME`)",
                span: name_span,
            });
        }
        if let Some(open) = &self.pass {
            return Err(ParseError::Unterminated {
                directive: "pass",
                span: open.span,
            });
        }
        if !self.frames.is_empty() {
            return Err(ParseError::Misplaced {
                directive: "pass",
                message: "cannot be conditional: close the `#if` first",
                span: name_span,
            });
        }
        // As for `#shader`: reported, and opened all the same so its body and `#endpass` are
        // not reported again.
        if !is_shader_or_pass_name(args) {
            self.errors.push(ParseError::Malformed {
                directive: "pass",
                message: NAME_RULE.into(),
                span: args_span,
            });
        }
        self.pass = Some(PassDecl {
            name: args.to_string(),
            span: args_span,
            tags: Vec::new(),
            pragmas: Vec::new(),
            body: Vec::new(),
            constants: Vec::new(),
            options: Default::default(),
            entry: None,
            module: None,
            profiles: Vec::new(),
            stage: None,
        });
        Ok(())
    }

    fn endpass(&mut self, span: Span) {
        if self.pass.is_none() {
            return self.errors.push(ParseError::Unmatched {
                directive: "endpass",
                span,
            });
        }
        self.finish_frames();
        if let (Some(pass), Some(shader)) = (self.pass.take(), self.shader.as_mut()) {
            shader.passes.push(pass);
        }
    }

    /// Pass-level directives must sit at the top level of a pass body.
    fn pass_level(
        &mut self,
        directive: &'static str,
        span: Span,
    ) -> Result<&mut PassDecl, ParseError> {
        if !self.frames.is_empty() {
            return Err(ParseError::Misplaced {
                directive,
                message: "cannot be conditional: move it out of the `#if`",
                span,
            });
        }
        let message = if self.shader.is_some() {
            "belongs inside a `#pass … #endpass` block"
        } else {
            "belongs in a `#pass` block of a shader file, not in an imported module"
        };
        self.pass.as_mut().ok_or(ParseError::Misplaced {
            directive,
            message,
            span,
        })
    }

    fn tag(&mut self, args: &str, name_span: Span, args_span: Span) -> Result<(), ParseError> {
        let words: Vec<&str> = args.split_whitespace().collect();
        let pass = self.pass_level("tag", name_span)?;
        match words.as_slice() {
            [key, value] => {
                pass.tags.push((key.to_string(), value.to_string()));
                Ok(())
            }
            _ => Err(ParseError::Malformed {
                directive: "tag",
                message: "expected `#tag KEY VALUE`, e.g. `#tag LightMode Deferred`".into(),
                span: args_span,
            }),
        }
    }

    fn pragma(&mut self, args: &str, args_start: usize, name_span: Span) -> Result<(), ParseError> {
        let file = self.file;
        let mut words = Vec::new();
        let mut offset = 0;
        for word in args.split_whitespace() {
            let at = args[offset..].find(word).map_or(offset, |i| offset + i);
            words.push((
                word,
                Span::new(file, args_start + at..args_start + at + word.len()),
            ));
            offset = at + word.len();
        }
        let Some(&(kind, kind_span)) = words.first() else {
            return Err(ParseError::Malformed {
                directive: "pragma",
                message: "expected a pragma name".into(),
                span: name_span,
            });
        };
        let whole = Span::new(file, name_span.start as usize..args_start + args.len());
        let names: Vec<(Box<str>, Span)> = words[1..]
            .iter()
            .map(|(w, s)| (Box::from(*w), *s))
            .collect();
        let pass = self.pass_level("pragma", name_span)?;
        let (set_kind, local) = match kind {
            "multi_compile" => (SetKind::MultiCompile, false),
            "multi_compile_local" => (SetKind::MultiCompile, true),
            "shader_feature" => (SetKind::ShaderFeature, false),
            "shader_feature_local" => (SetKind::ShaderFeature, true),
            "skip_variants" => {
                pass.pragmas.push(Pragma::SkipVariants(names));
                return Ok(());
            }
            "exclude_renderers" => {
                pass.pragmas.push(Pragma::ExcludeRenderers(
                    names.into_iter().map(|n| n.0).collect(),
                ));
                return Ok(());
            }
            "require" | "exclude" => {
                if names.len() < 2 {
                    return Err(ParseError::Malformed {
                        directive: "pragma",
                        message: format!(
                            "`{kind}` needs at least two keywords, e.g. `#pragma {kind} A B`"
                        ),
                        span: kind_span,
                    });
                }
                pass.pragmas.push(Pragma::Constraint {
                    kind: if kind == "require" {
                        ConstraintKind::Require
                    } else {
                        ConstraintKind::Exclude
                    },
                    names,
                    span: whole,
                });
                return Ok(());
            }
            other => {
                return Err(ParseError::Malformed {
                    directive: "pragma",
                    message: format!(
                        "unknown pragma `{other}`; supported: multi_compile, multi_compile_local, shader_feature, shader_feature_local, skip_variants, exclude_renderers, require, exclude"
                    ),
                    span: kind_span,
                });
            }
        };
        if names.is_empty() {
            return Err(ParseError::Malformed {
                directive: "pragma",
                message: format!("`{kind}` needs at least one keyword"),
                span: kind_span,
            });
        }
        if let Some((bad, span)) = names.iter().find(|(n, _)| !is_name(n)) {
            return Err(ParseError::Malformed {
                directive: "pragma",
                message: format!("`{bad}` is not a keyword name (letters, digits, `_`)"),
                span: *span,
            });
        }
        pass.pragmas.push(Pragma::Keywords {
            kind: set_kind,
            local,
            names,
            span: whole,
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ParsedModule, Vec<ParseError>> {
        parse_module(0, text, ParseLimits::default())
    }

    fn span(range: Range<usize>) -> Span {
        Span::new(0, range)
    }

    /// Consecutive WGSL lines form one `Text` run; an `#ifdef … #else … #endif` becomes an
    /// `If` with one branch and an `otherwise` body.
    #[test]
    fn text_runs_and_if_else() {
        let m = parse("a\nb\n#ifdef X\nc\n#else\nd\n#endif\ne").unwrap();
        assert_eq!(m.lines.len(), 8);
        assert_eq!(
            m.body,
            vec![
                Node::Text(0..2),
                Node::If(Box::new(Conditional {
                    branches: vec![(Expr::Defined("X".into()), vec![Node::Text(3..4)])],
                    otherwise: vec![Node::Text(5..6)],
                })),
                Node::Text(7..8),
            ]
        );
    }

    /// `#elif` adds a branch in order; without `#else` the `otherwise` body is empty.
    #[test]
    fn elif_branches_without_else() {
        let m = parse("#ifdef A\na\n#elif B\nb\n#endif").unwrap();
        let [Node::If(cond)] = m.body.as_slice() else {
            panic!("expected one `If`: {:?}", m.body);
        };
        assert_eq!(cond.branches.len(), 2);
        assert_eq!(cond.branches[0].0, Expr::Defined("A".into()));
        assert_eq!(cond.branches[0].1, vec![Node::Text(1..2)]);
        assert_eq!(cond.branches[1].0, Expr::Name("B".into()));
        assert_eq!(cond.branches[1].1, vec![Node::Text(3..4)]);
        assert!(cond.otherwise.is_empty());
    }

    /// `#ifndef` is the negation of `defined`.
    #[test]
    fn ifndef_negates() {
        let m = parse("#ifndef A\n#endif").unwrap();
        let [Node::If(cond)] = m.body.as_slice() else {
            panic!("expected one `If`: {:?}", m.body);
        };
        assert_eq!(
            cond.branches[0].0,
            Expr::Not(Box::new(Expr::Defined("A".into())))
        );
    }

    /// `#define` takes value 1 when none is written, or one (possibly negative) integer;
    /// `#undef` names one name.
    #[test]
    fn define_and_undef() {
        let m = parse("#define A\n#define B 16\n#define C -3\n#undef A").unwrap();
        assert_eq!(
            m.body,
            vec![
                Node::Define {
                    name: "A".into(),
                    value: 1
                },
                Node::Define {
                    name: "B".into(),
                    value: 16
                },
                Node::Define {
                    name: "C".into(),
                    value: -3
                },
                Node::Undef { name: "A".into() },
            ]
        );
    }

    /// Each `#import` gets the next index into `imports`, also inside an `#if`, and a
    /// `.wgsl` suffix is dropped from the path.
    #[test]
    fn import_indices() {
        let m = parse("#import a\n#ifdef X\n#import b.wgsl\n#endif\n#import a").unwrap();
        let paths: Vec<&str> = m.imports.iter().map(|i| i.path.as_str()).collect();
        assert_eq!(paths, ["a", "b", "a"]);
        assert_eq!(m.imports[0].span, span(8..9));
        assert_eq!(m.body[0], Node::Import(0));
        let Node::If(cond) = &m.body[1] else {
            panic!("expected an `If`: {:?}", m.body);
        };
        assert_eq!(cond.branches[0].1, vec![Node::Import(1)]);
        assert_eq!(m.body[2], Node::Import(2));
    }

    /// A shader file's pass keeps its name, tags and pragmas in order, and its body; a plain
    /// module body stays empty.
    #[test]
    fn pass_with_tags_and_pragmas() {
        let text = "#shader s\n#pass P\n#tag LightMode Deferred\n\
                    #pragma multi_compile_local _ A B\n#pragma shader_feature F\n\
                    #pragma skip_variants B\n#pragma exclude_renderers gles\nx\n#endpass";
        let m = parse(text).unwrap();
        assert!(m.body.is_empty());
        let shader = m.shader.unwrap();
        assert_eq!(shader.name, "s");
        assert_eq!(shader.passes.len(), 1);
        let pass = &shader.passes[0];
        assert_eq!(pass.name, "P");
        assert_eq!(pass.span, span(16..17));
        assert_eq!(pass.tags, vec![("LightMode".into(), "Deferred".into())]);
        assert_eq!(pass.pragmas.len(), 4);
        let Pragma::Keywords {
            kind,
            local,
            names,
            span: whole,
        } = &pass.pragmas[0]
        else {
            panic!("expected keywords: {:?}", pass.pragmas[0]);
        };
        assert_eq!(*kind, SetKind::MultiCompile);
        assert!(*local);
        let words: Vec<&str> = names.iter().map(|(n, _)| &**n).collect();
        assert_eq!(words, ["_", "A", "B"]);
        let a = text.find(" A B").unwrap() + 1;
        assert_eq!(names[1].1, span(a..a + 1));
        let line = text.find("#pragma multi").unwrap();
        let line_end = line + text[line..].find('\n').unwrap();
        assert_eq!(*whole, span(line..line_end));
        assert!(matches!(
            &pass.pragmas[1],
            Pragma::Keywords { kind: SetKind::ShaderFeature, local: false, names, .. } if names.len() == 1
        ));
        assert!(
            matches!(&pass.pragmas[2], Pragma::SkipVariants(n) if n.len() == 1 && &*n[0].0 == "B")
        );
        assert_eq!(
            pass.pragmas[3],
            Pragma::ExcludeRenderers(vec!["gles".into()])
        );
        assert_eq!(pass.body, vec![Node::Text(7..8)]);
    }

    /// `#endif`, `#else`, `#elif` and `#endpass` with nothing open are unmatched, at the
    /// directive's name.
    #[test]
    fn unmatched() {
        let errors = parse("a\n#endif").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unmatched {
                directive: "endif",
                span: span(2..8)
            }]
        );
        let errors = parse("#else").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unmatched {
                directive: "else",
                span: span(0..5)
            }]
        );
        let errors = parse("#elif 1").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unmatched {
                directive: "elif",
                span: span(0..5)
            }]
        );
        let errors = parse("#shader s\n#endpass").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unmatched {
                directive: "endpass",
                span: span(10..18)
            }]
        );
    }

    /// An `#if` left open is reported once, at the outermost open directive; so is an open
    /// `#pass`.
    #[test]
    fn unterminated() {
        let errors = parse("x\n#ifdef A\n#if B\ny").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unterminated {
                directive: "ifdef",
                span: span(2..8)
            }]
        );
        let errors = parse("#shader s\n#pass P\nx").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::Unterminated {
                directive: "pass",
                span: span(16..17)
            }]
        );
    }

    /// `#else` or `#elif` after an `#else` points at both directives.
    #[test]
    fn after_else() {
        let errors = parse("#ifdef A\n#else\n#else\n#endif").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::AfterElse {
                directive: "else",
                span: span(15..20),
                else_span: span(9..14)
            }]
        );
        let errors = parse("#ifdef A\n#else\n#elif 1\n#endif").unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::AfterElse {
                directive: "elif",
                span: span(15..20),
                else_span: span(9..14)
            }]
        );
    }

    /// Malformed arguments are reported at the arguments, every error of the file at once.
    #[test]
    fn malformed() {
        let errors = parse("#define 1x\n#import ../up\n#endif extra\n#undef").unwrap_err();
        assert_eq!(errors.len(), 4, "{errors:?}");
        assert!(matches!(
            &errors[0],
            ParseError::Malformed { directive: "define", span: s, .. } if *s == span(8..10)
        ));
        assert!(matches!(
            &errors[1],
            ParseError::Malformed { directive: "import", span: s, .. } if *s == span(19..24)
        ));
        // `#endif extra` is malformed, not unmatched.
        assert!(matches!(
            &errors[2],
            ParseError::Malformed { directive: "endif", span: s, .. } if *s == span(32..37)
        ));
        // No argument: the span is the directive's name.
        assert!(matches!(
            &errors[3],
            ParseError::Malformed { directive: "undef", span: s, .. } if *s == span(38..44)
        ));
        let errors = parse("#define A 1 2").unwrap_err();
        assert!(matches!(
            &errors[..],
            [ParseError::Malformed {
                directive: "define",
                ..
            }]
        ));
    }

    /// `if_depth` allows exactly that many nested `#if`s, and one more is reported once, at
    /// the `#if` that passes the limit.
    #[test]
    fn if_depth_limit() {
        let text = "#ifdef A\n#ifdef B\n#ifdef C\n#endif\n#endif\n#endif";
        let limits = |if_depth| ParseLimits {
            if_depth,
            ..ParseLimits::default()
        };
        assert!(parse_module(0, text, limits(3)).is_ok());
        let errors = parse_module(0, text, limits(2)).unwrap_err();
        assert_eq!(
            errors,
            vec![ParseError::TooDeep {
                what: "`#if`",
                limit: 2,
                span: span(18..24)
            }]
        );
        let errors = parse_module(0, text, limits(1)).unwrap_err();
        assert_eq!(errors.len(), 1, "{errors:?}");
        assert_eq!(errors[0].span(), span(9..15));
    }
}
