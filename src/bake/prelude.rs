// The fixed part of the Rust file `wgsl_variants::bake` generates: types, the strict lookup and
// helpers. The generated part after it defines `VARIANTS` and `PASSES`. Self-contained: the
// consuming crate needs no runtime dependency.

#[allow(dead_code)]
/// A shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// `@vertex`.
    Vertex,
    /// `@fragment`.
    Fragment,
    /// `@compute`.
    Compute,
    /// Another stage (task, mesh, ray tracing).
    Other,
}

#[allow(dead_code)]
/// An entry point of a baked variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EntryPoint {
    /// Its name.
    pub name: &'static str,
    /// Its stage.
    pub stage: Stage,
}

#[allow(dead_code)]
/// One baked variant: validated by naga when the crate was built.
#[derive(Debug)]
pub struct Variant {
    /// Shader name.
    pub shader: &'static str,
    /// Pass name.
    pub pass: &'static str,
    /// The keywords that are on, in the pass's set order.
    pub keywords: &'static [&'static str],
    /// Entry points in declaration order.
    pub entry_points: &'static [EntryPoint],
    /// The canonical WGSL (validated, compacted, written by naga), when WGSL was baked.
    pub wgsl: Option<&'static str>,
    /// SPIR-V words, when SPIR-V was baked.
    pub spirv: Option<&'static [u32]>,
    /// BLAKE3 hash (hex) of the canonical WGSL.
    pub hash: &'static str,
    /// `keywords`, sorted: the lookup key.
    sorted_keywords: &'static [&'static str],
}

#[allow(dead_code)]
/// A baked pass: its keywords and its variants.
#[derive(Debug)]
pub struct Pass {
    /// Shader name.
    pub shader: &'static str,
    /// Pass name.
    pub pass: &'static str,
    /// Every keyword the pass declares, sorted.
    pub keywords: &'static [&'static str],
    /// Indices into [`VARIANTS`] of the pass's variants, sorted by sorted keyword list.
    index: &'static [usize],
}

#[allow(dead_code)]
impl Pass {
    /// The pass's baked variants, in lookup order.
    pub fn variants(&self) -> impl Iterator<Item = &'static Variant> + 'static {
        self.index.iter().map(|&i| &VARIANTS[i])
    }
}

#[allow(dead_code)]
/// Why [`variant`] found nothing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LookupError {
    /// No baked shader has this name.
    UnknownShader(String),
    /// The shader has no baked pass of this name.
    UnknownPass {
        /// Shader.
        shader: String,
        /// Pass asked for.
        pass: String,
    },
    /// The pass declares no such keyword.
    UnknownKeyword {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The keyword.
        keyword: String,
    },
    /// The keywords are the pass's, but this combination was not baked (two keywords of one
    /// set, or a `shader_feature` combination no material uses, or a skipped variant).
    NotBaked {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The keywords asked for, sorted.
        keywords: Vec<String>,
    },
}

#[allow(dead_code)]
impl ::core::fmt::Display for LookupError {
    fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
        match self {
            LookupError::UnknownShader(name) => write!(f, "no baked shader `{name}`"),
            LookupError::UnknownPass { shader, pass } => {
                write!(f, "shader `{shader}` has no baked pass `{pass}`")
            }
            LookupError::UnknownKeyword {
                shader,
                pass,
                keyword,
            } => write!(f, "{shader}/{pass} declares no keyword `{keyword}`"),
            LookupError::NotBaked {
                shader,
                pass,
                keywords,
            } => write!(
                f,
                "{shader}/{pass} {{{}}} is not in the baked build set",
                keywords.join(", ")
            ),
        }
    }
}

#[allow(dead_code)]
impl ::std::error::Error for LookupError {}

#[allow(dead_code)]
/// The baked variant of `shader/pass` with exactly `keywords` on (in any order; repeats are
/// ignored). Strict: no other variant is substituted.
pub fn variant(
    shader: &str,
    pass: &str,
    keywords: &[&str],
) -> Result<&'static Variant, LookupError> {
    let Some(p) = PASSES.iter().find(|p| p.shader == shader && p.pass == pass) else {
        return Err(if PASSES.iter().any(|p| p.shader == shader) {
            LookupError::UnknownPass {
                shader: shader.to_string(),
                pass: pass.to_string(),
            }
        } else {
            LookupError::UnknownShader(shader.to_string())
        });
    };
    let mut sorted: Vec<&str> = keywords.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    if let Some(unknown) = sorted.iter().find(|k| p.keywords.binary_search(k).is_err()) {
        return Err(LookupError::UnknownKeyword {
            shader: shader.to_string(),
            pass: pass.to_string(),
            keyword: unknown.to_string(),
        });
    }
    p.index
        .binary_search_by(|&i| VARIANTS[i].sorted_keywords.cmp(sorted.as_slice()))
        .map(|found| &VARIANTS[p.index[found]])
        .map_err(|_| LookupError::NotBaked {
            shader: shader.to_string(),
            pass: pass.to_string(),
            keywords: sorted.iter().map(|k| k.to_string()).collect(),
        })
}

#[allow(dead_code)]
/// Every baked variant, pass by pass in enumeration order.
pub fn variants() -> &'static [Variant] {
    VARIANTS
}

#[allow(dead_code)]
/// Every baked pass.
pub fn passes() -> &'static [Pass] {
    PASSES
}

/// SPIR-V bytes kept 4-aligned, so that they can be read as words where they are.
#[allow(dead_code)]
#[repr(C, align(4))]
struct SpirvBytes<const N: usize>([u8; N]);

/// `spirv_words!(WORDS, "file.spv")`: a SPIR-V file (little-endian words, as the bake writes
/// it) as `&'static [u32]`. On little-endian targets the 4-aligned bytes are the words: read in
/// place, which costs the compiler nothing (assembling millions of words one by one in a
/// `const fn` took it minutes on a large build set).
#[cfg(target_endian = "little")]
#[allow(unused_macros)]
macro_rules! spirv_words {
    ($words:literal, $path:expr) => {{
        static BYTES: SpirvBytes<{ $words * 4 }> = SpirvBytes(*include_bytes!($path));
        // SAFETY: `BYTES` is 4-aligned, holds exactly `$words` words, lives for the whole
        // program and is never written; any four bytes are a `u32`, and on a little-endian
        // target these are the file's words.
        #[allow(unsafe_code)]
        let words = unsafe { ::core::slice::from_raw_parts(BYTES.0.as_ptr().cast::<u32>(), $words) };
        words
    }};
}

/// `spirv_words!(WORDS, "file.spv")` on big-endian targets: each word assembled at compile
/// time.
#[cfg(target_endian = "big")]
#[allow(unused_macros)]
macro_rules! spirv_words {
    ($words:literal, $path:expr) => {{
        static WORDS: [u32; $words] = spirv_words_swapped::<$words>(include_bytes!($path));
        &WORDS
    }};
}

/// Little-endian SPIR-V bytes to words, at compile time (big-endian targets).
#[cfg(target_endian = "big")]
#[allow(dead_code)]
const fn spirv_words_swapped<const N: usize>(bytes: &[u8]) -> [u32; N] {
    let mut words = [0u32; N];
    let mut i = 0;
    while i < N {
        words[i] = u32::from_le_bytes([
            bytes[4 * i],
            bytes[4 * i + 1],
            bytes[4 * i + 2],
            bytes[4 * i + 3],
        ]);
        i += 1;
    }
    words
}
