//! Draws limited to a volume, shared by the light volumes and the deferred probes' boxes: the
//! scene's depth written into the pass's depth buffer first, then a draw over the volume's
//! back faces where the scene lies in front of them.

use std::sync::Arc;

use crate::light_volume::LightVolume;
use crate::{BoundResource, DepthTest, Draw, Resource, StencilTest, VertexBuffer};

/// Writes the rig's depth (an `R32Float` texture) into the depth attachment.
pub(crate) const DEPTH_FILL_WGSL: &str = "
@group(0) @binding(0) var scene_depth: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) p: vec4f) -> @builtin(frag_depth) f32 {
    return textureLoad(scene_depth, vec2i(floor(p.xy)), 0).r;
}
";

/// The first draw of a pass whose volumes test the scene's depth: writes `depth` (an
/// `R32Float` texture of the scene's depth) into the pass's depth buffer, no colour.
pub(crate) fn depth_fill_draw(depth: Resource) -> Draw {
    let fill: Arc<str> = Arc::from(DEPTH_FILL_WGSL);
    Draw::fullscreen("scene depth", &fill, "vs_main", "fs_main")
        .with_resources(vec![BoundResource::new(0, 0, depth)])
        .with_depth(DepthTest {
            compare: wgpu::CompareFunction::Always,
            write: true,
        })
        .depth_only()
}

/// Sets a stencil bit where an `R8Uint` texture of stencil values has it.
const STENCIL_FILL_WGSL: &str = "
@group(0) @binding(0) var marks: texture_2d<u32>;
@group(0) @binding(1) var<uniform> bit: vec4u;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) p: vec4f) {
    if (textureLoad(marks, vec2i(floor(p.xy)), 0).r & bit.x) == 0u {
        discard;
    }
}
";

/// A draw of a pass with a stencil buffer that sets stencil bit `bit` where `marks` (an
/// `R8Uint` texture of an earlier pass's stencil values) has it: how a pass that reads its
/// depth from a texture ([`depth_fill_draw`]) gets an earlier pass's stencil marks too. No
/// depth test, no colour.
pub(crate) fn stencil_fill_draw(marks: Resource, bit: u32) -> Draw {
    let fill: Arc<str> = Arc::from(STENCIL_FILL_WGSL);
    let mut uniform = [0u8; 16];
    uniform[..4].copy_from_slice(&bit.to_le_bytes());
    Draw::fullscreen("scene stencil", &fill, "vs_main", "fs_main")
        .with_resources(vec![
            BoundResource::new(0, 0, marks),
            BoundResource::new(0, 1, Resource::Uniform(uniform.to_vec())),
        ])
        .with_stencil(StencilTest::set(bit))
        .depth_only()
}

/// `draw` over `volume` instead of full screen: the vertex entry `entry` (world positions at
/// `@location(0)`), back faces, depth test GreaterEqual without writes — the pixels whose
/// surface lies in front of the volume's far side.
pub(crate) fn over_volume(draw: Draw, entry: &str, volume: &LightVolume) -> Draw {
    Draw {
        vertex_entry: entry.to_owned(),
        ..draw
            .with_mesh(VertexBuffer::from_f32(&[(0, 3)], &volume.positions))
            .with_cull(wgpu::Face::Front)
            .with_depth(DepthTest {
                compare: wgpu::CompareFunction::GreaterEqual,
                write: false,
            })
    }
}
