//! What a pass's variants are made from, as one hash: when it is the same as at the last
//! verdict, so is every text of the pass, and its report stands.

use crate::cache::Hash;
use crate::library::Library;
use crate::shader::Pass;

/// The hash of a pass's inputs: the dialect, `options` (the plan options as text), the pass's
/// declaration (keyword sets, constraints, where it is declared) and each of its
/// [files](Library::pass_files) with its id, path and text. File ids are in it because a kept
/// report's spans hold them.
pub(super) fn fingerprint(lib: &Library, pass: &Pass, options: &str) -> Hash {
    let files = lib.files();
    let head = [
        lib.dialect().name().to_string(),
        options.to_string(),
        // The declaration as `list --json` shows it, and where it is (its Debug form holds a
        // hash map: no stable order).
        serde_json::to_string(pass).unwrap_or_default(),
        format!("{} {:?} {}", pass.shader, pass.span, pass.module()),
        // The devices, and whether the report names them (several in the tree).
        format!(
            "{:?} {}",
            lib.pass_profiles(pass)
                .iter()
                .map(|p| p.name())
                .collect::<Vec<_>>(),
            lib.several_profiles()
        ),
    ];
    let ids: Vec<(String, crate::diagnostic::FileId)> = lib
        .pass_files(pass)
        .into_iter()
        .map(|f| (f.to_string(), f))
        .collect();
    let parts = head
        .iter()
        .map(String::as_bytes)
        .chain(ids.iter().flat_map(|(id, f)| {
            [
                id.as_bytes(),
                files.path(*f).as_bytes(),
                files.text(*f).as_bytes(),
            ]
        }));
    *crate::fingerprint::hash_parts(parts).as_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn library(b: &str) -> Library {
        Library::from_sources([
            (
                "a.wgsl",
                "#shader a\n#pass P\n#pragma multi_compile _ X\n#import lib/b\n#endpass\n",
            ),
            ("c.wgsl", "#shader c\n#pass Q\n#endpass\n"),
            ("lib/b.wgsl", b),
        ])
        .unwrap()
    }

    /// Editing a module changes the inputs of the passes that import it, and only theirs.
    #[test]
    fn an_edit_changes_the_passes_that_read_the_file() {
        let (before, after) = (library("fn f() {}\n"), library("fn f() { }\n"));
        let inputs = |lib: &Library, shader: &str, pass: &str| {
            fingerprint(lib, lib.pass(shader, pass).unwrap(), "options")
        };
        assert_ne!(inputs(&before, "a", "P"), inputs(&after, "a", "P"));
        assert_eq!(inputs(&before, "c", "Q"), inputs(&after, "c", "Q"));
        let pass = before.pass("c", "Q").unwrap();
        assert_ne!(
            fingerprint(&before, pass, "options"),
            fingerprint(&before, pass, "other options")
        );
    }
}
