//! Errors found while parsing a module's directives.

use crate::diagnostic::{Diagnostic, Span};

/// A directive-level problem in one module, with where it happened.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseError {
    /// `#foo` where no directive `foo` exists.
    #[error("unknown directive `#{name}`")]
    UnknownDirective {
        /// The directive name as written.
        name: String,
        /// Where.
        span: Span,
    },
    /// A directive whose arguments are malformed.
    #[error("malformed `#{directive}`: {message}")]
    Malformed {
        /// The directive.
        directive: &'static str,
        /// What is wrong.
        message: String,
        /// Where.
        span: Span,
    },
    /// A malformed `#if` / `#elif` expression.
    #[error("malformed expression: {message}")]
    Expression {
        /// What is wrong.
        message: String,
        /// Where.
        span: Span,
    },
    /// `#elif`, `#else` or `#endif` with no open `#if`.
    #[error("`#{directive}` without a matching `#{}`", opener(directive))]
    Unmatched {
        /// The directive.
        directive: &'static str,
        /// Where.
        span: Span,
    },
    /// `#elif` or `#else` after the `#else` of the same `#if`.
    #[error("`#{directive}` after `#else`")]
    AfterElse {
        /// The directive.
        directive: &'static str,
        /// Where.
        span: Span,
        /// The earlier `#else`.
        else_span: Span,
    },
    /// An `#if` that is never closed.
    #[error("unterminated `#{directive}`: no matching `#{}`", closer(directive))]
    Unterminated {
        /// The opening directive.
        directive: &'static str,
        /// Where it opened.
        span: Span,
    },
    /// A directive in a place where it has no meaning.
    #[error("`#{directive}` {message}")]
    Misplaced {
        /// The directive.
        directive: &'static str,
        /// Why it is not allowed here.
        message: &'static str,
        /// Where.
        span: Span,
    },
    /// A WESL module that does not parse as WESL (reported by `wgsl-parse`).
    #[error("WESL syntax error: {message}")]
    Syntax {
        /// What is wrong.
        message: String,
        /// Where.
        span: Span,
    },
    /// A malformed WESL `@if` / `@elif` / `@else` attribute.
    #[error("malformed `@{attribute}`: {message}")]
    Attribute {
        /// `if`, `elif` or `else`.
        attribute: &'static str,
        /// What is wrong.
        message: String,
        /// Where.
        span: Span,
    },
    /// `#if` nesting or expression nesting beyond the configured limit.
    #[error("{what} nested deeper than the limit of {limit}")]
    TooDeep {
        /// What is nested.
        what: &'static str,
        /// The limit.
        limit: usize,
        /// Where the limit was passed.
        span: Span,
    },
}

impl ParseError {
    /// The primary location.
    pub fn span(&self) -> Span {
        match self {
            ParseError::UnknownDirective { span, .. }
            | ParseError::Malformed { span, .. }
            | ParseError::Expression { span, .. }
            | ParseError::Unmatched { span, .. }
            | ParseError::AfterElse { span, .. }
            | ParseError::Unterminated { span, .. }
            | ParseError::Misplaced { span, .. }
            | ParseError::TooDeep { span, .. }
            | ParseError::Syntax { span, .. }
            | ParseError::Attribute { span, .. } => *span,
        }
    }

    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        let label = match self {
            ParseError::UnknownDirective { .. } => "not a directive".to_string(),
            ParseError::Unterminated { .. } => "opened here".to_string(),
            _ => "here".to_string(),
        };
        let mut d = Diagnostic::new(self.to_string()).at(self.span(), label);
        match self {
            ParseError::AfterElse { else_span, .. } => d = d.also(*else_span, "the `#else`"),
            ParseError::UnknownDirective { .. } => {
                d = d.note("directives: #import #define #undef #if #ifdef #ifndef #elif #else #endif #shader #pass #endpass #tag #pragma")
            }
            _ => {}
        }
        d
    }
}

/// The directive that opens the block `directive` closes or continues.
fn opener(directive: &str) -> &'static str {
    if directive == "endpass" { "pass" } else { "if" }
}

/// The directive that closes the block `directive` opens.
fn closer(directive: &str) -> &'static str {
    if directive == "pass" {
        "endpass"
    } else {
        "endif"
    }
}
