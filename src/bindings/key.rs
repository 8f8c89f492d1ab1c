//! The typed variant key of a pass: one field per keyword set (`bool` for `_ X`, an enum for
//! a set of options), the pass's `require`, `exclude` and `skip_variants` checked in one
//! `const` constructor, and the key's option per set, position and keywords without strings.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use crate::keywords::ConstraintKind;
use crate::shader::Pass;

/// How one keyword set appears in the generated key.
#[derive(Clone, Debug)]
pub(crate) enum Field {
    /// A one-option `multi_compile K`: always on, no field.
    Always,
    /// `_ X`: a `bool` that is `true` when X is on.
    Flag {
        /// The field's name.
        field: String,
        /// The option index of X.
        on: usize,
    },
    /// Any other set: an enum with one variant per option.
    Choice {
        /// The field's name.
        field: String,
        /// The enum's name (in the generated `keywords` module).
        name: String,
        /// One variant name per option, in option order.
        variants: Vec<String>,
    },
}

/// Words of a keyword: `_SHADOWS_DEPTH` → `["SHADOWS", "DEPTH"]`.
fn words(keyword: &str) -> Vec<&str> {
    keyword.split('_').filter(|w| !w.is_empty()).collect()
}

/// `["SHADOWS", "DEPTH"]` → `ShadowsDepth`; an identifier never starts with a digit.
fn camel_words(words: &[&str]) -> String {
    let mut out = String::new();
    for w in words {
        let mut chars = w.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.extend(chars.map(|c| c.to_ascii_lowercase()));
        }
    }
    if out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, 'K');
    }
    out
}

/// `["SHADOWS", "DEPTH"]` → `shadows_depth`.
fn snake_words(words: &[&str]) -> String {
    let out = words
        .iter()
        .map(|w| w.to_ascii_lowercase())
        .collect::<Vec<_>>()
        .join("_");
    if out.starts_with(|c: char| c.is_ascii_digit()) || out.is_empty() {
        format!("k_{out}")
    } else {
        super::names::field_name(&out)
    }
}

/// A combination's [`Key::index`](self) in the generated tables: its options in set order,
/// the last set fastest.
pub(crate) fn combination_index(pass: &Pass, choice: &crate::variants::Choice) -> usize {
    choice
        .0
        .iter()
        .zip(&pass.sets)
        .fold(0, |at, (&o, set)| at * set.len() + usize::from(o))
}

/// The field of each keyword set of `pass`, in set order, with unique names.
pub(crate) fn fields(pass: &Pass) -> Vec<Field> {
    let mut used_fields = BTreeSet::new();
    let mut used_enums = BTreeSet::new();
    let unique = |name: String, used: &mut BTreeSet<String>, set: usize, sep: &str| {
        let name = if used.contains(&name) {
            format!("{name}{sep}{set}")
        } else {
            name
        };
        used.insert(name.clone());
        name
    };
    let mut out = Vec::with_capacity(pass.sets.len());
    for (i, set) in pass.sets.iter().enumerate() {
        let named: Vec<&str> = set.keywords().collect();
        if set.options.len() == 1 {
            out.push(Field::Always);
        } else if set.options.len() == 2 && named.len() == 1 {
            let on = set.options.iter().position(Option::is_some).unwrap_or(0);
            let field = unique(snake_words(&words(named[0])), &mut used_fields, i, "_");
            out.push(Field::Flag { field, on });
        } else {
            // The words every keyword of the set starts with name the set: `SHADOWS_DEPTH`,
            // `SHADOWS_CUBE` → `Shadows`, with variants `Depth` and `Cube`.
            let split: Vec<Vec<&str>> = named.iter().map(|k| words(k)).collect();
            let mut prefix = split.first().cloned().unwrap_or_default();
            for w in &split[1..] {
                let common = prefix.iter().zip(w).take_while(|(a, b)| a == b).count();
                prefix.truncate(common);
            }
            let (name, field) = if prefix.is_empty() {
                (format!("Set{i}"), format!("set{i}"))
            } else {
                (camel_words(&prefix), snake_words(&prefix))
            };
            let name = unique(name, &mut used_enums, i, "");
            let field = unique(field, &mut used_fields, i, "_");
            let mut variants: Vec<String> = Vec::new();
            let mut next = 0;
            for option in &set.options {
                let mut variant = match option {
                    None => "Off".to_string(),
                    Some(_) => {
                        let w = &split[next];
                        next += 1;
                        // The option that is the shared words alone (`_MAIN_LIGHT_SHADOWS`
                        // beside `_MAIN_LIGHT_SHADOWS_CASCADE`) is the set's `On`.
                        if w.len() == prefix.len() {
                            "On".to_string()
                        } else {
                            camel_words(&w[prefix.len()..])
                        }
                    }
                };
                if variants.contains(&variant) {
                    variant = format!("{variant}{}", variants.len());
                }
                variants.push(variant);
            }
            out.push(Field::Choice {
                field,
                name,
                variants,
            });
        }
    }
    out
}

/// Appends a struct literal the way rustfmt writes it: on one line when its fields take at
/// most 18 columns (rustfmt's `struct_lit_width`), else one field per line.
pub(crate) fn struct_lit(
    code: &mut String,
    indent: usize,
    head: &str,
    path: &str,
    fields: &[(&str, String)],
    tail: &str,
) {
    let pad = " ".repeat(indent);
    let body: Vec<String> = fields.iter().map(|(f, v)| format!("{f}: {v}")).collect();
    let body = body.join(", ");
    if fields.is_empty() {
        let _ = writeln!(code, "{pad}{head}{path} {{}}{tail}");
    } else if body.len() <= 18
        && indent + head.len() + path.len() + body.len() + tail.len() + 6 <= 100
    {
        let _ = writeln!(code, "{pad}{head}{path} {{ {body} }}{tail}");
    } else {
        let _ = writeln!(code, "{pad}{head}{path} {{");
        for (f, v) in fields {
            let _ = writeln!(code, "{pad}    {f}: {v},");
        }
        let _ = writeln!(code, "{pad}}}{tail}");
    }
}

/// A Rust condition over `k: &Keywords`, kept in parts until it is laid out: a long
/// `matches!` breaks the way rustfmt breaks it.
enum Cond {
    /// Any other expression: `k.f`, `!k.f`, `true`, `!(A || B)`.
    Expr(String),
    /// `matches!(value, arms[0] | arms[1] | …)`, negated or not.
    Matches {
        /// Whether the condition is `!matches!(…)`.
        negated: bool,
        /// The matched value, `k.field`.
        value: String,
        /// The pattern's alternatives.
        arms: Vec<String>,
    },
}

impl std::fmt::Display for Cond {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cond::Expr(e) => f.write_str(e),
            Cond::Matches {
                negated,
                value,
                arms,
            } => {
                let not = if *negated { "!" } else { "" };
                write!(f, "{not}matches!({value}, {})", arms.join(" | "))
            }
        }
    }
}

/// Appends `if A && B {`, broken before `&&` the way rustfmt does past 100 columns.
fn if_both(code: &mut String, a: &Cond, b: &Cond) {
    let line = format!("        if {a} && {b} {{");
    if line.len() <= 100 {
        let _ = writeln!(code, "{line}");
    } else if line.len() - 2 <= 100 {
        // The condition fits on its line: rustfmt moves only the brace.
        let _ = writeln!(code, "        if {a} && {b}");
        let _ = writeln!(code, "        {{");
    } else {
        let _ = writeln!(code, "        if {a}");
        match b {
            // A `matches!` too long for its line: rustfmt puts each argument on a line of its
            // own, and a pattern still too long one arm per line.
            Cond::Matches {
                negated,
                value,
                arms,
            } if 15 + b.to_string().len() > 100 => {
                let not = if *negated { "!" } else { "" };
                let pattern = arms.join(" | ");
                let _ = writeln!(code, "            && {not}matches!(");
                let _ = writeln!(code, "                {value},");
                if 16 + pattern.len() <= 100 {
                    let _ = writeln!(code, "                {pattern}");
                } else {
                    for (i, arm) in arms.iter().enumerate() {
                        let bar = if i == 0 { "" } else { "    | " };
                        let _ = writeln!(code, "                {bar}{arm}");
                    }
                }
                let _ = writeln!(code, "            )");
            }
            _ => {
                let _ = writeln!(code, "            && {b}");
            }
        }
        let _ = writeln!(code, "        {{");
    }
}

/// The Rust condition "option `option` of set `set` is on" over `k: &Keywords`.
fn on(fields: &[Field], set: usize, option: usize, negated: bool) -> Cond {
    match &fields[set] {
        Field::Always => Cond::Expr((if negated { "false" } else { "true" }).to_string()),
        Field::Flag { field, on } => {
            if (*on == option) != negated {
                Cond::Expr(format!("k.{field}"))
            } else {
                Cond::Expr(format!("!k.{field}"))
            }
        }
        Field::Choice {
            field,
            name,
            variants,
        } => Cond::Matches {
            negated,
            value: format!("k.{field}"),
            arms: vec![format!("keywords::{name}::{}", variants[option])],
        },
    }
}

/// The Rust condition "none of `alternatives` is on" (options of one set, so of one enum
/// field): the shorter of `!matches!(k.f, A | B)` and `matches!(k.f, C | D)` over the other
/// options, so the line stays as rustfmt leaves it.
fn none_of(fields: &[Field], alternatives: &[(usize, usize)]) -> Cond {
    let set = alternatives[0].0;
    let Field::Choice {
        field,
        name,
        variants,
    } = &fields[set]
    else {
        // Only a set of three or more options has alternatives; join the conditions.
        let any: Vec<String> = alternatives
            .iter()
            .map(|&(s, o)| on(fields, s, o, false).to_string())
            .collect();
        return Cond::Expr(format!("!({})", any.join(" || ")));
    };
    let pattern = |negated: bool, options: Vec<usize>| Cond::Matches {
        negated,
        value: format!("k.{field}"),
        arms: options
            .iter()
            .map(|&o| format!("keywords::{name}::{}", variants[o]))
            .collect(),
    };
    let named: Vec<usize> = alternatives.iter().map(|&(_, o)| o).collect();
    let others: Vec<usize> = (0..variants.len()).filter(|o| !named.contains(o)).collect();
    let negated = pattern(true, named);
    let complement = pattern(false, others);
    if complement.to_string().len() < negated.to_string().len() {
        complement
    } else {
        negated
    }
}

/// Writes `keywords` (the enums), `Keywords`, `Key`, `KeyError` and `Key`'s methods. With
/// `baked` (the module of a `Bake::bindings` bake), `Key::new` also refuses the combinations
/// the bake left out (`tables::BAKED`), and `Key::baked` finds a key's baked variant.
pub(crate) fn write(code: &mut String, pass: &Pass, fields: &[Field], baked: bool) {
    let label = format!("{}/{}", pass.shader, pass.name);
    // The enums.
    let enums: Vec<usize> = (0..fields.len())
        .filter(|&i| matches!(fields[i], Field::Choice { .. }))
        .collect();
    if !enums.is_empty() {
        let _ = writeln!(
            code,
            "/// The options of the keyword sets of `{label}` that are more than on/off."
        );
        let _ = writeln!(code, "pub mod keywords {{");
        for (n, &i) in enums.iter().enumerate() {
            let Field::Choice { name, variants, .. } = &fields[i] else {
                continue;
            };
            let set = &pass.sets[i];
            if n > 0 {
                let _ = writeln!(code);
            }
            let _ = writeln!(code, "    /// `{set}`.");
            let _ = writeln!(
                code,
                "    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]"
            );
            let _ = writeln!(code, "    #[repr(u16)]");
            let _ = writeln!(code, "    pub enum {name} {{");
            for (o, (variant, option)) in variants.iter().zip(&set.options).enumerate() {
                match option {
                    Some(k) => {
                        let _ = writeln!(code, "        /// `{k}`.");
                    }
                    None => {
                        let _ = writeln!(code, "        /// None of the set's keywords.");
                    }
                }
                let default = set.none_index().unwrap_or(0);
                if o == default {
                    let _ = writeln!(code, "        #[default]");
                }
                let _ = writeln!(code, "        {variant} = {o},");
            }
            let _ = writeln!(code, "    }}");
        }
        let _ = writeln!(code, "}}");
        let _ = writeln!(code);
    }

    // Keywords: the plain fields.
    let _ = writeln!(
        code,
        "/// The keyword sets of `{label}`, one field per set."
    );
    let _ = writeln!(code, "///");
    let _ = writeln!(
        code,
        "/// Unchecked: [`Key::new`] checks them against the pass's constraints. The default is"
    );
    let _ = writeln!(code, "/// every set's \"none\" option (or its first).");
    let _ = writeln!(
        code,
        "#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]"
    );
    let live: Vec<usize> = (0..fields.len())
        .filter(|&i| !matches!(fields[i], Field::Always))
        .collect();
    if live.is_empty() {
        let _ = writeln!(code, "pub struct Keywords {{}}");
    } else {
        let _ = writeln!(code, "pub struct Keywords {{");
        for &i in &live {
            let set = &pass.sets[i];
            match &fields[i] {
                Field::Flag { field, .. } => {
                    let k = set.keywords().next().unwrap_or_default();
                    let _ = writeln!(code, "    /// `{k}` is on (`{set}`).");
                    let _ = writeln!(code, "    pub {field}: bool,");
                }
                Field::Choice { field, name, .. } => {
                    let _ = writeln!(code, "    /// `{set}`.");
                    let _ = writeln!(code, "    pub {field}: keywords::{name},");
                }
                Field::Always => {}
            }
        }
        let _ = writeln!(code, "}}");
    }
    let _ = writeln!(code);
    let _ = writeln!(code, "impl Keywords {{");
    let _ = writeln!(
        code,
        "    /// [`Keywords::default`] for constants (`..Keywords::DEFAULT`)."
    );
    let defaults: Vec<(&str, String)> = live
        .iter()
        .map(|&i| match &fields[i] {
            Field::Flag { field, .. } => (field.as_str(), "false".to_string()),
            Field::Choice {
                field,
                name,
                variants,
            } => (
                field.as_str(),
                format!(
                    "keywords::{name}::{}",
                    variants[pass.sets[i].none_index().unwrap_or(0)]
                ),
            ),
            Field::Always => unreachable!("live sets have a field"),
        })
        .collect();
    struct_lit(
        code,
        4,
        "pub const DEFAULT: Keywords = ",
        "Keywords",
        &defaults,
        ";",
    );
    let _ = writeln!(code, "}}");
    let _ = writeln!(code);

    // KeyError.
    code.push_str(KEY_ERROR_HEAD);
    if baked {
        code.push_str(KEY_ERROR_NOT_BAKED);
    }
    code.push_str(KEY_ERROR_DISPLAY);
    if baked {
        code.push_str(KEY_ERROR_NOT_BAKED_RULE);
    }
    code.push_str(KEY_ERROR_FMT);
    if baked {
        code.push_str(KEY_ERROR_NOT_BAKED_DISPLAY);
    }
    code.push_str(KEY_ERROR_TAIL);
    let _ = writeln!(code);

    // Key.
    let _ = writeln!(code, "/// A variant of `{label}`.");
    let _ = writeln!(code, "///");
    let _ = writeln!(
        code,
        "/// [`Keywords`] that satisfy the pass's `require`, `exclude` and `skip_variants`."
    );
    let _ = writeln!(
        code,
        "#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]"
    );
    let _ = writeln!(code, "pub struct Key(Keywords);");
    let _ = writeln!(code);
    let _ = writeln!(code, "impl Key {{");
    let _ = writeln!(code, "    /// Number of keyword sets.");
    let _ = writeln!(code, "    pub const SETS: usize = {};", fields.len());
    let product: u128 = pass.sets.iter().map(|s| s.len() as u128).product();
    let _ = writeln!(
        code,
        "    /// Number of option combinations, constraints ignored: [`Key::index`] is below it."
    );
    let _ = writeln!(code, "    pub const COMBINATIONS: usize = {product};");
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "    /// Checks `keywords` against the pass's constraints, in declaration order."
    );
    let _ = writeln!(
        code,
        "    pub const fn new(keywords: Keywords) -> Result<Key, KeyError> {{"
    );
    let mut checks = String::new();
    for c in &pass.constraints {
        let (sa, oa) = c.at[0];
        let a = &c.keywords[0];
        // A requirement's alternatives, joined: "B or C".
        let b = c.keywords[1..].join(" or ");
        let (variant, other, negated) = match c.kind {
            ConstraintKind::Require => ("Requires", "required", true),
            ConstraintKind::Exclude => ("Excludes", "excluded", false),
        };
        let partner = match &c.at[1..] {
            [(sb, ob)] => on(fields, *sb, *ob, negated),
            alternatives => none_of(fields, alternatives),
        };
        if_both(&mut checks, &on(fields, sa, oa, false), &partner);
        struct_lit(
            &mut checks,
            12,
            "return Err(",
            &format!("KeyError::{variant}"),
            &[("keyword", format!("{a:?}")), (other, format!("{b:?}"))],
            ");",
        );
        let _ = writeln!(checks, "        }}");
    }
    for (i, set) in pass.sets.iter().enumerate() {
        for (o, option) in set.options.iter().enumerate() {
            if let Some(k) = option.as_deref().filter(|_| pass.is_skipped_option(i, o)) {
                let _ = writeln!(checks, "        if {} {{", on(fields, i, o, false));
                struct_lit(
                    &mut checks,
                    12,
                    "return Err(",
                    "KeyError::Skipped",
                    &[("keyword", format!("{k:?}"))],
                    ");",
                );
                let _ = writeln!(checks, "        }}");
            }
        }
    }
    if !checks.is_empty() {
        let _ = writeln!(code, "        let k = &keywords;");
        code.push_str(&checks);
    }
    if baked {
        // The bake's build set is any subset of the space (materials, covering, budget): a
        // table lookup, not a rule.
        let _ = writeln!(
            code,
            "        if tables::BAKED[Key(keywords).index()] == u32::MAX {{"
        );
        let _ = writeln!(code, "            return Err(KeyError::NotBaked);");
        let _ = writeln!(code, "        }}");
    }
    let _ = writeln!(code, "        Ok(Key(keywords))");
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "    /// [`Key::new`] for constants: an impossible combination fails to compile."
    );
    let _ = writeln!(
        code,
        "    pub const fn checked(keywords: Keywords) -> Key {{"
    );
    let _ = writeln!(code, "        match Key::new(keywords) {{");
    let _ = writeln!(code, "            Ok(key) => key,");
    // A const panic formats no fields, but takes one `&str`: the rule, per kind of error.
    let _ = writeln!(code, "            Err(e) => panic!(\"{{}}\", e.rule()),");
    let _ = writeln!(code, "        }}");
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);
    let _ = writeln!(code, "    /// The keywords, as checked.");
    let _ = writeln!(code, "    pub const fn get(&self) -> Keywords {{");
    let _ = writeln!(code, "        self.0");
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);

    // choice()
    let _ = writeln!(
        code,
        "    /// The option of each keyword set, in set order (`wgsl_variants::Choice`)."
    );
    let n = fields.len();
    let _ = writeln!(code, "    pub const fn choice(&self) -> [u16; {n}] {{");
    let needs_k = !live.is_empty();
    if needs_k {
        let _ = writeln!(code, "        let k = &self.0;");
    }
    if live.is_empty() {
        // No set to read: the array itself (a `let` returned at once is a clippy warning).
        let _ = writeln!(code, "        [0; {n}]");
    } else {
        let _ = writeln!(code, "        let mut choice = [0; {n}];");
    }
    for &i in &live {
        match &fields[i] {
            Field::Flag { field, on } => {
                if *on == 1 {
                    let _ = writeln!(code, "        choice[{i}] = k.{field} as u16;");
                } else {
                    let _ = writeln!(code, "        choice[{i}] = !k.{field} as u16;");
                }
            }
            Field::Choice { field, .. } => {
                let _ = writeln!(code, "        choice[{i}] = k.{field} as u16;");
            }
            Field::Always => {}
        }
    }
    if !live.is_empty() {
        let _ = writeln!(code, "        choice");
    }
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);

    // index()
    let _ = writeln!(
        code,
        "    /// The variant's position among [`Key::COMBINATIONS`]: options in set order, the last"
    );
    let _ = writeln!(
        code,
        "    /// set fastest (the order `Space::full` enumerates a pass without constraints)."
    );
    let _ = writeln!(code, "    pub const fn index(&self) -> usize {{");
    if live.is_empty() {
        let _ = writeln!(code, "        0");
    } else {
        let _ = writeln!(code, "        let choice = self.choice();");
        let _ = writeln!(code, "        let mut index = 0;");
        for &i in &live {
            let radix = pass.sets[i].len();
            let _ = writeln!(
                code,
                "        index = index * {radix} + choice[{i}] as usize;"
            );
        }
        let _ = writeln!(code, "        index");
    }
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);

    // keywords()
    let _ = writeln!(
        code,
        "    /// The keywords that are on, in set order: what the lookup of `wgsl_variants::bake`"
    );
    let _ = writeln!(
        code,
        "    /// takes (`shaders::variant(SHADER, PASS, &key.keywords())`)."
    );
    let _ = writeln!(code, "    pub fn keywords(&self) -> Vec<&'static str> {{");
    if needs_k {
        let _ = writeln!(code, "        let k = &self.0;");
    }
    let mut body = String::new();
    for (i, field) in fields.iter().enumerate() {
        let set = &pass.sets[i];
        match field {
            Field::Always => {
                if let Some(k) = set.keywords().next() {
                    let _ = writeln!(body, "        on.push({k:?});");
                }
            }
            Field::Flag { field, on } => {
                let k = set.options[*on].as_deref().unwrap_or_default();
                let _ = writeln!(body, "        if k.{field} {{");
                let _ = writeln!(body, "            on.push({k:?});");
                let _ = writeln!(body, "        }}");
            }
            Field::Choice {
                field,
                name,
                variants,
            } => {
                let _ = writeln!(body, "        match k.{field} {{");
                for (variant, option) in variants.iter().zip(&set.options) {
                    match option {
                        Some(k) => {
                            let _ = writeln!(
                                body,
                                "            keywords::{name}::{variant} => on.push({k:?}),"
                            );
                        }
                        None => {
                            let _ =
                                writeln!(body, "            keywords::{name}::{variant} => {{}}");
                        }
                    }
                }
                let _ = writeln!(body, "        }}");
            }
        }
    }
    if body.is_empty() {
        let _ = writeln!(code, "        Vec::new()");
    } else {
        let _ = writeln!(code, "        let mut on = Vec::new();");
        code.push_str(&body);
        let _ = writeln!(code, "        on");
    }
    let _ = writeln!(code, "    }}");
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "    /// The variant's bindings, vertex inputs and colour targets."
    );
    let _ = writeln!(code, "    pub fn interface(&self) -> &'static Interface {{");
    let _ = writeln!(
        code,
        "        &INTERFACES[VARIANT_INTERFACE[self.index()] as usize]"
    );
    let _ = writeln!(code, "    }}");
    if baked {
        code.push_str(BAKED_FN);
    }
    let _ = writeln!(code, "}}");
}

/// `Key::baked`: the key's entry in the bake's `variants()`, by index, no strings.
const BAKED_FN: &str = r#"
    /// The key's baked variant: `variants` is `variants()` of the file the same bake wrote
    /// (`shaders::variants()`), which this module indexes by [`Key::index`] without keyword
    /// strings. [`Key::new`] refused every combination the bake left out, so there is one.
    ///
    /// Panics if `variants` is not that bake's (its length differs).
    pub fn baked<V>(&self, variants: &'static [V]) -> &'static V {
        assert!(
            variants.len() == tables::BAKED_VARIANTS,
            "not the variants() of the bake that wrote this module"
        );
        &variants[tables::BAKED[self.index()] as usize]
    }
"#;

const KEY_ERROR_HEAD: &str = r#"/// Why [`Keywords`] name no variant of the pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum KeyError {
    /// `#pragma require`: `keyword` is on without `required`.
    Requires {
        /// The keyword that is on.
        keyword: &'static str,
        /// The keyword it needs (alternatives joined by ` or `).
        required: &'static str,
    },
    /// `#pragma exclude`: `keyword` and `excluded` are both on.
    Excludes {
        /// The first keyword.
        keyword: &'static str,
        /// The keyword it excludes.
        excluded: &'static str,
    },
    /// `#pragma skip_variants`: no variant with `keyword` on is built.
    Skipped {
        /// The skipped keyword.
        keyword: &'static str,
    },
"#;

const KEY_ERROR_NOT_BAKED: &str = r#"    /// The bake left the combination out: no material uses it (`shader_feature`), or the
    /// bake's covering set or budget does not include it.
    NotBaked,
"#;

const KEY_ERROR_DISPLAY: &str = r##"}

impl KeyError {
    /// The rule the keywords break, without them: what a refused [`Key::checked`] constant
    /// says (a `const` panic cannot format the keywords).
    pub const fn rule(&self) -> &'static str {
        match self {
            KeyError::Requires { .. } => "#pragma require: a keyword is on, its requirement off",
            KeyError::Excludes { .. } => "#pragma exclude: two mutually exclusive keywords are on",
            KeyError::Skipped { .. } => "skip_variants: a skipped keyword is on",
"##;

const KEY_ERROR_NOT_BAKED_RULE: &str = r#"            KeyError::NotBaked => "the bake left the combination out (materials, cover, budget)",
"#;

const KEY_ERROR_FMT: &str = r#"        }
    }
}

impl core::fmt::Display for KeyError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            KeyError::Requires { keyword, required } => {
                write!(f, "`{keyword}` requires `{required}` (#pragma require)")
            }
            KeyError::Excludes { keyword, excluded } => {
                write!(f, "`{keyword}` excludes `{excluded}` (#pragma exclude)")
            }
            KeyError::Skipped { keyword } => write!(f, "`{keyword}` is in skip_variants"),
"#;

const KEY_ERROR_NOT_BAKED_DISPLAY: &str = r#"            KeyError::NotBaked => write!(f, "not in the bake's build set"),
"#;

const KEY_ERROR_TAIL: &str = r#"        }
    }
}

impl std::error::Error for KeyError {}
"#;
