//! Reachability: a variant's text keeps only the top-level items its entry points reach.
//!
//! Our `#import` is textual, so a composed variant carries every function, struct, constant and
//! binding of every module it imports, used or not. [`prune`] drops the ones no entry point
//! reaches, before anything else sees the text: what is validated, emitted, baked and
//! snapshotted is the pruned text ([`crate::Library::compose`] returns it).
//!
//! # How it is decided, and why it is safe
//!
//! A lexer (`reach/items.rs`) splits the composed text into top-level items with a conservative lexer. An item
//! is **kept** when it is a root — an entry point (`@vertex`, `@fragment`, `@compute`), an
//! `override` (a pipeline's interface), a global directive or `const_assert`, or text the
//! lexer does not recognise — or when a kept item mentions its name. Every identifier an item
//! mentions counts, except after `.` (a member) and `@` (an attribute), so local variables
//! and struct members named like a global keep that global: the kept set can only be larger
//! than the set naga's own compaction keeps (a test holds every bundled variant to that).
//! Items that share a line are kept or dropped together, and an item takes with it the blank
//! and comment lines just above it, so the pruned text is whole lines of the composed text,
//! in order, and the line map still points every byte at its original file.
//!
//! Nothing is pruned — the text is left as composed, for naga to judge — when it has no entry
//! point (a module of helpers is validated whole), when the lexer cannot split it (unbalanced
//! braces, an unterminated item or comment) or when a name is declared twice (naga reports the
//! redefinition).
//!
//! What pruning hides: a broken item no entry point reaches is not validated. The audit lists
//! the items that no variant of a pass reaches ([`crate::analysis::unreached()`]), and `validate --strict` also
//! validates each distinct unpruned text ([`crate::Library::compose_unpruned`]).

pub(crate) mod items;

use std::collections::HashMap;

use crate::preprocess::Composed;
use items::Splitter;

/// `composed` with the top-level items no entry point reaches left out (see the
/// [module docs](self)); the line map, when there is one, follows the lines kept.
///
/// ```
/// use wgsl_variants::preprocess::Composed;
///
/// let text = "fn unused() -> f32 { return 1.0; }\n\
///             fn used() -> f32 { return 2.0; }\n\
///             @fragment fn fs() -> @location(0) vec4f { return vec4f(used()); }\n";
/// let composed = Composed { text: text.into(), ..Composed::default() };
/// let pruned = wgsl_variants::reach::prune(composed);
/// assert!(!pruned.text.contains("unused"));
/// assert!(pruned.text.starts_with("fn used()"));
/// ```
pub fn prune(composed: Composed) -> Composed {
    let Some(keep) = kept_lines(&composed.text, |_| true) else {
        return composed;
    };
    let mut out = Composed {
        text: String::with_capacity(composed.text.len()),
        failure: composed.failure,
        ..Composed::default()
    };
    for (n, line) in composed.text.split_inclusive('\n').enumerate() {
        if !keep[n] {
            continue;
        }
        if let Some((file, src)) = composed.map.line_source(n) {
            out.map.push(out.text.len(), file, src);
        }
        out.text.push_str(line);
    }
    out
}

/// The items of `text` that one pipeline stage runs: those its entry points reach (with the
/// directives and overrides every program keeps), each as its name (`None` for a nameless
/// root) and its lines; `None` when the text cannot be split or has no entry point.
pub(crate) fn stage_items(
    text: &str,
    stage: crate::stage::PipelineStage,
) -> Option<Vec<(Option<String>, String)>> {
    let items = Splitter::split(text)?;
    let keep = kept_lines(text, |stage_of| stage_of == Some(stage.attribute()))
        .unwrap_or_else(|| vec![true; text.split_terminator('\n').count()]);
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    Some(
        items
            .iter()
            .filter(|i| keep.get(i.first_line as usize).copied().unwrap_or(true))
            .map(|i| {
                let body = lines
                    [i.first_line as usize..=(i.last_line as usize).min(lines.len() - 1)]
                    .concat();
                (i.name.map(str::to_string), body)
            })
            .collect(),
    )
}

/// For each `\n`-ended line of `text`, whether pruning keeps it; `None` when every line is
/// kept (nothing unreached, or the text cannot be split). `entry` says which entry points
/// (by stage attribute) are roots.
fn kept_lines(text: &str, entry: impl Fn(Option<&str>) -> bool) -> Option<Vec<bool>> {
    let items = Splitter::split(text)?;
    // No entry point: a module of helpers (a test's, a library's), validated whole.
    if !items.iter().any(|i| i.entry) {
        return None;
    }
    let mut by_name: HashMap<&str, usize> = HashMap::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        if let Some(name) = item.name
            && by_name.insert(name, i).is_some()
        {
            return None;
        }
    }
    // Units: runs of items that share lines, kept or dropped together.
    let mut unit_of = Vec::with_capacity(items.len());
    let mut units: Vec<std::ops::Range<usize>> = Vec::new();
    for (i, item) in items.iter().enumerate() {
        match units.last_mut() {
            Some(last) if items[last.end - 1].last_line >= item.first_line => last.end = i + 1,
            _ => units.push(i..i + 1),
        }
        unit_of.push(units.len() - 1);
    }
    let mut kept = vec![false; units.len()];
    let mut stack: Vec<usize> = Vec::new();
    let mark = |i: usize, kept: &mut Vec<bool>, stack: &mut Vec<usize>| {
        let unit = unit_of[i];
        if !kept[unit] {
            kept[unit] = true;
            stack.extend(units[unit].clone());
        }
    };
    for (i, item) in items.iter().enumerate() {
        if item.is_root() && (!item.entry || entry(item.stage)) {
            mark(i, &mut kept, &mut stack);
        }
    }
    while let Some(i) = stack.pop() {
        for r in &items[i].refs {
            if let Some(&target) = by_name.get(r) {
                mark(target, &mut kept, &mut stack);
            }
        }
    }
    if kept.iter().all(|&k| k) {
        return None;
    }
    let mut keep = vec![true; text.split_terminator('\n').count()];
    let mut from = 0;
    for (unit, range) in units.iter().enumerate() {
        let last = items[range.end - 1].last_line as usize;
        if !kept[unit] {
            keep[from..=last].fill(false);
        }
        from = last + 1;
    }
    Some(keep)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::SourceFiles;

    fn pruned(text: &str) -> String {
        prune(Composed {
            text: text.into(),
            ..Composed::default()
        })
        .text
    }

    #[test]
    fn unreached_items_go_with_their_comments() {
        let text = "struct Unused { a: f32 }\n\
                    // the light\n\
                    struct Light { c: vec3f }\n\
                    \n\
                    // helper nobody calls\n\
                    fn helper(l: Unused) -> f32 { return l.a; }\n\
                    @group(0) @binding(0) var<uniform> light: Light;\n\
                    @group(0) @binding(1) var<uniform> other: Light;\n\
                    @fragment fn fs() -> @location(0) vec4f { return vec4f(light.c, 1.0); }\n";
        assert_eq!(
            pruned(text),
            "// the light\n\
             struct Light { c: vec3f }\n\
             @group(0) @binding(0) var<uniform> light: Light;\n\
             @fragment fn fs() -> @location(0) vec4f { return vec4f(light.c, 1.0); }\n"
        );
    }

    #[test]
    fn items_on_one_line_stay_together() {
        let text = "const a = 1; const b = 2;\nconst c = 3;\n\
                    @compute @workgroup_size(1) fn main() { let x = b; }\n";
        assert_eq!(
            pruned(text),
            "const a = 1; const b = 2;\n@compute @workgroup_size(1) fn main() { let x = b; }\n"
        );
    }

    #[test]
    fn roots_and_what_they_mention_are_kept() {
        let text = "enable f16;\noverride scale: f32 = 1.0;\nconst_assert N > 0;\nconst N = 2;\n\
                    const M = 3;\n@compute @workgroup_size(1) fn main() {}\n";
        assert_eq!(
            pruned(text),
            "enable f16;\noverride scale: f32 = 1.0;\nconst_assert N > 0;\nconst N = 2;\n\
             @compute @workgroup_size(1) fn main() {}\n"
        );
    }

    #[test]
    fn text_without_an_entry_point_that_cannot_be_split_or_redeclares_is_left_alone() {
        for text in [
            "fn f() {}\nfn g() {}\n",
            "fn f() {\n@fragment fn g() {}\n",
            "fn f() {}\nfn f() {}\n@fragment fn g() {}\n",
        ] {
            assert_eq!(pruned(text), text);
        }
    }

    #[test]
    fn the_line_map_follows_the_lines_kept() {
        let mut files = SourceFiles::new();
        let source = "fn unused() {}\n@compute @workgroup_size(1) fn main() {}\n";
        let file = files.add("m.wgsl".into(), source.into());
        let mut composed = Composed {
            text: source.into(),
            ..Composed::default()
        };
        composed.map.push(0, file, 0);
        composed.map.push(15, file, 15);
        let out = prune(composed);
        assert_eq!(out.text, "@compute @workgroup_size(1) fn main() {}\n");
        let span = out.map.to_original(31, 35, &out.text).unwrap();
        assert_eq!(&source[span.range()], "main");
    }
}
