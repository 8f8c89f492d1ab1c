//! The screen-space shadows the light rig carries (`SHADOWS_SCREEN`, docs/shading.md §11):
//! each directional light's cascaded maps — 1, 2 and 4 cascades fitted to slices of the
//! camera's view ([`CASCADE_COUNTS`]), each cascade rendered by `standard/ShadowCaster` through
//! its orthographic view and laid into its tile of an atlas — and the masks every
//! `screen_space_shadows/Collect` variant made of each atlas over the camera's depth buffer.
//! The `Collect` check compares these masks; the lighting and forward checks read the
//! 4-cascade mask. Each light also keeps one map over the region around the scene and URP's
//! cascades over the test quad ([`urp_split_spheres`]): URP's main light reads them
//! (`_MAIN_LIGHT_SHADOWS`, `_MAIN_LIGHT_SHADOWS_CASCADE`), and a stand-in for the target URP's
//! screen-space pass writes ([`ScreenShadowTexture`], `_MAIN_LIGHT_SHADOWS_SCREEN`).

use glam::{Mat4, Vec3};

use super::camera::{LightingCamera, depth_camera_resources};
use super::scene::{Rng, TestScene, texture};
use super::shadows::{MAP_SIZE, SPOT_BIAS, lay_tiles, refused, render_caster};
use crate::{
    BoundResource, CheckError, ColorTarget, GpuContext, GpuError, RenderJob, Resource,
    TargetFormat, render,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cascades::{
    Cascade, CascadeCamera, CascadeKeywords, Cascades,
};
use wgsl_variants_shaders::reference::light::{
    Light, LightType, look_at_rh, perspective_rh, world_from_depth,
};
use wgsl_variants_shaders::reference::shadow::{ShadowMap2d, ShadowParams};
use wgsl_variants_shaders::reference::urp::forward::MainLightShadows;
use wgsl_variants_shaders::reference::urp::shadow::main_light_map_factor;

/// The directional shadows' strength.
pub const DIRECTIONAL_STRENGTH: f32 = 0.85;

/// The radius of the region the directional maps cover, around the test floor's centre.
pub const REGION_RADIUS: f32 = 2.0;

/// The seed of each light's [`ScreenShadowTexture`] (with the light's index mixed in).
const SCREEN_SHADOW_SEED: u64 = 0x5C8E_E45D;

/// The cascade counts the masks are rendered with (Unity's choices): 1, 2 and 4.
pub const CASCADE_COUNTS: [usize; 3] = [1, 2, 4];

/// The camera's near plane, where the first cascade starts (as Unity starts it).
pub const CASCADE_NEAR: f32 = 0.5;

/// The deep view's camera: low over the floor, looking along it towards the occluders, so its
/// pixels' view depths run from a few units to the horizon. (The rig's camera looks down at
/// the floor: its pixels' depths lie in a band a tenth of the view's width, so the first
/// slice's bounding sphere holds nearly all of them and the split spheres go untested there.)
pub const DEEP_EYE: Vec3 = Vec3::new(0.3, -7.0, 1.6);

/// Where the deep view looks.
pub const DEEP_TARGET: Vec3 = Vec3::new(0.25, -0.25, 0.0);

/// The deep view's far plane (its sky pixels lie there, beyond every cascade).
pub const DEEP_FAR: f32 = 30.0;

/// URP's main-light split spheres over the test quad (`_MAIN_LIGHT_SHADOWS_CASCADE`), each
/// inside the next as URP's grow along the view (so exactly one cascade weight is on where
/// any is: URP's `ComputeCascadeIndex` subtracts only the previous sphere's weight): centres
/// 0.6 above the floor (each map's depth range then holds the occluders) along a line through
/// the occluders' shadow on the floor, radii 0.9, 1.35, 1.9 and 2.45. The shadow's left part
/// falls in cascade 0, its right part in cascade 1; the quad's corners lie in none (lit).
pub fn urp_split_spheres() -> [(Vec3, f32); 4] {
    // Near the middle of the two occluders' shadows on the floor (shadows::OCCLUDERS cast
    // along the rig's directional light), lifted to the occluders' height.
    let shadow = Vec3::new(0.4, -0.45, 0.6);
    [(-0.4, 0.9), (0.0, 1.35), (0.5, 1.9), (1.0, 2.45)]
        .map(|(dx, radius)| (shadow + Vec3::X * dx, radius))
}

/// Cascades rendered into one atlas (each tile a cascade's map, [`Cascades::grid`]).
#[derive(Clone, Debug)]
pub struct CascadeAtlas {
    /// The cascades.
    pub cascades: Cascades,
    /// The atlas, read back.
    pub map: ShadowMap2d,
    /// The atlas as rendered (`Depth16Unorm`).
    pub texels: Vec<u16>,
    /// The atlas's width and height in texels.
    pub size: (u32, u32),
}

impl CascadeAtlas {
    /// Lays the `tile × tile` map `render` draws of each of `cascades` (through the cascade's
    /// own view, row by row) into its tile of the atlas ([`Cascades::grid`]) and reads it back;
    /// `pass` names the reader in the error when the atlas is refused.
    pub(crate) fn render(
        cascades: Cascades,
        tile: u32,
        pass: &str,
        render: impl FnMut(&Cascade) -> Result<Vec<u16>, GpuError>,
    ) -> Result<CascadeAtlas, GpuError> {
        let (texels, size) = lay_atlas(&cascades, tile, render)?;
        let map = ShadowMap2d::from_depth16(size.0, size.1, &texels).map_err(refused(pass))?;
        Ok(CascadeAtlas {
            cascades,
            map,
            texels,
            size,
        })
    }

    /// Bindings 10-12 as Unity's collector reads them (`lighting/cascades`): the
    /// `CascadedShadow` record, the atlas and the comparison sampler.
    pub(crate) fn resources(&self) -> Vec<BoundResource> {
        map_resources(
            bytemuck::cast_slice(&self.cascades.uniform()),
            &self.texels,
            self.size,
            10,
        )
    }

    /// Bindings 12, 14 and 15 as URP's receivers read them (`universal/main_light_shadow`,
    /// `_MAIN_LIGHT_SHADOWS_CASCADE`): the comparison sampler, the `CascadedShadow` record and
    /// the atlas. Slots 10 and 11 are the one map's, so the record and atlas move.
    pub(crate) fn urp_resources(&self) -> Vec<BoundResource> {
        self.resources()
            .into_iter()
            .map(|r| match r.binding {
                10 => BoundResource { binding: 14, ..r },
                11 => BoundResource { binding: 15, ..r },
                _ => r,
            })
            .collect()
    }
}

/// Where the cascades end and the next starts, as fractions of the pixels' view depths sorted
/// (the depths half-way between two neighbours there): the last cascade ends before the
/// farthest pixels, so some pixels lie in no cascade.
pub fn split_fractions(count: usize) -> &'static [f32] {
    match count {
        1 => &[0.9],
        2 => &[0.45, 0.9],
        _ => &[0.2, 0.45, 0.7, 0.9],
    }
}

/// A directional light's cascades of one count, their atlas, and a mask per `Collect`
/// variant.
#[derive(Clone, Debug)]
pub struct CascadeSet {
    /// The cascades, fitted to the camera's view, and their atlas.
    pub atlas: CascadeAtlas,
    /// The mask of each `Collect` variant (in [`ScreenShadows::variants`] order),
    /// `Rgba8Unorm` bytes of the rig's camera view.
    pub masks: Vec<Vec<u8>>,
}

/// One directional light's shadow: its cascades with the masks `Collect` made of them, and one
/// map over the region around the scene.
#[derive(Clone, Debug)]
pub struct ScreenShadow {
    /// `DIRECTIONAL` or `DIRECTIONAL_COOKIE`.
    pub light: LightType,
    /// The region map's parameters (an orthographic box of [`REGION_RADIUS`]).
    pub params: ShadowParams,
    /// The region map, read back.
    pub map: ShadowMap2d,
    /// The region map as rendered (`Depth16Unorm`).
    pub map_texels: Vec<u16>,
    /// One per [`CASCADE_COUNTS`], in order, over the rig's camera view.
    pub sets: Vec<CascadeSet>,
    /// The same over the deep view ([`ScreenShadows::deep`]).
    pub deep_sets: Vec<CascadeSet>,
    /// URP's cascades over the test quad (its split spheres: `urp_split_spheres` of this
    /// module), with the region map's strength and bias.
    pub urp: CascadeAtlas,
    /// What the receivers' `_MAIN_LIGHT_SHADOWS_SCREEN` variants read in the pass checks.
    pub urp_screen: ScreenShadowTexture,
}

/// A stand-in for the camera-sized target URP's `ScreenSpaceShadows` pass writes, bound to the
/// receivers' `_MAIN_LIGHT_SHADOWS_SCREEN` variants in the pass checks: one `Rgba8Unorm` texel
/// per pixel, every channel the same pseudo-random code, so a receiver that reads another
/// pixel's texel, or works the shadow out itself, fails. The pass that writes the real one is
/// checked on its own (`check::urp_screen_shadows`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScreenShadowTexture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// One code per texel, rows top to bottom.
    pub codes: Vec<u8>,
}

impl ScreenShadowTexture {
    /// `width × height` codes drawn from `seed`, the same on every machine.
    ///
    /// ```
    /// use wgsl_variants_gpu::check::screen_shadows::ScreenShadowTexture;
    /// let t = ScreenShadowTexture::pseudo_random(4, 2, 7);
    /// assert_eq!(t, ScreenShadowTexture::pseudo_random(4, 2, 7));
    /// assert_eq!(t.codes.len(), 8);
    /// assert_eq!(t.at(3, 1), f32::from(t.codes[7]) / 255.0);
    /// ```
    pub fn pseudo_random(width: u32, height: u32, seed: u64) -> ScreenShadowTexture {
        let mut rng = Rng::new(seed);
        let codes = (0..width * height)
            .map(|_| rng.next_u64().to_le_bytes()[0])
            .collect();
        ScreenShadowTexture {
            width,
            height,
            codes,
        }
    }

    /// The realtime shadow a receiver reads at pixel `(x, y)`: the code over 255.
    pub fn at(&self, x: u32, y: u32) -> f32 {
        f32::from(self.codes[(y * self.width + x) as usize]) / 255.0
    }

    /// Binding 16 of `universal/main_light_shadow` (`main_light_screen_shadow`).
    pub(crate) fn resource(&self) -> BoundResource {
        let rgba: Vec<u8> = self.codes.iter().flat_map(|&c| [c; 4]).collect();
        BoundResource::new(
            0,
            16,
            texture(TargetFormat::Rgba8Unorm, self.width, self.height, &rgba),
        )
    }
}

impl ScreenShadow {
    /// URP's realtime main-light shadow at `p`, seen at pixel `(x, y)` of the rig's view,
    /// before the fade, as an interval (a tap or a split within a hair of flipping gives both
    /// outcomes): 1 without a shadow, the region map's ([`main_light_map_factor`]) with
    /// `_MAIN_LIGHT_SHADOWS`, the cascades' ([`Cascades::factor`] with URP's split-sphere
    /// selection) with `_MAIN_LIGHT_SHADOWS_CASCADE`, the [`ScreenShadowTexture`]'s texel with
    /// `_MAIN_LIGHT_SHADOWS_SCREEN`; `soft`: `_SHADOWS_SOFT` (the screen-space pass's business
    /// with `_SCREEN`).
    pub fn urp_factor(
        &self,
        mode: MainLightShadows,
        soft: bool,
        p: Vec3,
        (x, y): (u32, u32),
    ) -> (f32, f32) {
        match mode {
            MainLightShadows::Off => (1.0, 1.0),
            MainLightShadows::Screen => {
                let s = self.urp_screen.at(x, y);
                (s, s)
            }
            MainLightShadows::Map => main_light_map_factor(&self.params, &self.map, soft, p),
            MainLightShadows::Cascades => {
                self.urp
                    .cascades
                    .factor(CascadeKeywords::urp(soft), &self.urp.map, p)
            }
        }
    }

    /// What URP's cascades do at `positions`, for reports: how many lie in each cascade and in
    /// none, and how many of those the hard cascaded shadow darkens, e.g. `cascades 0-3, none:
    /// 30, 33, 61, 105, 27 positions; shadowed 5, 4, 0, 0, 0`.
    pub fn urp_cascade_census(&self, positions: &[Vec3]) -> String {
        let spheres = CascadeKeywords::urp(false);
        let mut all = [0usize; 5];
        let mut shadowed = [0usize; 5];
        for &p in positions {
            let Some(w) = self.urp.cascades.candidates(spheres, p)[0] else {
                continue;
            };
            let k = Cascades::picked(w).min(4);
            all[k] += 1;
            let lit = self.urp.cascades.factor(spheres, &self.urp.map, p).1;
            shadowed[k] += usize::from(lit < 1.0);
        }
        let list = |v: [usize; 5]| v.map(|n| n.to_string()).join(", ");
        format!(
            "cascades 0-3, none: {} positions; shadowed {}",
            list(all),
            list(shadowed)
        )
    }

    /// Bindings 10-12 and 14-16 of URP's main-light shadow (`universal/main_light_shadow`):
    /// the region map's `Shadow` record and map (`_MAIN_LIGHT_SHADOWS`), the comparison
    /// sampler, the cascades' `CascadedShadow` record and atlas
    /// (`_MAIN_LIGHT_SHADOWS_CASCADE`), the screen-space texture
    /// (`_MAIN_LIGHT_SHADOWS_SCREEN`). A variant binds those it declares.
    pub(crate) fn urp_resources(&self) -> Vec<BoundResource> {
        // The map's record and map (10, 11); the atlas brings the shared sampler (12).
        let mut out = shadow_map_resources(&self.params, &self.map_texels);
        out.retain(|r| r.binding != 12);
        out.extend(self.urp.urp_resources());
        out.push(self.urp_screen.resource());
        out
    }
}

/// A second camera view for the `Collect` check: the floor `z = 0` seen from [`DEEP_EYE`]
/// (each pixel's depth where its ray meets the floor, the far plane where it does not).
#[derive(Clone, Debug)]
pub struct DeepView {
    /// World to clip.
    pub view_proj: Mat4,
    /// The camera's position.
    pub position: Vec3,
    /// One depth per pixel, row by row.
    pub depth: Vec<f32>,
}

impl DeepView {
    /// The view at `width × height`.
    pub fn new(width: u32, height: u32) -> DeepView {
        let view_proj = perspective_rh(0.6, width as f32 / height as f32, CASCADE_NEAR, DEEP_FAR)
            * look_at_rh(DEEP_EYE, DEEP_TARGET, Vec3::Z);
        let inv = view_proj.inverse();
        let mut depth = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                let near = world_from_depth(inv, x, y, width, height, 0.0);
                let far = world_from_depth(inv, x, y, width, height, 1.0);
                let d = if near.z > 0.0 && far.z < 0.0 {
                    let hit = near + (far - near) * (near.z / (near.z - far.z));
                    let clip = view_proj * hit.extend(1.0);
                    clip.z / clip.w
                } else {
                    1.0
                };
                depth.push(d);
            }
        }
        DeepView {
            view_proj,
            position: DEEP_EYE,
            depth,
        }
    }

    /// The camera as the full-screen passes see it.
    pub(crate) fn camera(&self) -> LightingCamera<'_> {
        LightingCamera {
            view_proj: self.view_proj,
            position: self.position,
            depth: &self.depth,
        }
    }

    /// The world position `Collect` rebuilds at pixel `(x, y)` of a `width`-wide view.
    pub fn position(&self, x: u32, y: u32, width: u32, height: u32) -> Vec3 {
        let d = self.depth[(y * width + x) as usize];
        world_from_depth(self.view_proj.inverse(), x, y, width, height, d)
    }
}

/// The screen-space shadows of the rig's two directional lights.
#[derive(Clone, Debug)]
pub struct ScreenShadows {
    /// The `Collect` variants' keywords, in the order of each light's masks.
    pub variants: Vec<Vec<String>>,
    /// One per directional light type.
    pub lights: Vec<ScreenShadow>,
    /// The deep view the `Collect` check also renders its masks over.
    pub deep: DeepView,
    /// The masks' size in pixels.
    pub width: u32,
    /// The masks' height in pixels.
    pub height: u32,
}

impl ScreenShadows {
    /// Renders each of the `directional` lights' maps with the cut-out caster, then every
    /// `Collect` variant over `camera`'s depth buffer (what `ScreenShadows::render` does with
    /// the light rig's two directional lights and camera).
    ///
    /// # Errors
    /// A GPU failure, a variant that does not compile, or a map the reference refuses.
    pub(crate) fn render_lights(
        ctx: &GpuContext,
        lib: &Library,
        scene: &TestScene,
        directional: [(&Light, LightType); 2],
        camera: &LightingCamera<'_>,
    ) -> Result<ScreenShadows, GpuError> {
        let pass = lib
            .pass("screen_space_shadows", "Collect")
            .map_err(|e| CheckError::lookup("screen_space_shadows/Collect", e))?;
        let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
        let variants: Vec<Vec<String>> = choices
            .iter()
            .map(|c| c.keywords(pass).into_iter().map(str::to_owned).collect())
            .collect();
        let refused = refused("screen_space_shadows/Collect");
        let center = scene.centre.extend(0.5);
        let deep = DeepView::new(scene.width, scene.height);
        let mut lights = Vec::new();
        for (light, kind) in directional {
            let params = ShadowParams::for_directional(
                light,
                DIRECTIONAL_STRENGTH,
                SPOT_BIAS,
                center,
                REGION_RADIUS,
            )
            .map_err(&refused)?;
            let image = render_caster(
                ctx,
                lib,
                &["_RENDERING_CUTOUT", "SHADOWS_DEPTH"],
                params.world_to_shadow,
                params.light_position.extend(params.inv_range),
                MAP_SIZE,
            )?;
            let map =
                ShadowMap2d::from_depth16(MAP_SIZE, MAP_SIZE, &image.depth).map_err(&refused)?;
            let collect = Collect {
                pass,
                choices: &choices,
                size: (scene.width, scene.height),
            };
            let sets = collect.sets(ctx, lib, light, camera)?;
            let deep_sets = collect.sets(ctx, lib, light, &deep.camera())?;
            let urp = Cascades::from_spheres(
                light,
                DIRECTIONAL_STRENGTH,
                SPOT_BIAS,
                &urp_split_spheres(),
            )
            .map_err(&refused)?;
            let urp = cut_out_atlas(ctx, lib, urp)?;
            let urp_screen = ScreenShadowTexture::pseudo_random(
                scene.width,
                scene.height,
                SCREEN_SHADOW_SEED ^ lights.len() as u64,
            );
            lights.push(ScreenShadow {
                light: kind,
                params,
                map,
                map_texels: image.depth,
                sets,
                deep_sets,
                urp,
                urp_screen,
            });
        }
        Ok(ScreenShadows {
            variants,
            lights,
            deep,
            width: scene.width,
            height: scene.height,
        })
    }

    /// The light `t`'s shadow (directional types only).
    pub fn light(&self, t: LightType) -> Option<&ScreenShadow> {
        self.lights.iter().find(|l| l.light == t)
    }

    /// The 4-cascade set of light `t` (directional types only), whose masks the lighting and
    /// forward checks read.
    fn four(&self, t: LightType) -> Option<&CascadeSet> {
        self.light(t)?.sets.last()
    }

    /// The mask the `Lighting` variants read for light `t`: the hard one of 4 cascades split
    /// by view depth (the lighting pass leaves `SHADOWS_SOFT` and the cascades to
    /// `Collect`), as a texture resource.
    pub fn lighting_mask(&self, t: LightType) -> Option<Resource> {
        let hard = self.variants.iter().position(|v| v.is_empty())?;
        Some(texture(
            TargetFormat::Rgba8Unorm,
            self.width,
            self.height,
            &self.four(t)?.masks[hard],
        ))
    }

    /// The factor the hard mask holds at pixel `i` for light `t` (1 for other lights).
    pub fn lighting_factor(&self, t: LightType, i: usize) -> f32 {
        let hard = self.variants.iter().position(|v| v.is_empty());
        match (hard, self.four(t)) {
            (Some(hard), Some(set)) => f32::from(set.masks[hard][i * 4]) / 255.0,
            _ => 1.0,
        }
    }
}

/// What every cascade set's masks are rendered with: the `Collect` pass, its variants, the
/// masks' size.
struct Collect<'a> {
    pass: &'a wgsl_variants::Pass,
    choices: &'a [wgsl_variants::Choice],
    size: (u32, u32),
}

impl Collect<'_> {
    /// `light`'s cascades over `camera`'s view, one set per [`CASCADE_COUNTS`]: fitted to
    /// splits at [`split_fractions`] of the pixels' view depths from [`CASCADE_NEAR`], the
    /// atlas rendered, and a mask per variant.
    fn sets(
        &self,
        ctx: &GpuContext,
        lib: &Library,
        light: &Light,
        camera: &LightingCamera<'_>,
    ) -> Result<Vec<CascadeSet>, GpuError> {
        let refused = refused("screen_space_shadows/Collect");
        let view = cascade_camera(camera);
        let depths = view_depths(self.size, camera, &view);
        let mut sets = Vec::new();
        for count in CASCADE_COUNTS {
            let mut splits = vec![CASCADE_NEAR];
            splits.extend(split_fractions(count).iter().map(|&f| quantile(&depths, f)));
            let cascades = Cascades::fit(light, DIRECTIONAL_STRENGTH, SPOT_BIAS, &view, &splits)
                .map_err(&refused)?;
            let atlas = cut_out_atlas(ctx, lib, cascades)?;
            let mut masks = Vec::new();
            for choice in self.choices {
                let variant = wgsl_variants::Variant {
                    pass: self.pass,
                    choice: choice.clone(),
                };
                let mut resources = depth_camera_resources(self.size, camera);
                resources.extend(atlas.resources());
                masks.push(render_mask(
                    ctx,
                    &variant.label(),
                    &lib.wgsl(&variant),
                    self.size,
                    resources,
                )?);
            }
            sets.push(CascadeSet { atlas, masks });
        }
        Ok(sets)
    }
}

/// A full-screen mask pass — `wgsl`'s `vs_main` and `fs_main` over `resources` (the depth
/// buffer, the camera, the shadow maps) — into one `Rgba8Unorm` target of `size`: its texels.
///
/// # Errors
/// A GPU failure or a shader that does not compile.
pub(crate) fn render_mask(
    ctx: &GpuContext,
    label: &str,
    wgsl: &str,
    size: (u32, u32),
    resources: Vec<BoundResource>,
) -> Result<Vec<u8>, GpuError> {
    let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
    (job.width, job.height) = size;
    job.targets = vec![ColorTarget::new(TargetFormat::Rgba8Unorm)];
    job.resources = resources;
    Ok(render(ctx, &job)?.remove(0))
}

/// The cascades' view of `camera`.
fn cascade_camera(camera: &LightingCamera<'_>) -> CascadeCamera {
    CascadeCamera::from_view_proj(camera.position, camera.view_proj)
}

/// The view depth of every pixel's position rebuilt from `camera`'s depth buffer, sorted.
fn view_depths((w, h): (u32, u32), camera: &LightingCamera<'_>, view: &CascadeCamera) -> Vec<f32> {
    let mut depths: Vec<f32> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = camera.depth[(y * w + x) as usize];
            let p: Vec3 = world_from_depth(view.inv_view_proj, x, y, w, h, d);
            (p - view.position).dot(view.forward)
        })
        .collect();
    depths.sort_by(f32::total_cmp);
    depths
}

/// The depth half-way between the sorted `depths` at fraction `f` and the next one.
fn quantile(depths: &[f32], f: f32) -> f32 {
    let k = ((depths.len() as f32 * f) as usize).min(depths.len() - 2);
    0.5 * (depths[k] + depths[k + 1])
}

/// `cascades` rendered by the cut-out caster into their atlas of [`MAP_SIZE`] tiles.
fn cut_out_atlas(
    ctx: &GpuContext,
    lib: &Library,
    cascades: Cascades,
) -> Result<CascadeAtlas, GpuError> {
    CascadeAtlas::render(cascades, MAP_SIZE, "screen_space_shadows/Collect", |c| {
        Ok(render_caster(
            ctx,
            lib,
            &["_RENDERING_CUTOUT", "SHADOWS_DEPTH"],
            c.view_proj,
            c.params.light_position.extend(c.params.inv_range),
            MAP_SIZE,
        )?
        .depth)
    })
}

/// Lays each cascade's `tile × tile` map (row by row, as `render` returns it for the cascade's
/// own view) into its tile of the atlas ([`Cascades::grid`]): the texels and the atlas's size.
fn lay_atlas(
    cascades: &Cascades,
    tile: u32,
    render: impl FnMut(&Cascade) -> Result<Vec<u16>, GpuError>,
) -> Result<(Vec<u16>, (u32, u32)), GpuError> {
    let grid = Cascades::grid(cascades.cascades.len());
    lay_tiles(grid, tile, cascades.cascades.iter().map(render))
}

/// Bindings 10-12 of a directional light's shadow (`lighting/shadow`): the `Shadow` uniform of
/// `params`, the `Depth16Unorm` map's texels and the LessEqual comparison sampler. Shared by
/// URP's main light (`stencil_deferred`, `_MAIN_LIGHT_SHADOWS`) and its forward pass.
pub(crate) fn shadow_map_resources(params: &ShadowParams, map: &[u16]) -> Vec<BoundResource> {
    map_resources(
        bytemuck::cast_slice(&params.uniform()),
        map,
        (MAP_SIZE, MAP_SIZE),
        10,
    )
}

/// Bindings `first` to `first + 2` of a shadow map: `record` (the `Shadow`, `CascadedShadow`
/// or `AdditionalShadows` record's bytes), the `Depth16Unorm` map of `size` and the LessEqual
/// comparison sampler (nearest).
pub(crate) fn map_resources(
    record: &[u8],
    map: &[u16],
    (width, height): (u32, u32),
    first: u32,
) -> Vec<BoundResource> {
    vec![
        BoundResource::new(0, first, Resource::Uniform(record.to_vec())),
        BoundResource::new(
            0,
            first + 1,
            Resource::Texture2d {
                format: wgpu::TextureFormat::Depth16Unorm,
                width,
                height,
                data: map.iter().flat_map(|d| d.to_le_bytes()).collect(),
            },
        ),
        BoundResource::new(
            0,
            first + 2,
            Resource::ComparisonSampler {
                compare: wgpu::CompareFunction::LessEqual,
                nearest: true,
            },
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn urp_split_spheres_nest_so_one_cascade_is_picked() {
        let spheres = urp_split_spheres();
        for w in spheres.windows(2) {
            let ((a, ra), (b, rb)) = (w[0], w[1]);
            assert!(a.distance(b) + ra <= rb, "{w:?}: not inside the next");
        }
        // Every point of the quad's plane is in one cascade or in none.
        let sun = Light::directional(Vec3::new(0.25, -0.35, -0.9), Vec3::ONE);
        let c = Cascades::from_spheres(&sun, 0.5, 0.0, &spheres).unwrap();
        let keywords = CascadeKeywords::urp(false);
        let mut picked = [0usize; 5];
        for i in 0..=40 {
            for j in 0..=40 {
                let p = Vec3::new(-1.5 + 0.1 * i as f32, -2.25 + 0.1 * j as f32, 0.0);
                for w in c.candidates(keywords, p) {
                    let k = Cascades::picked(w.unwrap());
                    assert!(k <= 4, "{p}: more than one cascade");
                    picked[k] += 1;
                }
            }
        }
        // Each cascade and the outside are reached.
        assert!(picked.iter().all(|&n| n > 0), "{picked:?}");
    }
}
