//! Materials: which `shader_feature` keywords the content actually uses.
//!
//! A materials file lists materials, each naming a shader and the keywords it enables — the
//! keyword state Unity keeps per material. Given materials, a pass's build set keeps only the
//! `shader_feature` combinations some material of its shader uses. JSON and TOML are accepted:
//!
//! ```toml
//! [[material]]
//! name = "Bricks"
//! shader = "standard"
//! keywords = ["_NORMAL_MAP", "_METALLIC_MAP"]
//! ```
//!
//! ```json
//! { "materials": [ { "name": "Bricks", "shader": "standard", "keywords": ["_NORMAL_MAP"] } ] }
//! ```

use std::collections::BTreeSet;
use std::path::Path;

use serde::Deserialize;

use crate::data_file::{self, FileError, Format};
use crate::diagnostic::suggest;
use crate::shader::{Pass, Shader};

/// One material: a shader and the keywords it has on.
#[derive(Clone, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Material name, for messages.
    pub name: String,
    /// The shader it uses.
    pub shader: String,
    /// Keywords that are on.
    #[serde(default)]
    pub keywords: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialsFile {
    #[serde(alias = "material")]
    materials: Vec<Material>,
}

/// A problem with a materials file.
#[derive(Debug, thiserror::Error)]
pub enum MaterialsError {
    /// The file could not be read, or is not valid JSON/TOML of the expected shape.
    #[error(transparent)]
    File(#[from] FileError),
    /// A material names a shader the library does not have.
    #[error(
        "material `{material}` uses shader `{shader}`, which the library does not have{}",
        crate::diagnostic::hint(suggestion.as_deref())
    )]
    UnknownShader {
        /// The material.
        material: String,
        /// The shader it names.
        shader: String,
        /// The closest shader name.
        suggestion: Option<String>,
    },
    /// A keyword no pass of the shader declares.
    #[error(
        "material `{material}` enables `{keyword}`, which no pass of shader `{shader}` declares{}",
        crate::diagnostic::hint(suggestion.as_deref())
    )]
    UnknownKeyword {
        /// The material.
        material: String,
        /// The shader.
        shader: String,
        /// The keyword.
        keyword: String,
        /// The closest declared keyword.
        suggestion: Option<String>,
    },
    /// Two keywords of one set.
    #[error(
        "material `{material}` enables both `{first}` and `{second}`, options of one set of `{shader}/{pass}`"
    )]
    Conflicting {
        /// The material.
        material: String,
        /// The shader.
        shader: String,
        /// The pass.
        pass: String,
        /// First keyword.
        first: String,
        /// Second keyword.
        second: String,
    },
    /// A keyword that `#pragma skip_variants` removes from the pass: no variant of the pass has
    /// it on, so the material could never be drawn with it.
    #[error(
        "material `{material}` enables `{keyword}`, which `#pragma skip_variants` removes from `{shader}/{pass}`: no variant of the pass has it"
    )]
    Skipped {
        /// The material.
        material: String,
        /// The shader.
        shader: String,
        /// The pass.
        pass: String,
        /// The keyword.
        keyword: String,
    },
    /// The material's keywords break a `require`/`exclude` constraint of a pass between two
    /// `shader_feature` sets: no variant of that pass could be built for it.
    #[error(
        "material `{material}` breaks `#pragma {constraint}` of `{shader}/{pass}`: no variant of the pass has its keywords"
    )]
    Constraint {
        /// The material.
        material: String,
        /// The shader.
        shader: String,
        /// The pass.
        pass: String,
        /// The constraint as written, e.g. `exclude _A _B`.
        constraint: String,
    },
}

/// Reads a materials file (`.toml`, otherwise JSON).
pub fn load(path: &Path) -> Result<Vec<Material>, MaterialsError> {
    let text = data_file::read(path, "materials")?;
    parse(
        &text,
        path.extension().is_some_and(|e| e == "toml"),
        &path.display().to_string(),
    )
}

/// Parses materials from text; `toml` selects the format. `path` is used in messages.
pub fn parse(text: &str, toml: bool, path: &str) -> Result<Vec<Material>, MaterialsError> {
    let format = if toml { Format::Toml } else { Format::Json };
    let file: MaterialsFile = data_file::parse(text, format, path)?;
    Ok(file.materials)
}

/// Checks materials against the library's shaders: every shader exists and every keyword is
/// declared by some pass of it.
pub(crate) fn check(materials: &[Material], shaders: &[Shader]) -> Result<(), MaterialsError> {
    for m in materials {
        let Some(shader) = shaders.iter().find(|s| s.name == m.shader) else {
            return Err(MaterialsError::UnknownShader {
                material: m.name.clone(),
                shader: m.shader.clone(),
                suggestion: suggest(&m.shader, shaders.iter().map(|s| s.name.as_str())),
            });
        };
        for k in &m.keywords {
            if !shader.passes.iter().any(|p| p.keyword(k).is_some()) {
                let all = shader.passes.iter().flat_map(|p| p.keywords());
                return Err(MaterialsError::UnknownKeyword {
                    material: m.name.clone(),
                    shader: m.shader.clone(),
                    keyword: k.clone(),
                    suggestion: suggest(k, all),
                });
            }
        }
    }
    Ok(())
}

/// The `shader_feature` combinations the materials of `pass`'s shader use: for each material,
/// one option per shader_feature set (the material's keyword of that set, else the set's
/// "none" option, else its first option, as Unity does).
pub(crate) fn feature_combinations(
    pass: &Pass,
    materials: &[Material],
) -> Result<BTreeSet<Vec<u16>>, MaterialsError> {
    let sf: Vec<usize> = pass.shader_feature_sets().collect();
    let mut combos = BTreeSet::new();
    for m in materials.iter().filter(|m| m.shader == pass.shader) {
        let mut options: Vec<Option<u16>> = vec![None; pass.sets.len()];
        for k in &m.keywords {
            let Some((set, option)) = pass.keyword(k) else {
                continue;
            };
            // Unity lets a material enable any keyword of its shader (a global one too: on
            // when enabled globally or on the material), but one that skip_variants strips
            // from this pass leaves the material with no variant here.
            if pass.skip_variants.contains(k) {
                return Err(MaterialsError::Skipped {
                    material: m.name.clone(),
                    shader: pass.shader.clone(),
                    pass: pass.name.clone(),
                    keyword: k.clone(),
                });
            }
            if let Some(prev) = options[set]
                && prev as usize != option
            {
                return Err(MaterialsError::Conflicting {
                    material: m.name.clone(),
                    shader: pass.shader.clone(),
                    pass: pass.name.clone(),
                    first: pass.sets[set].options[prev as usize]
                        .clone()
                        .unwrap_or_default(),
                    second: k.clone(),
                });
            }
            options[set] = Some(option as u16);
        }
        let chosen: Vec<u16> = (0..pass.sets.len())
            .map(|s| options[s].unwrap_or_else(|| pass.sets[s].none_index().unwrap_or(0) as u16))
            .collect();
        // Only constraints between shader_feature sets are the material's to break; the others
        // also depend on what the pipeline sets.
        let broken = pass
            .constraints
            .iter()
            .find(|c| c.sets().iter().all(|&s| sf.contains(&s)) && !c.holds(&chosen));
        if let Some(c) = broken {
            return Err(MaterialsError::Constraint {
                material: m.name.clone(),
                shader: pass.shader.clone(),
                pass: pass.name.clone(),
                constraint: c.to_string(),
            });
        }
        combos.insert(sf.iter().map(|&s| chosen[s]).collect());
    }
    Ok(combos)
}
