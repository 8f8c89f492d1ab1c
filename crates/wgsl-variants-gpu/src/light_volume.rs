//! Light volumes (docs/shading.md §10, "Light volumes"): how a renderer draws one light of the
//! deferred lighting pass — the mesh that bounds a point or spot light, and the rule that picks
//! a volume draw with the stencil pre-pass or the full-screen triangle.
//!
//! This is the scheme of Unity's built-in deferred path (`Internal-DeferredShading.shader`,
//! `Internal-StencilWrite.shader`): directional lights cover the screen; a point light is drawn
//! as an icosphere and a spot light as a pyramid, after a stencil pass that marks the pixels
//! whose geometry lies in front of the volume; a volume that reaches in front of the near plane
//! (or behind the far plane) is drawn full-screen instead. The meshes are plain world-space
//! triangle lists a renderer can copy into its own vertex buffers. Deferred reflection probes
//! are drawn the same way, as their (grown) boxes ([`probe_draw`]).
//!
//! ```
//! use glam::{Mat4, Vec3};
//! use wgsl_variants_shaders::reference::light::{Light, perspective_rh, look_at_rh};
//! use wgsl_variants_gpu::light_volume::{FullScreenReason, LightDraw, light_draw};
//! let view_proj = perspective_rh(1.0, 1.0, 0.5, 50.0)
//!     * look_at_rh(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y);
//! // A point light in front of the camera: an icosphere with the stencil pre-pass.
//! let near = light_draw(&Light::point(Vec3::ZERO, 2.0, Vec3::ONE), view_proj).unwrap();
//! assert!(matches!(near, LightDraw::Volume(_)));
//! // A point light around the camera: full-screen.
//! let around = light_draw(&Light::point(Vec3::new(0.0, 0.0, 9.0), 2.0, Vec3::ONE), view_proj);
//! assert_eq!(around.unwrap(), LightDraw::FullScreen(FullScreenReason::CrossesNearPlane));
//! // Undefined lights are refused with the light's own error.
//! assert!(light_draw(&Light::point(Vec3::ZERO, 0.0, Vec3::ONE), view_proj).is_err());
//! ```

use glam::{Mat4, Vec3};
use wgsl_variants_shaders::reference::light::{Light, LightError, LightShape, light_frame};
use wgsl_variants_shaders::reference::probe::{Probe, ProbeError};

/// Relative margin between a light's reach and its volume: the mesh lies at least
/// `VOLUME_MARGIN · range` outside every point the light reaches, so a pixel with a non-zero
/// attenuation is never on the edge of the volume's rasterization or depth test.
pub const VOLUME_MARGIN: f32 = 0.05;

/// Subdivisions of the icosahedron for a point light: 1 gives 80 triangles.
pub const ICOSPHERE_SUBDIVISIONS: u32 = 1;

/// Why a light is drawn as a full-screen triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FullScreenReason {
    /// A directional light reaches every pixel.
    Directional,
    /// Part of the volume lies in front of the near plane (this includes a camera inside the
    /// volume): its front faces would be clipped and the stencil pass would not mark them.
    CrossesNearPlane,
    /// Part of the volume lies beyond the far plane: its back faces, which the light draw
    /// rasterizes, would be clipped.
    CrossesFarPlane,
}

/// A light's bounding mesh: a triangle list in world space, three vertices per triangle,
/// counter-clockwise seen from outside (wgpu's default front face), closed and convex.
#[derive(Clone, Debug, PartialEq)]
pub struct LightVolume {
    /// World positions, three per triangle.
    pub positions: Vec<[f32; 3]>,
}

impl LightVolume {
    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.positions.len() / 3
    }

    /// Whether world point `p` lies inside the closed convex mesh (on a face counts as inside).
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::Light;
    /// use wgsl_variants_gpu::light_volume::light_volume;
    /// let v = light_volume(&Light::point(Vec3::ZERO, 1.0, Vec3::ONE)).unwrap().unwrap();
    /// assert!(v.contains(Vec3::new(0.0, 0.0, 0.99)) && !v.contains(Vec3::new(0.0, 0.0, 1.5)));
    /// ```
    pub fn contains(&self, p: Vec3) -> bool {
        self.positions.chunks_exact(3).all(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(Vec3::from);
            (b - a).cross(c - a).dot(p - a) <= 0.0
        })
    }

    /// The vertices' clip positions under `view_proj`.
    fn clip(&self, view_proj: Mat4) -> impl Iterator<Item = glam::Vec4> + '_ {
        self.positions
            .iter()
            .map(move |&p| view_proj * Vec3::from(p).extend(1.0))
    }
}

/// How to draw one light.
#[derive(Clone, Debug, PartialEq)]
pub enum LightDraw {
    /// One full-screen triangle (`deferred_shading/Lighting`'s `vs_main`), no stencil.
    FullScreen(FullScreenReason),
    /// The stencil pre-pass (`internal/stencil_write`) and then the light
    /// (`deferred_shading/Lighting`'s `vs_volume`) over this mesh.
    Volume(LightVolume),
}

/// The mesh bounding `light`'s reach: `None` for a directional light.
///
/// - Point: an icosphere ([`ICOSPHERE_SUBDIVISIONS`]) around the light's position. A polyhedron
///   with its vertices on a sphere of radius `R` lies partly inside that sphere (its faces cut
///   the sphere), so the vertices go at `R = range · (1 + VOLUME_MARGIN) / k` where `k` is the
///   mesh's inradius over circumradius (the smallest distance from the centre to a face plane,
///   ≈ 0.934 for one subdivision, so `R ≈ 1.124 · range`): every face is then at least
///   `range · (1 + VOLUME_MARGIN)` from the light, so the mesh circumscribes the range sphere
///   with the margin.
/// - Spot: a square pyramid with its apex `range · VOLUME_MARGIN` behind the light on the axis,
///   side slopes `tan(angle / 2) · (1 + VOLUME_MARGIN)` and its base at `range ·
///   (1 + VOLUME_MARGIN)` along the axis. The light reaches only points of the cone
///   `|lateral| < axial · tan(angle / 2)` within `range` of the light (so with `axial < range`);
///   the pyramid's square base circumscribes the cone's disk, the apex moved back keeps the
///   cone inside it near the light, and the margins keep every reached point off its faces.
///
/// # Errors
/// The light's [`LightError`] when its parameters make the math undefined
/// ([`Light::params`]).
pub fn light_volume(light: &Light) -> Result<Option<LightVolume>, LightError> {
    light.params()?;
    let positions = match light.shape {
        LightShape::Directional { .. } => return Ok(None),
        LightShape::Point {
            position, range, ..
        } => {
            let unit = icosphere(ICOSPHERE_SUBDIVISIONS);
            let radius = range * (1.0 + VOLUME_MARGIN) / inradius(&unit);
            unit.iter()
                .map(|&p| (position + Vec3::from(p) * radius).to_array())
                .collect()
        }
        LightShape::Spot {
            position,
            direction,
            angle_degrees,
            range,
        } => {
            let (right, up, axis) = light_frame(direction.normalize());
            let slope = (angle_degrees.to_radians() * 0.5).tan() * (1.0 + VOLUME_MARGIN);
            let back = range * VOLUME_MARGIN;
            let apex = position - axis * back;
            let depth = range * (1.0 + VOLUME_MARGIN) + back;
            let half = depth * slope;
            let centre = apex + axis * depth;
            let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
                .map(|(x, y)| centre + right * (x * half) + up * (y * half));
            let mut tris = Vec::new();
            for i in 0..4 {
                tris.push([apex, corners[i], corners[(i + 1) % 4]]);
            }
            tris.push([corners[0], corners[2], corners[1]]);
            tris.push([corners[0], corners[3], corners[2]]);
            outward(tris, apex + axis * (depth * 0.5))
        }
    };
    Ok(Some(LightVolume { positions }))
}

/// How to draw `light` seen through `view_proj` (world to clip, wgpu's depth range [0, 1]):
/// directional lights full-screen; a volume with a vertex in front of the near plane
/// (`clip.z < 0`) or beyond the far plane (`clip.z > clip.w`) full-screen; otherwise the volume
/// with the stencil pre-pass. Clip `z` and `w` are affine in the world position, so checking
/// the vertices of the convex mesh checks all of it; a camera inside the volume is in front of
/// the near plane, so it falls back too.
///
/// # Errors
/// The light's [`LightError`] when its parameters make the math undefined.
pub fn light_draw(light: &Light, view_proj: Mat4) -> Result<LightDraw, LightError> {
    let Some(volume) = light_volume(light)? else {
        return Ok(LightDraw::FullScreen(FullScreenReason::Directional));
    };
    Ok(volume_draw(volume, view_proj))
}

/// The volume, or full screen when part of it lies in front of the near plane or beyond the
/// far plane.
fn volume_draw(volume: LightVolume, view_proj: Mat4) -> LightDraw {
    if volume.clip(view_proj).any(|c| c.z < 0.0 || !c.is_finite()) {
        return LightDraw::FullScreen(FullScreenReason::CrossesNearPlane);
    }
    if volume.clip(view_proj).any(|c| c.z > c.w) {
        return LightDraw::FullScreen(FullScreenReason::CrossesFarPlane);
    }
    LightDraw::Volume(volume)
}

/// The mesh bounding where a deferred reflection probe contributes: its box grown by the
/// blend distance ([`Probe::grown`]; outside it the probe's falloff is 0) and then by
/// [`VOLUME_MARGIN`] of its largest edge, so no pixel with a non-zero falloff is on the
/// mesh's edge. Twelve triangles, counter-clockwise from outside.
///
/// # Errors
/// The probe's [`ProbeError`] when its parameters make the math undefined ([`Probe::check`]).
pub fn probe_volume(probe: &Probe) -> Result<LightVolume, ProbeError> {
    probe.check()?;
    let grown = probe.grown();
    let margin = (grown.box_max - grown.box_min).max_element() * VOLUME_MARGIN;
    let (lo, hi) = (grown.box_min - margin, grown.box_max + margin);
    let corner = |i: usize| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    // Each face as two triangles over its four corners (bits: the fixed axis and side).
    const FACES: [[usize; 4]; 6] = [
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 6, 7, 5],
    ];
    let tris = FACES
        .iter()
        .flat_map(|&[a, b, c, d]| {
            [
                [corner(a), corner(b), corner(c)],
                [corner(a), corner(c), corner(d)],
            ]
        })
        .collect();
    Ok(LightVolume {
        positions: outward(tris, (lo + hi) * 0.5),
    })
}

/// How to draw a deferred reflection probe (`deferred_reflections/Reflections`) seen through
/// `view_proj`: its [`probe_volume`] (`vs_box`, back faces, depth test GreaterEqual: the
/// pixels whose geometry lies in front of the box's far side) — Unity's built-in path draws
/// each probe as its box — or full screen (`vs_main`) when the box reaches in front of the
/// near plane (a camera inside the box, say) or beyond the far plane. The result is the same:
/// outside the grown box the probe's falloff is 0 and its blend leaves the buffer as it is.
///
/// # Errors
/// The probe's [`ProbeError`] when its parameters make the math undefined.
pub fn probe_draw(probe: &Probe, view_proj: Mat4) -> Result<LightDraw, ProbeError> {
    Ok(volume_draw(probe_volume(probe)?, view_proj))
}

/// A unit icosphere: the icosahedron with each triangle split `subdivisions` times into four,
/// every vertex pushed onto the unit sphere; triangle list, counter-clockwise from outside.
fn icosphere(subdivisions: u32) -> Vec<[f32; 3]> {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let v = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .map(|(x, y, z)| Vec3::new(x, y, z).normalize());
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut tris: Vec<[Vec3; 3]> = FACES.iter().map(|f| f.map(|i| v[i])).collect();
    for _ in 0..subdivisions {
        tris = tris
            .into_iter()
            .flat_map(|[a, b, c]| {
                let [ab, bc, ca] = [a + b, b + c, c + a].map(Vec3::normalize);
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    outward(tris, Vec3::ZERO)
}

/// Flattens triangles, each wound so its normal points away from `inside`.
fn outward(tris: Vec<[Vec3; 3]>, inside: Vec3) -> Vec<[f32; 3]> {
    tris.into_iter()
        .flat_map(|[a, b, c]| {
            let facing_out = (b - a).cross(c - a).dot(a - inside) > 0.0;
            let [a, b, c] = if facing_out { [a, b, c] } else { [a, c, b] };
            [a, b, c].map(|v| v.to_array())
        })
        .collect()
}

/// The smallest distance from the origin to a face plane of a mesh around the origin.
fn inradius(positions: &[[f32; 3]]) -> f32 {
    positions
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(Vec3::from);
            (b - a).cross(c - a).normalize().dot(a)
        })
        .fold(f32::INFINITY, f32::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use wgsl_variants_shaders::reference::light::{LightType, look_at_rh, perspective_rh};

    fn closed_and_outward(v: &LightVolume, inside: Vec3) {
        // Every edge is shared by exactly two triangles, in opposite directions.
        let mut edges = std::collections::HashMap::new();
        for t in v.positions.chunks_exact(3) {
            for i in 0..3 {
                let key = (t[i].map(f32::to_bits), t[(i + 1) % 3].map(f32::to_bits));
                *edges.entry(key).or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1);
            assert_eq!(edges.get(&(b, a)), Some(&1), "open edge");
        }
        for t in v.positions.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(Vec3::from);
            assert!((b - a).cross(c - a).dot(a - inside) > 0.0, "inward face");
        }
    }

    #[test]
    fn icosphere_is_closed_and_circumscribes_the_range_with_the_margin() {
        let unit = icosphere(ICOSPHERE_SUBDIVISIONS);
        assert_eq!(unit.len(), 80 * 3);
        let k = inradius(&unit);
        assert!((k - 0.934_172_4).abs() < 1e-5, "inradius ratio {k}");
        let centre = Vec3::new(1.0, -2.0, 3.0);
        let light = Light::point(centre, 2.5, Vec3::ONE);
        let v = light_volume(&light).unwrap().unwrap();
        closed_and_outward(&v, centre);
        let reach = 2.5 * (1.0 + VOLUME_MARGIN);
        assert!(
            (inradius(
                &v.positions
                    .iter()
                    .map(|p| (Vec3::from(*p) - centre).to_array())
                    .collect::<Vec<_>>()
            ) - reach)
                .abs()
                < 1e-4
        );
    }

    #[test]
    fn every_lit_point_is_inside_the_volume() {
        let lights = [
            Light::point(Vec3::new(0.3, 0.1, -0.2), 2.0, Vec3::ONE),
            Light::spot(Vec3::ZERO, Vec3::new(0.3, -1.0, 0.2), 70.0, 3.0, Vec3::ONE),
            Light::spot(Vec3::ONE, Vec3::NEG_Z, 170.0, 1.5, Vec3::ONE),
            Light::spot(Vec3::ONE, Vec3::Y, 5.0, 4.0, Vec3::ONE),
        ];
        for light in lights {
            let params = light.params().unwrap();
            let v = light_volume(&light).unwrap().unwrap();
            let t = match light.shape {
                LightShape::Spot { .. } => LightType::Spot,
                _ => LightType::Point,
            };
            let mut lit = 0;
            // A grid over a cube of side 10 around the origin.
            for i in 0..64_000u32 {
                let g = |n: u32| (n % 40) as f32 / 39.0 * 10.0 - 5.0;
                let p = Vec3::new(g(i), g(i / 40), g(i / 1600));
                if params.sample(t, p, None).1 > 0.0 {
                    lit += 1;
                    assert!(v.contains(p), "{light:?}: lit point {p} outside the volume");
                }
            }
            assert!(lit > 0, "{light:?} lights no grid point");
        }
    }

    #[test]
    fn spot_pyramid_is_closed_and_outward() {
        let light = Light::spot(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), 60.0, 2.0, Vec3::ONE);
        let v = light_volume(&light).unwrap().unwrap();
        assert_eq!(v.triangles(), 6);
        closed_and_outward(&v, Vec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn the_draw_rule() {
        let view_proj = perspective_rh(1.0, 1.0, 0.5, 20.0)
            * look_at_rh(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y);
        let draw = |l: Light| light_draw(&l, view_proj).unwrap();
        assert_eq!(
            draw(Light::directional(Vec3::NEG_Z, Vec3::ONE)),
            LightDraw::FullScreen(FullScreenReason::Directional)
        );
        assert!(matches!(
            draw(Light::point(Vec3::ZERO, 2.0, Vec3::ONE)),
            LightDraw::Volume(_)
        ));
        // Around the camera, crossing the near plane only, behind the camera, beyond far.
        for p in [
            Vec3::new(0.0, 0.0, 10.0),
            Vec3::new(0.0, 0.0, 8.0),
            Vec3::new(0.0, 0.0, 15.0),
        ] {
            assert_eq!(
                draw(Light::point(p, 2.0, Vec3::ONE)),
                LightDraw::FullScreen(FullScreenReason::CrossesNearPlane),
                "{p}"
            );
        }
        assert_eq!(
            draw(Light::point(Vec3::new(0.0, 0.0, -9.5), 2.0, Vec3::ONE)),
            LightDraw::FullScreen(FullScreenReason::CrossesFarPlane)
        );
        // A spot pointing at the camera from afar reaches it: fallback.
        assert_eq!(
            draw(Light::spot(Vec3::ZERO, Vec3::Z, 40.0, 11.0, Vec3::ONE)),
            LightDraw::FullScreen(FullScreenReason::CrossesNearPlane)
        );
        assert!(matches!(
            draw(Light::spot(Vec3::ZERO, Vec3::NEG_Z, 40.0, 3.0, Vec3::ONE)),
            LightDraw::Volume(_)
        ));
    }

    #[test]
    fn undefined_lights_are_refused() {
        let vp = Mat4::IDENTITY;
        let bad = [
            Light::point(Vec3::ZERO, 0.0, Vec3::ONE),
            Light::point(Vec3::NAN, 1.0, Vec3::ONE),
            Light::spot(Vec3::ZERO, Vec3::Z, 180.0, 1.0, Vec3::ONE),
            Light::spot(Vec3::ZERO, Vec3::ZERO, 30.0, 1.0, Vec3::ONE),
        ];
        for l in bad {
            assert!(light_draw(&l, vp).is_err(), "{l:?}");
            assert!(light_volume(&l).is_err(), "{l:?}");
        }
    }
}
