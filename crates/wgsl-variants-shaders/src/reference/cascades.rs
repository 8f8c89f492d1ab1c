//! A directional light's cascaded shadow map as Unity's screen-space shadow collector reads it
//! (`Internal-ScreenSpaceShadows.shader` with `UnityShadowLibrary.cginc`; docs/shading.md §11):
//! the camera's view split into 1, 2 or 4 slices by view depth, each slice's own orthographic
//! shadow view rendered into one tile of an atlas, and per pixel the cascade picked by the
//! slice its view depth falls in (`_LightSplitsNear` / `_LightSplitsFar`) or, with
//! `SHADOWS_SPLIT_SPHERES`, by the first of the slices' bounding spheres that holds it
//! (`unity_ShadowSplitSpheres`, `unity_ShadowSplitSqRadii`; each weight minus the previous
//! sphere's, as Unity writes it). `SHADOWS_SINGLE_CASCADE` reads cascade 0 without selecting. A
//! pixel in no cascade is lit (Unity moves its coordinate in front of every caster).
//!
//! The WGSL is `lighting/cascades`; [`Cascades::uniform`] is its `CascadedShadow` record.

use glam::{Mat4, Vec3, Vec4};

use super::light::Light;
use super::shadow::{
    ShadowError, ShadowMap2d, ShadowParams, atlas_tile, lit_beyond_shadow_far, shadow_coords,
    shadow_mix,
};

/// Most cascades (Unity's four).
pub const MAX_CASCADES: usize = 4;

/// How close (relative) a view depth or squared distance may come to a split before the
/// cascade picked there counts as uncertain: the GPU rebuilds the position from the depth
/// buffer in f32, as the reference does, but not in the same order of operations.
pub const SPLIT_MARGIN: f32 = 1e-4;

/// The keywords of Unity's `multi_compile_shadowcollector`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CascadeKeywords {
    /// `SHADOWS_SINGLE_CASCADE`: read cascade 0, select nothing.
    pub single: bool,
    /// `SHADOWS_SPLIT_SPHERES`: select by the slices' bounding spheres, not by view depth.
    pub split_spheres: bool,
    /// `SHADOWS_SOFT`: the 3 × 3 tent of each cascade's tile.
    pub soft: bool,
    /// URP's `BEYOND_SHADOW_FAR`: a coordinate outside the light's depth range reads as lit
    /// ([`lit_beyond_shadow_far`]); Unity's collector has no such test.
    pub lit_beyond_far: bool,
}

impl CascadeKeywords {
    /// The collector's keywords among `names` (others ignored).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::cascades::CascadeKeywords;
    /// let k = CascadeKeywords::of(&["SHADOWS_SPLIT_SPHERES", "SHADOWS_SOFT"]);
    /// assert!(k.split_spheres && k.soft && !k.single);
    /// ```
    pub fn of(names: &[&str]) -> CascadeKeywords {
        CascadeKeywords {
            single: names.contains(&"SHADOWS_SINGLE_CASCADE"),
            split_spheres: names.contains(&"SHADOWS_SPLIT_SPHERES"),
            soft: names.contains(&"SHADOWS_SOFT"),
            lit_beyond_far: false,
        }
    }

    /// URP's selection (`ComputeCascadeIndex` in URP's `Shadows.hlsl`): always by the split
    /// spheres, never one cascade alone, lit beyond the light's depth range
    /// (`SampleShadowmap`'s `BEYOND_SHADOW_FAR`); `soft`: `_SHADOWS_SOFT`.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::cascades::CascadeKeywords;
    /// let k = CascadeKeywords::urp(true);
    /// assert!(k.split_spheres && k.soft && !k.single && k.lit_beyond_far);
    /// ```
    pub fn urp(soft: bool) -> CascadeKeywords {
        CascadeKeywords {
            single: false,
            split_spheres: true,
            soft,
            lit_beyond_far: true,
        }
    }
}

/// The camera a cascade set is fitted to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CascadeCamera {
    /// Its world position.
    pub position: Vec3,
    /// Its view direction (normalized by [`Cascades::fit`]).
    pub forward: Vec3,
    /// Its inverse view-projection (clip to world), for the frustum's corners.
    pub inv_view_proj: Mat4,
}

impl CascadeCamera {
    /// The camera at `position` whose world-to-clip transform is `view_proj` (depth 0 to 1):
    /// its forward axis points from `position` to the centre of the screen at mid depth.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::cascades::CascadeCamera;
    /// use wgsl_variants_shaders::reference::light::{look_at_rh, perspective_rh};
    /// let eye = Vec3::new(0.0, 2.0, 5.0);
    /// let view_proj = perspective_rh(0.8, 1.5, 0.5, 20.0) * look_at_rh(eye, Vec3::ZERO, Vec3::Y);
    /// let camera = CascadeCamera::from_view_proj(eye, view_proj);
    /// assert!((camera.forward - (-eye).normalize()).length() < 1e-5);
    /// ```
    pub fn from_view_proj(position: Vec3, view_proj: Mat4) -> CascadeCamera {
        let inv_view_proj = view_proj.inverse();
        let q = inv_view_proj * Vec4::new(0.0, 0.0, 0.5, 1.0);
        CascadeCamera {
            position,
            forward: (q.truncate() / q.w - position).normalize(),
            inv_view_proj,
        }
    }
}

/// One cascade: its slice of the view and its view into the atlas.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascade {
    /// The view depths `[near, far)` of its slice.
    pub splits: (f32, f32),
    /// The slice's bounding sphere: centre and radius.
    pub sphere: (Vec3, f32),
    /// Its shadow view, `world_to_shadow` into its tile of the atlas ([`Cascades::tile`]).
    pub params: ShadowParams,
    /// The same view into a whole map of its own (what the caster pass renders).
    pub view_proj: Mat4,
}

/// 1, 2 or 4 cascades of one directional light.
#[derive(Clone, Debug, PartialEq)]
pub struct Cascades {
    /// The cascades, nearest first.
    pub cascades: Vec<Cascade>,
    /// The camera's forward axis and `dot(forward, position)`: view depth = `dot(p, xyz) − w`.
    pub view_axis: Vec4,
}

impl Cascades {
    /// Fits one cascade per slice `[splits[i], splits[i + 1])` of `camera`'s view: the slice's
    /// bounding sphere (around its eight frustum corners) and the light's orthographic view
    /// around it ([`ShadowParams::for_directional`]), placed in tile `i` of the atlas.
    ///
    /// # Errors
    /// Not 2, 3 or 5 split depths (1, 2 or 4 cascades), depths not increasing from above 0,
    /// or what [`ShadowParams::for_directional`] refuses.
    pub fn fit(
        light: &Light,
        strength: f32,
        bias: f32,
        camera: &CascadeCamera,
        splits: &[f32],
    ) -> Result<Cascades, ShadowError> {
        let count = splits.len().saturating_sub(1);
        let increasing = splits.windows(2).all(|w| w[0] < w[1]);
        if ![1, 2, 4].contains(&count) || !increasing || splits[0] <= 0.0 {
            return Err(ShadowError::Cascades(splits.to_vec()));
        }
        let forward = camera.forward.normalize();
        let mut cascades = Vec::with_capacity(count);
        for (i, w) in splits.windows(2).enumerate() {
            let corners = slice_corners(camera, forward, w[0], w[1]);
            let center = corners.iter().sum::<Vec3>() / 8.0;
            let radius = corners
                .iter()
                .map(|c| c.distance(center))
                .fold(0.0, f32::max);
            let params = ShadowParams::for_directional(light, strength, bias, center, radius)?;
            let view_proj = params.world_to_shadow;
            cascades.push(Cascade {
                splits: (w[0], w[1]),
                sphere: (center, radius),
                params: ShadowParams {
                    world_to_shadow: Cascades::tile(count, i) * view_proj,
                    ..params
                },
                view_proj,
            });
        }
        Ok(Cascades {
            cascades,
            view_axis: forward.extend(forward.dot(camera.position)),
        })
    }

    /// URP's cascades as its shader sees them (`_MAIN_LIGHT_SHADOWS_CASCADE`): one per split
    /// sphere `(centre, radius)`, the light's orthographic view around it
    /// ([`ShadowParams::for_directional`]) in tile `i` of the atlas. URP's host derives the
    /// spheres from its split ratios; its shader reads only the spheres and the matrices, so a
    /// check may place them where they split its pixels. No view-depth slices: select with
    /// `split_spheres` ([`CascadeKeywords`]).
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades};
    /// use wgsl_variants_shaders::reference::light::Light;
    /// let sun = Light::directional(Vec3::NEG_Z, Vec3::ONE);
    /// let rings = [(Vec3::ZERO, 1.0), (Vec3::ZERO, 2.0)];
    /// let c = Cascades::from_spheres(&sun, 0.8, 0.0, &rings).unwrap();
    /// let spheres = CascadeKeywords { split_spheres: true, ..CascadeKeywords::default() };
    /// let pick = |p: Vec3| Cascades::picked(c.candidates(spheres, p)[0].unwrap());
    /// // The first sphere that holds the point; none beyond the last.
    /// assert_eq!(pick(Vec3::new(0.5, 0.0, 0.0)), 0);
    /// assert_eq!(pick(Vec3::new(1.5, 0.0, 0.0)), 1);
    /// assert_eq!(pick(Vec3::new(2.5, 0.0, 0.0)), 4);
    /// ```
    ///
    /// # Errors
    /// Not 1 to 4 spheres ([`ShadowError::SplitSpheres`]), or what
    /// [`ShadowParams::for_directional`] refuses.
    pub fn from_spheres(
        light: &Light,
        strength: f32,
        bias: f32,
        spheres: &[(Vec3, f32)],
    ) -> Result<Cascades, ShadowError> {
        if !(1..=MAX_CASCADES).contains(&spheres.len()) {
            return Err(ShadowError::SplitSpheres(spheres.len()));
        }
        let count = spheres.len();
        let mut cascades = Vec::with_capacity(count);
        for (i, &(center, radius)) in spheres.iter().enumerate() {
            let params = ShadowParams::for_directional(light, strength, bias, center, radius)?;
            cascades.push(Cascade {
                splits: (0.0, 0.0),
                sphere: (center, radius),
                params: ShadowParams {
                    world_to_shadow: Cascades::tile(count, i) * params.world_to_shadow,
                    ..params
                },
                view_proj: params.world_to_shadow,
            });
        }
        Ok(Cascades {
            cascades,
            view_axis: Vec4::ZERO,
        })
    }

    /// One cascade over a whole map of its own: `params`'s view (what a light with
    /// `SHADOWS_SINGLE_CASCADE` binds), covering every depth and every point.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades};
    /// use wgsl_variants_shaders::reference::light::Light;
    /// use wgsl_variants_shaders::reference::shadow::ShadowParams;
    /// let sun = Light::directional(Vec3::NEG_Y, Vec3::ONE);
    /// let params = ShadowParams::for_directional(&sun, 0.8, 0.001, Vec3::ZERO, 5.0).unwrap();
    /// let one = Cascades::single(&params);
    /// let far = Vec3::new(0.0, 0.0, -1000.0);
    /// let w = one.candidates(CascadeKeywords::default(), far)[0].unwrap();
    /// assert_eq!(Cascades::picked(w), 0);
    /// assert_eq!(&one.uniform()[..16], &params.world_to_shadow.to_cols_array());
    /// ```
    pub fn single(params: &ShadowParams) -> Cascades {
        // Far enough for any scene, small enough to square in f32.
        const ALL: f32 = 1e18;
        Cascades {
            cascades: vec![Cascade {
                splits: (-ALL, ALL),
                sphere: (Vec3::ZERO, ALL),
                params: *params,
                view_proj: params.world_to_shadow,
            }],
            view_axis: Vec4::new(0.0, 0.0, 1.0, 0.0),
        }
    }

    /// The atlas's tiles across and down for `count` cascades: 1 × 1, 2 × 1 or 2 × 2 (3
    /// cascades leave the last tile empty).
    pub fn grid(count: usize) -> (u32, u32) {
        match count {
            1 => (1, 1),
            2 => (2, 1),
            _ => (2, 2),
        }
    }

    /// The clip-space transform that puts a whole map's view into tile `i` of the atlas
    /// (row-major tiles, [`Cascades::grid`]): texture coordinates `uv · size + offset`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::cascades::Cascades;
    /// use wgsl_variants_shaders::reference::shadow::shadow_coords;
    /// // The map's centre lands in the centre of tile 3 (bottom right) of a 2 × 2 atlas.
    /// let c = shadow_coords(Cascades::tile(4, 3), Vec3::new(0.0, 0.0, 0.5));
    /// assert_eq!((c.x, c.y, c.z), (0.75, 0.75, 0.5));
    /// ```
    pub fn tile(count: usize, i: usize) -> Mat4 {
        atlas_tile(Cascades::grid(count), i)
    }

    /// The view depth of `p`.
    pub fn view_depth(&self, p: Vec3) -> f32 {
        p.dot(self.view_axis.truncate()) - self.view_axis.w
    }

    /// The weights Unity's collector gives the cascades at `p`, given its view depth `z` and
    /// the squared distances `d2` to the spheres' centres (nudged by the caller to find the
    /// uncertain ones): one-hot, or zero where no cascade holds `p`. `None` with
    /// `SHADOWS_SINGLE_CASCADE` (cascade 0, nothing weighed).
    fn weights(&self, keywords: CascadeKeywords, z: f32, d2: &[f32]) -> Option<[f32; 4]> {
        if keywords.single {
            return None;
        }
        let mut w = [0.0; MAX_CASCADES];
        for (i, c) in self.cascades.iter().enumerate() {
            w[i] = if keywords.split_spheres {
                f32::from(u8::from(d2[i] < c.sphere.1 * c.sphere.1))
            } else {
                f32::from(u8::from(z >= c.splits.0 && z < c.splits.1))
            };
        }
        if keywords.split_spheres {
            // weights.yzw = saturate(weights.yzw − weights.xyz), from the unsubtracted values.
            let s = w;
            for i in 1..MAX_CASCADES {
                w[i] = (s[i] - s[i - 1]).clamp(0.0, 1.0);
            }
        }
        Some(w)
    }

    /// The weights `p` may get: those at `p`, and those with the view depth or the squared
    /// distances moved by [`SPLIT_MARGIN`] (relative) either way. `None`:
    /// `SHADOWS_SINGLE_CASCADE`.
    pub fn candidates(&self, keywords: CascadeKeywords, p: Vec3) -> Vec<Option<[f32; 4]>> {
        let z = self.view_depth(p);
        let d2: Vec<f32> = self
            .cascades
            .iter()
            .map(|c| p.distance_squared(c.sphere.0))
            .collect();
        let mut out = Vec::new();
        for s in [0.0, -SPLIT_MARGIN, SPLIT_MARGIN] {
            let nudged: Vec<f32> = d2.iter().map(|d| d * (1.0 + s)).collect();
            let w = self.weights(keywords, z + s * z.abs().max(1.0), &nudged);
            if !out.contains(&w) {
                out.push(w);
            }
        }
        out
    }

    /// The atlas coordinate the collector reads for `p` with `weights`
    /// ([`Cascades::candidates`]): `Σ w_i · coords_i(p)`, or cascade 0's for `None`.
    pub fn coords(&self, weights: Option<[f32; 4]>, p: Vec3) -> Vec3 {
        let coords = |i: usize| shadow_coords(self.cascades[i].params.world_to_shadow, p);
        match weights {
            None => coords(0),
            Some(w) => (0..self.cascades.len())
                .filter(|&i| w[i] != 0.0)
                .map(|i| coords(i) * w[i])
                .sum(),
        }
    }

    /// The shadow factor at `p` as an interval, from `atlas` (the tiles as rendered, read
    /// back): over every candidate weighting ([`Cascades::candidates`]), the tap interval of
    /// [`ShadowMap2d::visibility`] at its coordinate ([`Cascades::coords`]; no cascade reads
    /// `(0, 0, 0)`, in front of every caster: lit), mixed by the strength; with
    /// [`CascadeKeywords::lit_beyond_far`], lit outside the light's depth range.
    pub fn factor(&self, keywords: CascadeKeywords, atlas: &ShadowMap2d, p: Vec3) -> (f32, f32) {
        let first = &self.cascades[0].params;
        let mut lo = f32::INFINITY;
        let mut hi = f32::NEG_INFINITY;
        for w in self.candidates(keywords, p) {
            let c = self.coords(w, p);
            let v = atlas.visibility(Vec3::new(c.x, c.y, c.z - first.bias), keywords.soft);
            let mut f = (
                shadow_mix(first.strength, v.lo),
                shadow_mix(first.strength, v.hi),
            );
            if keywords.lit_beyond_far {
                f = lit_beyond_shadow_far(c.z, f);
            }
            lo = lo.min(f.0);
            hi = hi.max(f.1);
        }
        (lo, hi)
    }

    /// The index of the one cascade `weights` pick, [`MAX_CASCADES`] for none, and
    /// `MAX_CASCADES + 1` for more than one (overlapping spheres Unity's subtraction does not
    /// separate).
    pub fn picked(weights: [f32; 4]) -> usize {
        let on: Vec<usize> = (0..MAX_CASCADES).filter(|&i| weights[i] != 0.0).collect();
        match on.as_slice() {
            [] => MAX_CASCADES,
            [i] => *i,
            _ => MAX_CASCADES + 1,
        }
    }

    /// The WGSL `CascadedShadow` record as 100 floats (a 400-byte uniform): the four
    /// `world_to_shadow` matrices (column-major; unused cascades repeat the last), the split
    /// spheres (centre, 0), their squared radii, the split depths near and far (unused
    /// cascades: the empty range at the last far depth, radius 0), the view axis, and
    /// `(strength, bias, 0, 0)`.
    pub fn uniform(&self) -> Vec<f32> {
        let last = self.cascades[self.cascades.len() - 1];
        let at = |i: usize| self.cascades.get(i).copied();
        let mut out = Vec::with_capacity(100);
        for i in 0..MAX_CASCADES {
            let m = at(i).map_or(last.params.world_to_shadow, |c| c.params.world_to_shadow);
            out.extend(m.to_cols_array());
        }
        for i in 0..MAX_CASCADES {
            let centre = at(i).map_or(last.sphere.0, |c| c.sphere.0);
            out.extend(centre.extend(0.0).to_array());
        }
        out.extend((0..MAX_CASCADES).map(|i| at(i).map_or(0.0, |c| c.sphere.1 * c.sphere.1)));
        let end = last.splits.1;
        out.extend((0..MAX_CASCADES).map(|i| at(i).map_or(end, |c| c.splits.0)));
        out.extend((0..MAX_CASCADES).map(|i| at(i).map_or(end, |c| c.splits.1)));
        out.extend(self.view_axis.to_array());
        out.extend([last.params.strength, last.params.bias, 0.0, 0.0]);
        out
    }
}

/// The eight world-space corners of `camera`'s frustum between view depths `near` and `far`.
fn slice_corners(camera: &CascadeCamera, forward: Vec3, near: f32, far: f32) -> [Vec3; 8] {
    let mut out = [Vec3::ZERO; 8];
    let mut n = 0;
    for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        // Any point on the corner's ray, then along it to each depth.
        let q = camera.inv_view_proj * Vec4::new(x, y, 0.5, 1.0);
        let ray = q.truncate() / q.w - camera.position;
        let along = ray.dot(forward);
        for depth in [near, far] {
            out[n] = camera.position + ray * (depth / along);
            n += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::light::{look_at_rh, perspective_rh};

    fn camera() -> CascadeCamera {
        let position = Vec3::new(0.0, 2.0, 6.0);
        let view_proj =
            perspective_rh(1.0, 1.0, 0.1, 50.0) * look_at_rh(position, Vec3::ZERO, Vec3::Y);
        CascadeCamera {
            position,
            forward: (Vec3::ZERO - position).normalize(),
            inv_view_proj: view_proj.inverse(),
        }
    }

    fn sun() -> Light {
        Light::directional(Vec3::new(-0.3, -1.0, -0.2), Vec3::ONE)
    }

    #[test]
    fn slices_hold_their_corners_and_tiles_split_the_atlas() {
        let c = Cascades::fit(&sun(), 0.8, 0.001, &camera(), &[0.5, 2.0, 4.0, 7.0, 12.0]).unwrap();
        assert_eq!(c.cascades.len(), 4);
        let cam = camera();
        for (i, k) in c.cascades.iter().enumerate() {
            let f = cam.forward.normalize();
            for corner in slice_corners(&cam, f, k.splits.0, k.splits.1) {
                // Every corner is inside the sphere and lands inside the cascade's own tile.
                assert!(corner.distance(k.sphere.0) <= k.sphere.1 * (1.0 + 1e-5));
                let uv = shadow_coords(k.params.world_to_shadow, corner);
                let (tx, ty) = ((i % 2) as f32 * 0.5, (i / 2) as f32 * 0.5);
                assert!((tx..=tx + 0.5).contains(&uv.x) && (ty..=ty + 0.5).contains(&uv.y));
                assert!((0.0..=1.0).contains(&uv.z));
                // And its depth along the view axis is the slice's.
                let z = c.view_depth(corner);
                assert!(z >= k.splits.0 - 1e-4 && z <= k.splits.1 + 1e-4);
            }
        }
    }

    #[test]
    fn picks_by_depth_or_by_sphere_and_none_beyond() {
        let c = Cascades::fit(&sun(), 0.8, 0.001, &camera(), &[0.5, 2.0, 4.0, 7.0, 12.0]).unwrap();
        let cam = camera();
        let f = cam.forward.normalize();
        let planes = CascadeKeywords::default();
        let spheres = CascadeKeywords {
            split_spheres: true,
            ..planes
        };
        let pick = |k: CascadeKeywords, p: Vec3| -> Vec<usize> {
            c.candidates(k, p)
                .into_iter()
                .map(|w| Cascades::picked(w.unwrap()))
                .collect()
        };
        for (i, depth) in [1.0, 3.0, 5.5, 9.0].into_iter().enumerate() {
            let p = cam.position + f * depth;
            assert_eq!(pick(planes, p), [i]);
            // On the axis, the slice's own sphere or an earlier (overlapping) one.
            let s = pick(spheres, p);
            assert!(s.len() == 1 && s[0] <= i, "{s:?}");
            // The coordinate is the picked cascade's.
            let w = c.candidates(planes, p)[0];
            let own = shadow_coords(c.cascades[i].params.world_to_shadow, p);
            assert_eq!(c.coords(w, p), own);
        }
        let beyond = cam.position + f * 20.0;
        assert_eq!(pick(planes, beyond), [MAX_CASCADES]);
        assert_eq!(pick(spheres, beyond), [MAX_CASCADES]);
        assert_eq!(
            c.coords(c.candidates(planes, beyond)[0], beyond),
            Vec3::ZERO
        );
        // Exactly on a split, both sides are candidates.
        let split = cam.position + f * 4.0;
        let both = pick(planes, split);
        assert!(both.contains(&1) && both.contains(&2), "{both:?}");
        // Single cascade weighs nothing and reads cascade 0 anywhere.
        let single = CascadeKeywords {
            single: true,
            ..planes
        };
        assert_eq!(c.candidates(single, beyond), [None]);
        let own = shadow_coords(c.cascades[0].params.world_to_shadow, beyond);
        assert_eq!(c.coords(None, beyond), own);
        // Unity's subtraction separates nested spheres only: in 0 and 2, not 1, two weights.
        let w = c.weights(spheres, 0.0, &[0.0, 1e9, 0.0, 1e9]).unwrap();
        assert_eq!(w, [1.0, 0.0, 1.0, 0.0]);
        assert_eq!(Cascades::picked(w), MAX_CASCADES + 1);
    }

    #[test]
    fn uniform_layout() {
        let c = Cascades::fit(&sun(), 0.8, 0.001, &camera(), &[0.5, 3.0, 12.0]).unwrap();
        let u = c.uniform();
        assert_eq!(u.len(), 100);
        // Cascades 2 and 3 repeat cascade 1's matrix and centre, radius 0, empty ranges.
        assert_eq!(&u[32..48], &u[48..64]);
        assert_eq!(u[64 + 4 * 4 + 2], 0.0);
        assert_eq!(&u[84..88], &[0.5, 3.0, 12.0, 12.0]);
        assert_eq!(&u[88..92], &[3.0, 12.0, 12.0, 12.0]);
        assert_eq!(&u[96..], &[0.8, 0.001, 0.0, 0.0]);
        assert!(Cascades::fit(&sun(), 0.8, 0.001, &camera(), &[0.5, 3.0, 2.0]).is_err());
        assert!(Cascades::fit(&sun(), 0.8, 0.001, &camera(), &[0.5, 1.0, 2.0, 3.0]).is_err());
    }
}
