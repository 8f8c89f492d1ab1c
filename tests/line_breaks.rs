//! WGSL line breaks (LF, VT, FF, CR, CR LF, NEL, LS, PS) and blankspace, everywhere the
//! preprocessor splits text: named cases from the issue, then a deterministic corpus of
//! generated modules where naga must give the lean text, the emitted text and an independent
//! expectation the same outcome.

use wgsl_variants_fuzz_checks as checks;

use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Library, Variant};

/// Every WGSL line break, CR LF included.
const BREAKS: [&str; 8] = [
    "\n", "\r", "\r\n", "\u{b}", "\u{c}", "\u{85}", "\u{2028}", "\u{2029}",
];

/// The breaks that are not LF: the ones the old scanner missed.
const ODD_BREAKS: [&str; 7] = [
    "\r", "\r\n", "\u{b}", "\u{c}", "\u{85}", "\u{2028}", "\u{2029}",
];

const MAIN: &str = "#shader s\n#pass P\n#pragma multi_compile _ A\n#import m\n#endpass\n";

fn library(module: &str) -> Library {
    Library::from_sources([("main.wgsl", MAIN), ("m.wgsl", module)]).expect("library loads")
}

fn variant<'l>(lib: &'l Library, keywords: &[&str]) -> Variant<'l> {
    lib.variant("s", "P", keywords).expect("variant")
}

/// What `validate` says of one variant: `None` if valid, else the first error's location.
fn validate(lib: &Library, v: &Variant<'_>) -> Option<String> {
    let report = validate_pass(lib, v.pass, std::slice::from_ref(&v.choice), &|_| {});
    assert_eq!(report.built, 1);
    report.failures.first().map(|f| {
        f.error
            .location(lib.files())
            .map_or_else(String::new, |l| l.to_string())
    })
}

/// validate, naga on the emitted text (`naga_module`) and naga on the lean text agree; returns
/// the error location if they reject the variant.
fn agree(lib: &Library, v: &Variant<'_>) -> Option<String> {
    let by_validate = validate(lib, v);
    let by_naga = lib
        .naga_module(v)
        .err()
        .map(|e| e.location(lib.files()).unwrap().to_string());
    assert_eq!(by_validate, by_naga, "validate and naga_module disagree");
    let (full, lean) = (lib.compose(v).text, lib.wgsl(v));
    assert!(
        checks::same_outcome(&checks::naga_outcome(&full), &checks::naga_outcome(&lean)),
        "lean and emitted texts differ\nemitted: {full:?}\nlean: {lean:?}"
    );
    by_naga
}

#[test]
fn old_mac_line_endings_are_validated_like_naga() {
    let m = "// header\rfn f() -> f32 {\r    return vec2f(1.0);\r}\r";
    let lib = library(m);
    let v = variant(&lib, &[]);
    assert_eq!(lib.wgsl(&v), "fn f() -> f32 {\n    return vec2f(1.0);\n}\n");
    assert_eq!(
        lib.compose(&v).text,
        "// header\nfn f() -> f32 {\n    return vec2f(1.0);\n}\n"
    );
    assert_eq!(agree(&lib, &v).as_deref(), Some("m.wgsl:3:12"));
}

#[test]
fn code_after_a_line_comment_and_any_break_is_kept() {
    for brk in ODD_BREAKS {
        let ok = library(&format!("// note{brk}fn f() -> f32 {{ return 1.0; }}{brk}"));
        let v = variant(&ok, &[]);
        assert!(ok.wgsl(&v).contains("fn f()"), "{brk:?}");
        assert_eq!(agree(&ok, &v), None, "{brk:?}");

        let line = "fn f() -> f32 { return vec2f(1.0); }";
        let bad = library(&format!("// note{brk}{line}{brk}"));
        let v = variant(&bad, &[]);
        assert!(bad.wgsl(&v).contains("fn f()"), "{brk:?}");
        let col = line.find("vec2f").unwrap() + 1;
        assert_eq!(agree(&bad, &v), Some(format!("m.wgsl:2:{col}")), "{brk:?}");
    }
}

#[test]
fn a_block_comment_after_any_break_hides_an_if_0() {
    for brk in ODD_BREAKS {
        let m = format!("// note{brk}/*\n#if 0\n*/\nfn f() -> f32 {{ return 1.0; }}\n");
        let lib = library(&m);
        let v = variant(&lib, &[]);
        assert!(lib.wgsl(&v).contains("#if 0"), "{brk:?}");
        assert!(lib.wgsl(&v).contains("fn f()"), "{brk:?}");
        assert_eq!(agree(&lib, &v), None, "{brk:?}");
    }
}

#[test]
fn a_commented_out_define_is_neither_applied_nor_removed() {
    for brk in ODD_BREAKS {
        let m = format!(
            "// note{brk}/*\n#define X\n*/\n#ifdef X\nfn f() -> f32 {{ return vec2f(1.0); }}\n#endif\n"
        );
        let lib = library(&m);
        let v = variant(&lib, &[]);
        let full = lib.compose(&v).text;
        assert!(full.contains("#define X"), "{brk:?}");
        assert!(!full.contains("fn f()"), "{brk:?}");
        assert_eq!(agree(&lib, &v), None, "{brk:?}");
    }
}

#[test]
fn only_wgsl_blankspace_is_blank() {
    // NBSP and the ideographic space are Unicode white space but not WGSL blankspace.
    for space in ["\u{a0}", "\u{3000}", "\u{2003}"] {
        let lib = library(&format!("{space}\nfn f() -> f32 {{ return 1.0; }}\n"));
        let v = variant(&lib, &[]);
        assert!(lib.wgsl(&v).contains(space), "{space:?}");
        assert_eq!(agree(&lib, &v).as_deref(), Some("m.wgsl:1:1"), "{space:?}");
    }
    // The directional marks are WGSL blankspace though not Unicode white space.
    let lib = library("\u{200e}\u{200f}\t\n// \u{200e}\nfn f() -> f32 { return 1.0; }\n");
    let v = variant(&lib, &[]);
    assert_eq!(lib.wgsl(&v), "fn f() -> f32 { return 1.0; }\n");
    assert_eq!(agree(&lib, &v), None);
}

#[test]
fn a_shader_file_holds_only_blankspace_and_comments_outside_passes() {
    // LRM and a comment ended by LS are fine between passes; NBSP is code, so it is refused.
    let ok = "#shader s\u{2028}\u{200e}\n// x\u{2028}#pass P\n#endpass\n";
    assert!(Library::from_sources([("main.wgsl", ok)]).is_ok());
    let bad = "#shader s\n\u{a0}\n#pass P\n#endpass\n";
    let err = Library::from_sources([("main.wgsl", bad)]).unwrap_err();
    let at: Vec<String> = err
        .diagnostics()
        .iter()
        .filter_map(|d| d.location(&err.files))
        .map(|l| l.to_string())
        .collect();
    assert_eq!(at, ["main.wgsl:2:1"]);
}

#[test]
fn diagnostics_count_every_wgsl_break() {
    let mut m = String::new();
    for (i, brk) in BREAKS.iter().enumerate() {
        m.push_str(&format!("const c{i} = {i};{brk}"));
    }
    let line = "fn f() -> f32 { return vec2f(1.0); }";
    m.push_str(line);
    m.push('\u{2028}');
    let lib = library(&m);
    let v = variant(&lib, &[]);
    let col = line.find("vec2f").unwrap() + 1;
    let at = format!("m.wgsl:{}:{col}", BREAKS.len() + 1);
    assert_eq!(agree(&lib, &v), Some(at.clone()));
    let rendered = lib
        .naga_module(&v)
        .unwrap_err()
        .diagnostic()
        .render(lib.files(), false);
    assert!(rendered.contains(&at), "{rendered}");
    assert!(rendered.contains(line), "{rendered}");
    assert!(!rendered.contains('\u{2028}'), "{rendered}");

    // A directive error counts the same lines.
    let bad = format!("{m}#bogus\n");
    let err = Library::from_sources([("main.wgsl", MAIN), ("m.wgsl", bad.as_str())]).unwrap_err();
    let locations: Vec<String> = err
        .diagnostics()
        .iter()
        .filter_map(|d| d.location(&err.files))
        .map(|l| l.to_string())
        .collect();
    assert_eq!(locations, [format!("m.wgsl:{}:1", BREAKS.len() + 2)]);
}

#[test]
fn crlf_is_one_break_and_offsets_stay_those_of_the_file() {
    let m = "const a = 1;\r\n\r\nfn f() -> f32 { return vec2f(1.0); }\r\n";
    let lib = library(m);
    let v = variant(&lib, &[]);
    let err = lib.naga_module(&v).unwrap_err();
    assert_eq!(
        err.location(lib.files()).unwrap().to_string(),
        "m.wgsl:3:24"
    );
    let span = err.labels[0].0;
    assert!(lib.files().text(span.file)[span.range()].starts_with("vec2f"));
    assert_eq!(lib.compose(&v).text.matches('\n').count(), 3);
}

#[test]
fn an_error_at_the_end_points_after_the_last_code_whatever_the_break() {
    for brk in ["", "\n", "\r\n", "\u{2028}", "\n#if A\n#endif\n"] {
        let lib = library(&format!("fn f() -> f32 {{{brk}"));
        let v = variant(&lib, &[]);
        assert_eq!(agree(&lib, &v).as_deref(), Some("m.wgsl:1:16"), "{brk:?}");
        let rendered = lib
            .naga_module(&v)
            .unwrap_err()
            .diagnostic()
            .render(lib.files(), false);
        // One caret on line 1, not a label running into the next line.
        assert!(!rendered.contains("2 │"), "{brk:?}\n{rendered}");
    }
}

// ---- Generated corpus -----------------------------------------------------------------------

/// SplitMix64: small, seeded, and the same on every platform.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }

    fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }
}

/// The keyword state the generator tracks itself, to know which lines a variant keeps.
#[derive(Clone, Copy)]
struct Env {
    a: bool,
    b: bool,
    c: bool,
}

type Cond = fn(&Env) -> bool;

/// `#if`-family directives and what they mean, written out by hand (not parsed).
const CONDS: [(&str, Cond); 6] = [
    ("if A", |e| e.a),
    ("ifdef B", |e| e.b),
    ("ifndef A", |e| !e.a),
    ("if A && !B", |e| e.a && !e.b),
    ("if defined(C) || B", |e| e.c || e.b),
    ("if C", |e| e.c),
];

enum Kind {
    Text,
    If(Cond),
    Else,
    Endif,
    Define,
    Undef,
}

struct GenLine {
    text: String,
    kind: Kind,
}

/// WGSL blankspace that is not a line break.
const BLANKS: [&str; 6] = ["", " ", "\t", "    ", "\u{200e}", "\u{200f}"];

/// Comment contents: directive look-alikes, comment tokens, NBSP, never a line break.
const JUNK: [&str; 14] = [
    "#if 0",
    "#define C",
    "#endif",
    "/*",
    "*/",
    "//",
    "# x",
    "fn g(",
    "note",
    "/*/",
    "*/*",
    "\u{a0}",
    "**",
    "#else",
];

/// Junk that keeps a block comment's nesting (no `/*` or `*/` inside).
const INNER_JUNK: [&str; 10] = [
    "#if 0",
    "#define C",
    "#endif",
    "// x",
    "# y",
    "fn g(",
    "note",
    "\u{a0}",
    "*",
    "/",
];

struct Gen {
    rng: Rng,
    lines: Vec<GenLine>,
    id: usize,
}

impl Gen {
    fn junk(&mut self, pieces: &[&str]) -> String {
        let n = self.rng.below(4);
        (0..n)
            .map(|_| self.rng.pick(pieces))
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn blank(&mut self) -> &'static str {
        self.rng.pick(&BLANKS)
    }

    fn text(&mut self, text: String) {
        let (pre, post) = (self.blank(), self.blank());
        self.lines.push(GenLine {
            text: format!("{pre}{text}{post}"),
            kind: Kind::Text,
        });
    }

    fn directive(&mut self, body: &str, kind: Kind) {
        let pre = self.blank();
        let comment = if self.rng.one_in(3) {
            format!(" // {}", self.junk(&JUNK))
        } else {
            String::new()
        };
        self.lines.push(GenLine {
            text: format!("{pre}#{body}{comment}"),
            kind,
        });
    }

    fn name(&mut self, prefix: &str) -> String {
        self.id += 1;
        format!("{prefix}{}", self.id)
    }

    fn block_comment(&mut self) {
        let lead = if self.rng.one_in(2) {
            format!("const {} = 1; ", self.name("k"))
        } else {
            String::new()
        };
        let junk = self.junk(&INNER_JUNK);
        self.text(format!("{lead}/* {junk}"));
        let mut open = 1;
        for _ in 0..self.rng.below(5) {
            let junk = self.junk(&INNER_JUNK);
            match self.rng.below(5) {
                0 => {
                    open += 1;
                    self.text(format!("{junk} /* nested"));
                }
                1 if open > 1 => {
                    open -= 1;
                    self.text(format!("nested */ {junk}"));
                }
                2 => self.text(format!("/* {junk} */ {junk}")),
                3 => self.text(String::new()),
                _ => self.text(junk),
            }
        }
        let tail = if self.rng.one_in(2) {
            format!(" const {} = 2;", self.name("k"))
        } else {
            String::new()
        };
        self.text(format!("{}{tail}", " */".repeat(open)));
    }

    fn item(&mut self, depth: usize) {
        match self.rng.below(12) {
            0 | 1 => {
                let f = self.name("f");
                if self.rng.one_in(2) {
                    self.text(format!("fn {f}() -> f32 {{ return 1.0; }}"));
                } else {
                    self.text(format!("fn {f}() -> f32 {{"));
                    let junk = self.junk(&JUNK);
                    self.text(format!("// {junk}"));
                    self.text("return 2.0;".into());
                    self.text("}".into());
                }
            }
            2 => {
                let k = self.name("k");
                let comment = if self.rng.one_in(2) {
                    format!(" // {}", self.junk(&JUNK))
                } else {
                    String::new()
                };
                self.text(format!("const {k} = 1;{comment}"));
            }
            3 | 4 => {
                let junk = self.junk(&JUNK);
                self.text(format!("//{junk}"));
            }
            5 => self.block_comment(),
            6 => self.text(String::new()),
            7 if depth < 3 => {
                let (body, cond) = self.rng.pick(&CONDS);
                self.directive(body, Kind::If(cond));
                for _ in 0..self.rng.below(4) {
                    self.item(depth + 1);
                }
                if self.rng.one_in(2) {
                    self.directive("else", Kind::Else);
                    for _ in 0..self.rng.below(4) {
                        self.item(depth + 1);
                    }
                }
                self.directive("endif", Kind::Endif);
            }
            8 => {
                if self.rng.one_in(2) {
                    self.directive("define C", Kind::Define);
                } else {
                    self.directive("undef C", Kind::Undef);
                }
            }
            9 => {
                let k = self.name("k");
                self.text(format!("/* # {k} */ const {k} = 3; /* # */"));
            }
            10 if self.rng.one_in(3) => {
                // Rejected by naga: a wrong return type, or a non-blank space.
                if self.rng.one_in(2) {
                    let f = self.name("bad");
                    self.text(format!("fn {f}() -> f32 {{ return vec2f(1.0); }}"));
                } else {
                    self.text("\u{a0}".into());
                }
            }
            _ => {
                let k = self.name("k");
                self.text(format!("const {k}: i32 = 4;"));
            }
        }
    }
}

/// A generated module: its lines and the break after each (the last may have none).
struct Module {
    lines: Vec<GenLine>,
    breaks: Vec<&'static str>,
}

impl Module {
    fn generate(rng: Rng) -> Module {
        let mut g = Gen {
            rng,
            lines: Vec::new(),
            id: 0,
        };
        for _ in 0..1 + g.rng.below(8) {
            g.item(0);
        }
        let odd = g.rng.pick(&ODD_BREAKS);
        let breaks = (0..g.lines.len())
            .map(|i| {
                if i + 1 == g.lines.len() && g.rng.one_in(3) {
                    ""
                } else if g.rng.one_in(2) {
                    // Often one odd break throughout, as a file saved by one editor has.
                    odd
                } else {
                    g.rng.pick(&BREAKS)
                }
            })
            .collect();
        Module {
            lines: g.lines,
            breaks,
        }
    }

    fn text(&self) -> String {
        self.lines
            .iter()
            .zip(&self.breaks)
            .map(|(l, b)| format!("{}{b}", l.text))
            .collect()
    }

    /// The program a variant must be, from the generator's own bookkeeping: the text lines of
    /// the branches taken, with their original breaks.
    fn expected(&self, a: bool, b: bool) -> String {
        let mut env = Env { a, b, c: false };
        // (parent active, this branch active, some branch taken)
        let mut stack: Vec<(bool, bool, bool)> = Vec::new();
        let mut out = String::new();
        for (line, brk) in self.lines.iter().zip(&self.breaks) {
            let active = stack.last().is_none_or(|f| f.1);
            match line.kind {
                Kind::Text if active => {
                    out.push_str(&line.text);
                    out.push_str(if brk.is_empty() { "\n" } else { brk });
                }
                Kind::Text => {}
                Kind::If(cond) => {
                    let taken = active && cond(&env);
                    stack.push((active, taken, taken));
                }
                Kind::Else => {
                    let f = stack.last_mut().expect("generated #else inside #if");
                    f.1 = f.0 && !f.2;
                    f.2 = true;
                }
                Kind::Endif => {
                    stack.pop();
                }
                Kind::Define => env.c |= active,
                Kind::Undef => env.c &= !active,
            }
        }
        out
    }
}

#[test]
fn generated_modules_lean_emitted_and_expected_agree_in_naga() {
    const CASES: u64 = 800;
    let (mut variants, mut accepted, mut rejected) = (0usize, 0usize, 0usize);
    for case in 0..CASES {
        let mut rng = Rng(0x5eed_0000 + case);
        let module = Module::generate(Rng(rng.next()));
        let text = module.text();
        let main: String = [
            "#shader s",
            "#pass P",
            "#pragma multi_compile _ A",
            "#pragma shader_feature _ B",
            "#import m",
            "#endpass",
        ]
        .iter()
        .map(|l| format!("{l}{}", rng.pick(&BREAKS)))
        .collect();
        let lib = Library::from_sources([("main.wgsl", main.as_str()), ("m.wgsl", text.as_str())])
            .unwrap_or_else(|e| {
                panic!(
                    "case {case}: generated module does not load: {:?}\n{text:?}",
                    e.diagnostics()
                        .iter()
                        .map(|d| d.render(&e.files, false))
                        .collect::<Vec<_>>()
                )
            });
        // Same outcome for lean and emitted texts, and `validate` agrees with naga.
        variants += checks::lean_matches_emitted(&lib);
        for (a, b) in [(false, false), (true, false), (false, true), (true, true)] {
            let keywords: Vec<&str> = [("A", a), ("B", b)]
                .iter()
                .filter(|k| k.1)
                .map(|k| k.0)
                .collect();
            let v = variant(&lib, &keywords);
            let expected = module.expected(a, b);
            let outcome = checks::naga_outcome(&lib.compose(&v).text);
            assert!(
                checks::same_outcome(&outcome, &checks::naga_outcome(&expected)),
                "case {case} {keywords:?}: emitted text is not the expected program\nmodule: {text:?}\nexpected: {expected:?}\nemitted: {:?}",
                lib.compose(&v).text
            );
            if outcome.is_ok() {
                accepted += 1;
            } else {
                rejected += 1;
            }
        }
    }
    println!(
        "{CASES} generated modules, {variants} variants: {accepted} accepted, {rejected} rejected by naga"
    );
    assert_eq!(variants, 4 * CASES as usize);
    // Both outcomes are well represented, so neither side of the comparison is vacuous.
    assert!(accepted > variants / 4 && rejected > variants / 20);
}
