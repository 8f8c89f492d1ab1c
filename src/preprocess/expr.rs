//! `#if` / `#elif` expressions: parsing and evaluation.
//!
//! Grammar (C precedence, lowest first): `||`, `&&`, `== !=`, `< <= > >=`, unary `! -`,
//! then atoms: integer literals (decimal or `0x` hex), names, `defined(NAME)` / `defined NAME`,
//! and parentheses. A name's value is its define's value; an undefined name is 0; a keyword
//! that is on is 1. Comparisons and logic yield 0 or 1.

use crate::diagnostic::{FileId, Span};

use super::error::ParseError;

/// A parsed expression.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Expr {
    /// An integer literal.
    Int(i64),
    /// A name: its value, or 0 when undefined.
    Name(Box<str>),
    /// `defined(NAME)`.
    Defined(Box<str>),
    /// `!e`.
    Not(Box<Expr>),
    /// `-e`.
    Neg(Box<Expr>),
    /// A binary operation.
    Binary(BinOp, Box<Expr>, Box<Expr>),
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BinOp {
    /// `||`
    Or,
    /// `&&`
    And,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl BinOp {
    /// The value of `a op b`: 0 or 1. The one definition of the operators, for every
    /// evaluator of expressions (composition, the audit's static walk, the naga_oil export).
    pub fn apply(self, a: i64, b: i64) -> i64 {
        (match self {
            BinOp::Or => a != 0 || b != 0,
            BinOp::And => a != 0 && b != 0,
            BinOp::Eq => a == b,
            BinOp::Ne => a != b,
            BinOp::Lt => a < b,
            BinOp::Le => a <= b,
            BinOp::Gt => a > b,
            BinOp::Ge => a >= b,
        }) as i64
    }

    /// The operator as written: `||`, `&&`, `==`, `!=`, `<`, `<=`, `>`, `>=`.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Or => "||",
            BinOp::And => "&&",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
        }
    }
}

impl Expr {
    /// Evaluates with `value(name)` giving each defined name's value.
    pub fn eval(&self, value: &dyn Fn(&str) -> Option<i64>) -> i64 {
        match self {
            Expr::Int(v) => *v,
            Expr::Name(n) => value(n).unwrap_or(0),
            Expr::Defined(n) => value(n).is_some() as i64,
            Expr::Not(e) => Expr::logical_not(e.eval(value)),
            Expr::Neg(e) => Expr::negate(e.eval(value)),
            Expr::Binary(op, a, b) => {
                let a = a.eval(value);
                // `||` and `&&` short-circuit: a decided left operand leaves `b` unread.
                match (op, a != 0) {
                    (BinOp::Or, true) => 1,
                    (BinOp::And, false) => 0,
                    _ => op.apply(a, b.eval(value)),
                }
            }
        }
    }

    /// The value of `!v`: 1 when `v` is 0, else 0.
    pub fn logical_not(v: i64) -> i64 {
        (v == 0) as i64
    }

    /// The value of `-v` (wrapping: `-i64::MIN` is `i64::MIN`).
    pub fn negate(v: i64) -> i64 {
        v.wrapping_neg()
    }

    /// Calls `f` on every name the expression reads (names and `defined` operands).
    pub fn visit_names(&self, f: &mut dyn FnMut(&str)) {
        match self {
            Expr::Int(_) => {}
            Expr::Name(n) | Expr::Defined(n) => f(n),
            Expr::Not(e) | Expr::Neg(e) => e.visit_names(f),
            Expr::Binary(_, a, b) => {
                a.visit_names(f);
                b.visit_names(f);
            }
        }
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum Tok {
    Int(i64),
    Ident(Box<str>),
    Op(&'static str),
}

/// Parses `text`, which starts at byte `offset` of `file`. `max_depth` bounds nesting.
pub(crate) fn parse(
    text: &str,
    offset: usize,
    file: FileId,
    max_depth: usize,
) -> Result<Expr, ParseError> {
    let toks = tokenize(text, offset, file)?;
    let end = offset + text.len();
    let mut p = Parser {
        toks,
        pos: 0,
        file,
        end,
        max_depth,
        depth: 0,
    };
    if p.toks.is_empty() {
        return Err(p.error(
            "expected an expression",
            Span::new(file, offset..end.max(offset + 1)),
        ));
    }
    let e = p.or()?;
    if let Some((tok, span)) = p.toks.get(p.pos) {
        return Err(p.error(
            &format!("unexpected {} after the expression", describe(tok)),
            *span,
        ));
    }
    Ok(e)
}

fn describe(tok: &Tok) -> String {
    match tok {
        Tok::Int(v) => format!("`{v}`"),
        Tok::Ident(n) => format!("`{n}`"),
        Tok::Op(o) => format!("`{o}`"),
    }
}

const OPS: [&str; 14] = [
    "||", "&&", "==", "!=", "<=", ">=", "<", ">", "!", "(", ")", "-", "+", "=",
];

fn tokenize(text: &str, offset: usize, file: FileId) -> Result<Vec<(Tok, Span)>, ParseError> {
    let mut toks = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let span = |end: usize| Span::new(file, offset + start..offset + end);
        if c.is_ascii_digit() {
            // Take `.` too, so `1.5` is reported as one literal that is not an integer.
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_' || bytes[i] == b'.')
            {
                i += 1;
            }
            let lit = &text[start..i];
            let value = parse_int(lit).ok_or_else(|| ParseError::Expression {
                message: format!(
                    "`{lit}` is not an integer literal (decimal or 0x hex, fitting in 64 bits)"
                ),
                span: span(i),
            })?;
            toks.push((Tok::Int(value), span(i)));
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            toks.push((Tok::Ident(text[start..i].into()), span(i)));
        } else if let Some(op) = OPS.iter().find(|op| text[i..].starts_with(**op)) {
            if *op == "=" || *op == "+" {
                return Err(ParseError::Expression {
                    message: format!("`{op}` is not an operator here (comparisons use `==`)"),
                    span: span(i + 1),
                });
            }
            i += op.len();
            toks.push((Tok::Op(op), span(i)));
        } else {
            let ch = text[i..].chars().next().unwrap_or('?');
            return Err(ParseError::Expression {
                message: format!("unexpected character `{ch}`"),
                span: span(i + ch.len_utf8()),
            });
        }
    }
    Ok(toks)
}

/// Parses a decimal or `0x` hexadecimal integer literal.
pub(crate) fn parse_int(lit: &str) -> Option<i64> {
    if let Some(hex) = lit.strip_prefix("0x").or_else(|| lit.strip_prefix("0X")) {
        i64::from_str_radix(hex, 16).ok()
    } else {
        lit.parse().ok()
    }
}

struct Parser {
    toks: Vec<(Tok, Span)>,
    pos: usize,
    file: FileId,
    end: usize,
    max_depth: usize,
    depth: usize,
}

impl Parser {
    fn error(&self, message: &str, span: Span) -> ParseError {
        ParseError::Expression {
            message: message.to_string(),
            span,
        }
    }

    fn peek_op(&self) -> Option<&'static str> {
        match self.toks.get(self.pos) {
            Some((Tok::Op(o), _)) => Some(o),
            _ => None,
        }
    }

    fn eof_span(&self) -> Span {
        Span::new(self.file, self.end..self.end + 1)
    }

    fn binary(
        &mut self,
        ops: &[(&str, BinOp)],
        next: fn(&mut Parser) -> Result<Expr, ParseError>,
    ) -> Result<Expr, ParseError> {
        let mut lhs = next(self)?;
        let depth = self.depth;
        while let Some(op) = self
            .peek_op()
            .and_then(|o| ops.iter().find(|(s, _)| *s == o))
        {
            // A chain `a || b || c …` is a left-deep tree: each operator counts as a level.
            let span = self.toks[self.pos].1;
            self.enter(span)?;
            self.pos += 1;
            let rhs = next(self)?;
            lhs = Expr::Binary(op.1, Box::new(lhs), Box::new(rhs));
        }
        self.depth = depth;
        Ok(lhs)
    }

    fn or(&mut self) -> Result<Expr, ParseError> {
        self.binary(&[("||", BinOp::Or)], Parser::and)
    }

    fn and(&mut self) -> Result<Expr, ParseError> {
        self.binary(&[("&&", BinOp::And)], Parser::equality)
    }

    fn equality(&mut self) -> Result<Expr, ParseError> {
        self.binary(&[("==", BinOp::Eq), ("!=", BinOp::Ne)], Parser::relational)
    }

    fn relational(&mut self) -> Result<Expr, ParseError> {
        let ops = [
            ("<", BinOp::Lt),
            ("<=", BinOp::Le),
            (">", BinOp::Gt),
            (">=", BinOp::Ge),
        ];
        self.binary(&ops, Parser::unary)
    }

    fn enter(&mut self, span: Span) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > self.max_depth {
            return Err(ParseError::TooDeep {
                what: "expression (parentheses, unary and binary operators)",
                limit: self.max_depth,
                span,
            });
        }
        Ok(())
    }

    fn unary(&mut self) -> Result<Expr, ParseError> {
        let Some((tok, span)) = self.toks.get(self.pos).cloned() else {
            return Err(self.error(
                "expected a value, found the end of the line",
                self.eof_span(),
            ));
        };
        match tok {
            Tok::Op(op @ ("!" | "-")) => {
                self.pos += 1;
                self.enter(span)?;
                let inner = self.unary()?;
                self.depth -= 1;
                Ok(if op == "!" {
                    Expr::Not(Box::new(inner))
                } else {
                    Expr::Neg(Box::new(inner))
                })
            }
            Tok::Op("(") => {
                self.pos += 1;
                self.enter(span)?;
                let inner = self.or()?;
                self.depth -= 1;
                self.expect_close(span)?;
                Ok(inner)
            }
            Tok::Int(v) => {
                self.pos += 1;
                Ok(Expr::Int(v))
            }
            Tok::Ident(name) if &*name == "defined" => {
                self.pos += 1;
                let paren = self.peek_op() == Some("(");
                if paren {
                    self.pos += 1;
                }
                let name = match self.toks.get(self.pos) {
                    Some((Tok::Ident(n), _)) => n.clone(),
                    Some((t, s)) => {
                        return Err(self.error(
                            &format!("`defined` needs a name, found {}", describe(t)),
                            *s,
                        ));
                    }
                    None => return Err(self.error("`defined` needs a name", self.eof_span())),
                };
                self.pos += 1;
                if paren {
                    self.expect_close(span)?;
                }
                Ok(Expr::Defined(name))
            }
            Tok::Ident(name) => {
                self.pos += 1;
                Ok(Expr::Name(name))
            }
            Tok::Op(op) => Err(self.error(&format!("expected a value, found `{op}`"), span)),
        }
    }

    fn expect_close(&mut self, open: Span) -> Result<(), ParseError> {
        if self.peek_op() == Some(")") {
            self.pos += 1;
            Ok(())
        } else {
            let span = self.toks.get(self.pos).map_or(self.eof_span(), |t| t.1);
            let _ = open;
            Err(self.error("expected `)`", span))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eval_names() {
        let e = parse("defined(DEFERRED_PASS) && UNITY_HDR_ON", 0, 0, 64).unwrap();
        let on = |n: &str| (n == "DEFERRED_PASS" || n == "UNITY_HDR_ON").then_some(1);
        assert_eq!(e.eval(&on), 1);
        assert_eq!(e.eval(&|_: &str| None), 0);
    }

    #[test]
    fn apply_is_0_or_1() {
        assert_eq!(BinOp::Le.apply(2, 3), 1);
        assert_eq!(BinOp::Or.apply(0, -1), 1);
        assert_eq!(BinOp::And.apply(2, 0), 0);
    }

    fn eval(text: &str, defs: &[(&str, i64)]) -> i64 {
        let e = parse(text, 0, 0, 64).unwrap_or_else(|err| panic!("{text}: {err}"));
        e.eval(&|n: &str| defs.iter().find(|d| d.0 == n).map(|d| d.1))
    }

    fn err(text: &str) -> (String, std::ops::Range<usize>) {
        let e = parse(text, 10, 0, 8).unwrap_err();
        (e.to_string(), e.span().range())
    }

    #[test]
    fn precedence_matches_c() {
        assert_eq!(eval("1 || 0 && 0", &[]), 1);
        assert_eq!(eval("(1 || 0) && 0", &[]), 0);
        assert_eq!(eval("1 < 2 == 1", &[]), 1);
        assert_eq!(eval("!0 && !!5", &[]), 1);
        assert_eq!(eval("-1 < 0", &[]), 1);
    }

    #[test]
    fn names_and_defined() {
        assert_eq!(eval("X", &[]), 0);
        assert_eq!(eval("X", &[("X", 7)]), 7);
        assert_eq!(eval("defined(X)", &[("X", 0)]), 1);
        assert_eq!(eval("defined X && X == 0", &[("X", 0)]), 1);
        assert_eq!(
            eval("CASCADES >= 2 && CASCADES <= 4", &[("CASCADES", 4)]),
            1
        );
        assert_eq!(eval("0x10 == 16", &[]), 1);
    }

    #[test]
    fn errors_point_at_the_token() {
        assert_eq!(
            err("A &&"),
            (
                "malformed expression: expected a value, found the end of the line".into(),
                14..15
            )
        );
        assert_eq!(err("A = 1").1, 12..13);
        assert_eq!(err("(A").0, "malformed expression: expected `)`");
        assert_eq!(err("A B").1, 12..13);
        assert_eq!(err("1.5").1, 10..13);
        assert_eq!(err("").0, "malformed expression: expected an expression");
        assert_eq!(err("A $").1, 12..13);
    }

    #[test]
    fn depth_is_bounded() {
        let deep = "(".repeat(100) + "1" + &")".repeat(100);
        assert!(matches!(
            parse(&deep, 0, 0, 64),
            Err(ParseError::TooDeep { .. })
        ));
        let nots = "!".repeat(100_000) + "1";
        assert!(matches!(
            parse(&nots, 0, 0, 64),
            Err(ParseError::TooDeep { .. })
        ));
        let chain = vec!["A"; 100_000].join(" || ");
        assert!(matches!(
            parse(&chain, 0, 0, 64),
            Err(ParseError::TooDeep { .. })
        ));
        let ok = vec!["A"; 60].join(" && ");
        assert_eq!(parse(&ok, 0, 0, 64).unwrap().eval(&|_: &str| Some(1)), 1);
    }
}
