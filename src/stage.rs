//! The pipeline stages a declared pass can be split into, each composed with its own defs.
//!
//! A render pipeline compiles its vertex and its fragment shader separately, each from its
//! own module and with its own shader defs: Bevy's `RenderPipelineDescriptor` carries one
//! `shader_defs` list in its `VertexState` and another in its `FragmentState` (a material's
//! `specialize` pushes its defs to the fragment state only, and the 3D line gizmo pushes
//! `PERSPECTIVE` to the fragment state only). A declaration file says the same with a pass's
//! `stages` table; each stage becomes a pass of its own, named `PASS/STAGE`.

/// A stage of a render pipeline that a declared pass can compose on its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PipelineStage {
    /// The vertex shader (`@vertex` entry points).
    Vertex,
    /// The fragment shader (`@fragment` entry points).
    Fragment,
}

impl PipelineStage {
    /// Every stage, in pipeline order.
    pub const ALL: [PipelineStage; 2] = [PipelineStage::Vertex, PipelineStage::Fragment];

    /// The stage's name in declaration files and pass names: `vertex`, `fragment`.
    ///
    /// ```
    /// use wgsl_variants::PipelineStage;
    /// assert_eq!(PipelineStage::Fragment.name(), "fragment");
    /// assert_eq!(PipelineStage::from_name("vertex"), Some(PipelineStage::Vertex));
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            PipelineStage::Vertex => "vertex",
            PipelineStage::Fragment => "fragment",
        }
    }

    /// The stage named `name`, if any.
    pub fn from_name(name: &str) -> Option<PipelineStage> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The WGSL attribute that marks this stage's entry points, without `@`.
    pub fn attribute(self) -> &'static str {
        self.name()
    }
}

impl std::fmt::Display for PipelineStage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
