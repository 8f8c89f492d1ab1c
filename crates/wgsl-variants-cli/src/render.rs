//! `wgsl-variants render`: the GPU check's test scene as PNG pictures (G-buffer contents, the
//! light in RT3, the final frame), or with `--frame [builtin|urp]` a whole frame (Unity's
//! built-in paths or URP's) forward, deferred and as the CPU reference, with the differences.

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::frame::FrameScene;
use wgsl_variants_gpu::check::urp_frame::UrpFrame;
use wgsl_variants_gpu::check::{TestScene, pictures};

use super::context::{Context, Failed};
use super::output::print_json;

/// `render` arguments.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Shader name (default: standard).
    #[arg(requires = "pass", conflicts_with = "frame")]
    shader: Option<String>,
    /// Pass name: Deferred or ForwardBase (default: Deferred).
    pass: Option<String>,
    /// Keywords that are on, comma-separated (default for standard/Deferred: every map and
    /// UNITY_ENABLE_REFLECTION_BUFFERS).
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "A,B",
        conflicts_with = "frame"
    )]
    keywords: Option<Vec<String>>,
    /// Render a whole frame forward and deferred and as the CPU reference, with the
    /// forward − deferred differences: `builtin` (the default; five objects, five lights,
    /// cookies and shadows, HDR and LDR; docs/shading.md §12) or `urp` (URP Lit's forward
    /// and deferred paths, HDR; docs/urp.md §12).
    #[arg(
        long,
        value_enum,
        value_name = "FRAME",
        num_args = 0..=1,
        default_missing_value = "builtin"
    )]
    frame: Option<Frame>,
    /// Folder to write the PNG files into (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Each scene pixel becomes SCALE × SCALE image pixels (nearest neighbour).
    #[arg(long, value_name = "SCALE", default_value_t = 16)]
    scale: u32,
    /// Use the first adapter whose name contains NAME (case-insensitive).
    #[arg(long, value_name = "NAME")]
    adapter: Option<String>,
}

/// Which frame `--frame` renders.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum Frame {
    /// Unity's built-in forward and deferred paths.
    Builtin,
    /// URP's forward and deferred paths.
    Urp,
}

pub fn run(ctx: &Context, args: &RenderArgs) -> Result<ExitCode, Failed> {
    if let Some(frame) = args.frame {
        let gpu = GpuContext::new(args.adapter.as_deref())?;
        let (pictures, what) = match frame {
            Frame::Builtin => (
                pictures::frame_pictures(&gpu, &ctx.lib, &FrameScene::new())?,
                "the frame",
            ),
            Frame::Urp => (
                pictures::urp_frame_pictures(&gpu, &ctx.lib, &UrpFrame::new())?,
                "URP's frame",
            ),
        };
        return write(
            ctx,
            args,
            &pictures,
            &format!("{what} on {}", gpu.adapter_name()),
        );
    }
    let shader = args.shader.as_deref().unwrap_or("standard");
    let pass = args.pass.as_deref().unwrap_or("Deferred");
    let keywords: Vec<&str> = match &args.keywords {
        Some(k) => k
            .iter()
            .map(|k| k.trim())
            .filter(|k| !k.is_empty())
            .collect(),
        None if (shader, pass) == ("standard", "Deferred") => pictures::DEFAULT_KEYWORDS.names(),
        None => Vec::new(),
    };
    let gpu = GpuContext::new(args.adapter.as_deref())?;
    let scene = TestScene::default();
    let pictures = pictures::render_pictures(&gpu, &ctx.lib, &scene, shader, pass, &keywords)?;
    let what = format!(
        "{shader}/{pass} {{{}}} on {}",
        keywords.join(", "),
        gpu.adapter_name()
    );
    write(ctx, args, &pictures, &what)
}

/// Writes the pictures as PNG files into `--out` and lists them.
fn write(
    ctx: &Context,
    args: &RenderArgs,
    pictures: &[pictures::Picture],
    what: &str,
) -> Result<ExitCode, Failed> {
    std::fs::create_dir_all(&args.out)
        .map_err(|e| Failed(format!("error: cannot create {}: {e}", args.out.display())))?;
    let written = pictures::write_pngs(pictures, &args.out, args.scale)
        .map_err(|e| Failed(format!("error: {e}")))?;
    if ctx.json {
        print_json(&written)?;
    } else {
        println!("{what}:");
        for w in &written {
            println!("  {}  {}", w.path, w.description);
        }
    }
    Ok(ExitCode::SUCCESS)
}
