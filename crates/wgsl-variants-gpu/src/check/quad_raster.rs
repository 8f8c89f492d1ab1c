//! The reference rasterizer of the URP scene's quad for the depth-writing passes' checks
//! (`universal_lit/ShadowCaster`, `universal_lit/DepthOnly`): the quad's two triangles, each
//! vertex placed in clip space by the pass under test's own formula, rasterized at texel
//! centres (depth affine in screen space, uv perspective-correct) with URP's alpha test
//! against the base map's texel at that uv. Texels within a hair of a triangle edge, of a
//! base-map texel edge or of a clip plane are [`Expected::Edge`]: left to the rasterizer.

use glam::{Vec2, Vec3, Vec4};
use wgsl_variants_shaders::reference::tolerance::SUBPIXEL_WINDOW;

use super::scene::MapTexture;
use super::urp::UrpScene;

/// Barycentric margin: texel centres closer than this to a triangle edge are not compared.
const EDGE_MARGIN: f32 = 1e-4;

/// Texel margin: a uv closer than this (in base-map texels) to a texel edge is not compared.
const UV_MARGIN: f32 = 1e-3;

/// Depth margin: a depth closer than this to a clip plane is not compared.
const DEPTH_MARGIN: f32 = 1e-4;

/// What the reference says of one texel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Expected {
    /// The quad's depth there.
    Depth {
        /// At the texel's centre.
        depth: f32,
        /// How far the depth moves within the rasterizer's sub-pixel snapping
        /// ([`SUBPIXEL_WINDOW`] of a texel either way, along each axis).
        window: f32,
    },
    /// Nothing drawn (not covered, clipped or discarded): the clear value.
    Clear,
    /// Within a hair of an edge: not compared.
    Edge,
}

/// URP's `Alpha()` as the depth passes run it: the keywords and the material's values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AlphaTest<'a> {
    /// `_ALPHATEST_ON`: discard where alpha < `cutoff`.
    on: bool,
    /// `_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A`: alpha is `_BaseColor.a` alone.
    albedo_alpha_smoothness: bool,
    /// The base map.
    base: &'a MapTexture,
    /// `_BaseColor.a`.
    base_alpha: f32,
    /// `_Cutoff`.
    cutoff: f32,
}

impl AlphaTest<'_> {
    /// The alpha test of `urp`'s material under the two keywords.
    pub(crate) fn of(urp: &UrpScene, on: bool, albedo_alpha_smoothness: bool) -> AlphaTest<'_> {
        AlphaTest {
            on,
            albedo_alpha_smoothness,
            base: &urp.scene.maps.main_tex,
            base_alpha: urp.material.base_color.w,
            cutoff: urp.material.cutoff,
        }
    }
}

/// The reference depth map of `urp`'s quad, `size` texels, each vertex (world position,
/// unit world normal) placed in clip space by `place`, which also says whether the vertex was
/// pancaked onto the near plane; with `near_clip` the GPU clips at depth 0 (nothing pancaked).
/// Also returns how many depth texels lie on a triangle with a pancaked vertex.
pub(crate) fn rasterize_quad(
    urp: &UrpScene,
    place: impl Fn(Vec3, Vec3) -> (Vec4, bool),
    (width, height): (u32, u32),
    alpha: AlphaTest<'_>,
    near_clip: bool,
) -> (Vec<Expected>, usize) {
    let s = &urp.scene;
    let n = (s.normal_matrix * s.object_normal.extend(0.0))
        .truncate()
        .normalize();
    // Object corners and uvs as the quad's vertex buffer (top-left is uv (0, 0)).
    let corner = |ox: f32, oy: f32| {
        let p = (s.model * Vec4::new(ox, oy, 0.0, 1.0)).truncate();
        let (clip, pancaked) = place(p, n);
        let ndc = clip.truncate() / clip.w;
        (
            Vec2::new(
                (ndc.x * 0.5 + 0.5) * width as f32,
                (0.5 - ndc.y * 0.5) * height as f32,
            ),
            ndc.z,
            1.0 / clip.w,
            Vec2::new((ox + 1.0) * 0.5, (1.0 - oy) * 0.5),
            pancaked,
        )
    };
    let (tl, tr, bl, br) = (
        corner(-1.0, 1.0),
        corner(1.0, 1.0),
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
    );
    let triangles = [[tl, bl, tr], [tr, bl, br]];
    let base = alpha.base;
    let mut pancaked = 0usize;
    let map = (0..width * height)
        .map(|i| {
            let c = Vec2::new((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
            let mut out = Expected::Clear;
            for t in &triangles {
                let cross = |a: Vec2, b: Vec2, p: Vec2| (b - a).perp_dot(p - a);
                let area = cross(t[0].0, t[1].0, t[2].0);
                if area.abs() < 1e-12 {
                    continue;
                }
                let bary = |c: Vec2| {
                    [
                        cross(t[1].0, t[2].0, c) / area,
                        cross(t[2].0, t[0].0, c) / area,
                        cross(t[0].0, t[1].0, c) / area,
                    ]
                };
                let depth_at = |b: [f32; 3]| (0..3).map(|k| b[k] * t[k].1).sum::<f32>();
                let b = bary(c);
                if b.iter().any(|&x| x < -EDGE_MARGIN) {
                    continue;
                }
                if b.iter().any(|&x| x < EDGE_MARGIN) {
                    return Expected::Edge;
                }
                let depth = depth_at(b);
                // Beyond a clip plane the GPU clips; at it, either way.
                if depth > 1.0 + DEPTH_MARGIN || (near_clip && depth < -DEPTH_MARGIN) {
                    continue;
                }
                if depth > 1.0 - DEPTH_MARGIN || (near_clip && depth < DEPTH_MARGIN) {
                    return Expected::Edge;
                }
                let inv_w: f32 = (0..3).map(|k| b[k] * t[k].2).sum();
                let uv = (0..3).map(|k| t[k].3 * b[k] * t[k].2).sum::<Vec2>() / inv_w;
                let texel = uv * Vec2::new(base.width as f32, base.height as f32);
                let frac = texel - texel.floor();
                if alpha.on
                    && (frac.min_element() < UV_MARGIN || frac.max_element() > 1.0 - UV_MARGIN)
                {
                    return Expected::Edge;
                }
                let a = if alpha.albedo_alpha_smoothness {
                    alpha.base_alpha
                } else {
                    let tx = (texel.x.floor() as u32).min(base.width - 1);
                    let ty = (texel.y.floor() as u32).min(base.height - 1);
                    base.get(tx, ty).w * alpha.base_alpha
                };
                out = if alpha.on && a < alpha.cutoff {
                    Expected::Clear
                } else {
                    pancaked += usize::from(t.iter().any(|v| v.4));
                    // Depth is affine across the triangle: its steps along x and y.
                    let dx = depth_at(bary(c + Vec2::X)) - depth;
                    let dy = depth_at(bary(c + Vec2::Y)) - depth;
                    Expected::Depth {
                        depth,
                        window: (dx.abs() + dy.abs()) * SUBPIXEL_WINDOW,
                    }
                };
            }
            out
        })
        .collect();
    (map, pancaked)
}
