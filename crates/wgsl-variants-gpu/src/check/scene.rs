//! The test scene of the GPU check, made by code: deterministic (seeded), small, and chosen so
//! that the CPU reference computes exactly what the GPU is asked to compute.
//!
//! - A `SIZE × SIZE` target covered by one quad (two triangles) in the world plane `z = 0`,
//!   drawn with an orthographic view: pixel `(x, y)` has its centre at world position
//!   [`TestScene::world_position`], exact in `f32`, and `uv = ((x + 0.5)/W, (y + 0.5)/H)`.
//! - Every map texture is `W × H` `Rgba8Unorm`, sampled with a nearest sampler, so each pixel
//!   reads exactly one texel at its centre (the detail maps at `uv · 2 + offset`, repeating,
//!   which lands on texel `(2x + 3) mod W`, again at its centre).
//! - Texel values are chosen to make each keyword visible: `main_tex.a` straddles the cutoff
//!   (never within 2·10⁻³ of it), normal maps have varied tilts, the detail mask is 0, ½ or 1,
//!   metallic and occlusion vary, emission varies.
//! - Reflection probes sample cube maps whose faces are each one colour, equal on every mip
//!   level, through a nearest sampler: a sample depends only on the face a direction selects.
//!   The scene is built so that every direction any pass samples is at least
//!   [`MIN_FACE_MARGIN`] away from a cube-face edge ([`reference::cube::face_margin`]), for every
//!   combination of the normal keywords, with and without the 10-bit G-buffer normal.
//!
//! [`reference::cube::face_margin`]: wgsl_variants_shaders::reference::cube::face_margin

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::{BoundResource, Resource, TargetFormat, VertexBuffer};
use wgsl_variants_shaders::reference::cube::{CubeFaces, face_margin};
use wgsl_variants_shaders::reference::gbuffer::{decode_normal, encode_normal};
use wgsl_variants_shaders::reference::lightmap::{LightmapDecode, LightmapTexels};
use wgsl_variants_shaders::reference::probe::{Probe, box_project, box_project_grown, falloff};
use wgsl_variants_shaders::reference::quantize::{unorm, unorm_to_f32};
use wgsl_variants_shaders::reference::surface::{
    Geometry, Keywords, Material, Scene, Texels, surface, view_and_reflection,
};

/// Width and height of the test scene's targets, in pixels.
pub const SIZE: u32 = 16;

/// Edge length of mip level 0 of the probes' cube maps (7 mip levels: 64 … 1, so every mip
/// level the smoothness can select exists).
pub const CUBE_SIZE: u32 = 64;

/// The smallest [`face_margin`] any reflection lookup of the scene may have.
pub const MIN_FACE_MARGIN: f32 = 0.05;

/// The seed of the scene the check uses.
pub const DEFAULT_SEED: u64 = 0x005E_ED0F_11A7;

/// Smallest distance between a pixel's alpha and the cutoff.
const CUTOFF_MARGIN: f32 = 2.0e-3;

/// The normal keywords' combinations that give different world normals:
/// (`_NORMAL_MAP`, `_DETAIL_NORMAL_MAP`, `_DETAIL_MASK`).
pub const NORMAL_COMBINATIONS: [(bool, bool, bool); 6] = [
    (false, false, false),
    (true, false, false),
    (false, true, false),
    (false, true, true),
    (true, true, false),
    (true, true, true),
];

/// A tiny deterministic generator (SplitMix64), so the scene needs no dependency and is the same
/// on every machine.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator with this seed.
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform `f32` in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * unit
    }

    /// An 8-bit unorm code for a uniform value in `[lo, hi]`.
    pub fn byte(&mut self, lo: f32, hi: f32) -> u8 {
        unorm(self.range(lo, hi), 8) as u8
    }

    /// One of `items`, uniformly.
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[(self.next_u64() % items.len() as u64) as usize]
    }
}

/// An `Rgba8Unorm` texture of the scene: `width × height` texels, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapTexture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels, row-major.
    pub texels: Vec<[u8; 4]>,
}

impl MapTexture {
    /// A `width × height` texture whose texel `(x, y)` is `texel(x, y)`.
    pub fn new(width: u32, height: u32, mut texel: impl FnMut(u32, u32) -> [u8; 4]) -> MapTexture {
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| texel(x, y))
            .collect();
        MapTexture {
            width,
            height,
            texels,
        }
    }

    /// The texel at `(x, y)` as the shader reads it (`code / 255`).
    pub fn get(&self, x: u32, y: u32) -> Vec4 {
        let t = self.texels[(y * self.width + x) as usize];
        Vec4::from_array(t.map(|c| unorm_to_f32(u32::from(c), 8)))
    }

    fn set(&mut self, x: u32, y: u32, texel: [u8; 4]) {
        self.texels[(y * self.width + x) as usize] = texel;
    }

    /// The texture as a bindable resource.
    pub fn resource(&self) -> Resource {
        Resource::Texture2d {
            format: wgpu::TextureFormat::Rgba8Unorm,
            width: self.width,
            height: self.height,
            data: self.texels.iter().flatten().copied().collect(),
        }
    }
}

/// The material's textures.
#[derive(Clone, Debug, PartialEq)]
pub struct Maps {
    /// `main_tex`.
    pub main_tex: MapTexture,
    /// `metallic_map`.
    pub metallic_map: MapTexture,
    /// `normal_map`.
    pub normal_map: MapTexture,
    /// `occlusion_map`.
    pub occlusion_map: MapTexture,
    /// `emission_map`.
    pub emission_map: MapTexture,
    /// `detail_mask`.
    pub detail_mask: MapTexture,
    /// `detail_albedo` (sampled at the detail uv).
    pub detail_albedo: MapTexture,
    /// `detail_normal` (sampled at the detail uv).
    pub detail_normal: MapTexture,
    /// `shadowmask_map`: the object's baked occlusion of up to four lights, one per channel
    /// (the Deferred pass's `SHADOWS_SHADOWMASK` variants copy it to RT4).
    pub shadowmask: MapTexture,
    /// `lightmap_tex`, `lightmap_dir`, `dynamic_lightmap`, `dynamic_lightmap_dir` (read at the
    /// lightmap uvs, [`Maps::lightmap_st`]).
    pub lightmaps: [MapTexture; 4],
    /// Unity's `unity_LightmapST` and `unity_DynamicLightmapST`: lightmap uv = uv · xy + zw.
    pub lightmap_st: [Vec4; 2],
}

impl Maps {
    /// One-texel black lightmaps (RGBM alpha 1) and flat directional maps, read at uv: for
    /// scenes without lightmapped objects.
    pub fn no_lightmaps() -> ([MapTexture; 4], [Vec4; 2]) {
        let black = || MapTexture::new(1, 1, |_, _| [0, 0, 0, 255]);
        let flat = || MapTexture::new(1, 1, |_, _| [128, 128, 128, 255]);
        let st = Vec4::new(1.0, 1.0, 0.0, 0.0);
        ([black(), flat(), black(), flat()], [st, st])
    }
}

/// The whole test scene: geometry, material, textures, lighting and probes.
#[derive(Clone, Debug)]
pub struct TestScene {
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// The material's uniforms.
    pub material: Material,
    /// Detail tiling (xy) and offset (zw).
    pub detail_st: Vec4,
    /// The textures.
    pub maps: Maps,
    /// Camera, ambient light, directional light and the forward pass's two probes.
    pub scene: Scene,
    /// The deferred reflection pass's probes with their cube maps, in the order given to the
    /// pass (which draws them in [`wgsl_variants_shaders::reference::probe::draw_order`]).
    pub deferred_probes: Vec<(Probe, CubeFaces)>,
    /// Object-to-world transform of the quad.
    pub model: Mat4,
    /// Inverse transpose of `model` (for normals).
    pub normal_matrix: Mat4,
    /// World-to-clip transform (orthographic).
    pub view_proj: Mat4,
    /// The quad's vertex normal, in object space.
    pub object_normal: Vec3,
    /// The quad's vertex tangent (xyz in object space, w the bitangent sign).
    pub object_tangent: Vec4,
    /// Centre of the quad in world space.
    pub centre: Vec2,
    /// Half the quad's edge length in world space.
    pub half_size: f32,
}

/// A cube of six colours from 8-bit codes, RGBM alpha in the last component.
pub(crate) fn cube(colours: [[u8; 4]; 6]) -> CubeFaces {
    CubeFaces(colours.map(|c| Vec4::from_array(c.map(|x| unorm_to_f32(u32::from(x), 8)))))
}

/// A probe.
pub(crate) fn probe(
    position: Vec3,
    box_min: Vec3,
    box_max: Vec3,
    box_projection: bool,
    hdr: Vec3,
    blend_distance: f32,
    importance: i32,
) -> Probe {
    Probe {
        position,
        box_min,
        box_max,
        hdr,
        box_projection,
        blend_distance,
        importance,
        forward_weight: 1.0,
    }
}

/// A tangent-space normal-map texel with tilt `(tx, ty)` (components of the unit normal).
fn normal_texel(rng: &mut Rng, max_tilt: f32) -> [u8; 4] {
    let tx = rng.range(-max_tilt, max_tilt);
    let ty = rng.range(-max_tilt, max_tilt);
    let tz = (1.0 - tx * tx - ty * ty).max(0.0).sqrt();
    [
        unorm(tx * 0.5 + 0.5, 8) as u8,
        unorm(ty * 0.5 + 0.5, 8) as u8,
        unorm(tz * 0.5 + 0.5, 8) as u8,
        255,
    ]
}

impl TestScene {
    /// The scene with `seed` (see [`DEFAULT_SEED`]).
    ///
    /// # Panics
    /// If the random seed gives a scene whose reflection directions cannot be kept
    /// [`MIN_FACE_MARGIN`] away from cube-face edges (never for the default seed).
    pub fn new(seed: u64) -> TestScene {
        let (w, h) = (SIZE, SIZE);
        let mut rng = Rng::new(seed);
        let material = Material {
            tint: Vec4::new(0.95, 0.85, 0.75, 0.9),
            emission: Vec3::new(0.06, 0.12, 0.18),
            metallic: 0.25,
            smoothness: 0.8,
            cutoff: 0.5,
            occlusion_strength: 0.75,
            bump_scale: 0.8,
            detail_bump_scale: 0.6,
        };
        // Detail uv = uv · 2 + offset: texel (2x + 3) mod W, at its centre.
        let detail_st = Vec4::new(2.0, 2.0, 2.5 / w as f32, 2.5 / h as f32);

        let tint_a = material.tint.w;
        let cutoff = material.cutoff;
        let main_tex = MapTexture::new(w, h, |_, _| {
            loop {
                let a = rng.byte(0.4, 1.0);
                if (tint_a * unorm_to_f32(u32::from(a), 8) - cutoff).abs() >= CUTOFF_MARGIN {
                    break [
                        rng.byte(0.3, 1.0),
                        rng.byte(0.3, 1.0),
                        rng.byte(0.3, 1.0),
                        a,
                    ];
                }
            }
        });
        let metallic_map = MapTexture::new(w, h, |_, _| {
            let m = rng.pick(&[0u8, 255, 64, 160]);
            let m = if m == 160 { rng.byte(0.0, 1.0) } else { m };
            [m, 0, 0, rng.byte(0.2, 1.0)]
        });
        let normal_map = MapTexture::new(w, h, |_, _| normal_texel(&mut rng, 0.45));
        let occlusion_map = MapTexture::new(w, h, |_, _| [0, rng.byte(0.1, 1.0), 0, 255]);
        let emission_map = MapTexture::new(w, h, |_, _| {
            [
                rng.byte(0.0, 1.0),
                rng.byte(0.0, 1.0),
                rng.byte(0.0, 1.0),
                255,
            ]
        });
        let detail_mask = MapTexture::new(w, h, |_, _| [0, 0, 0, rng.pick(&[0u8, 128, 255])]);
        let detail_albedo = MapTexture::new(w, h, |_, _| {
            [
                rng.byte(0.25, 0.75),
                rng.byte(0.25, 0.75),
                rng.byte(0.25, 0.75),
                255,
            ]
        });
        let detail_normal = MapTexture::new(w, h, |_, _| normal_texel(&mut rng, 0.35));
        // Fully lit, fully occluded and partial texels in every channel; its own generator, so
        // the other maps stay what they were.
        let mut baked = Rng::new(seed ^ 0x5ad0_4a5c);
        let shadowmask = MapTexture::new(w, h, |_, _| {
            [0; 4].map(|_| match baked.pick(&[0u8, 1, 2, 3]) {
                0 => 255,
                1 => 0,
                _ => baked.byte(0.0, 1.0),
            })
        });
        // The lightmaps, twice the scene's size, read through uv · ½ + offset (texel x + w/2
        // for the baked one, x + w for the realtime one): RGBM multipliers that decode to
        // 0.2-3.4, realtime texels to 0-1.5, directional maps of every direction. Their own
        // generator, so the other maps stay what they were.
        let mut lm = Rng::new(seed ^ 0x11_6d_4a_95);
        let baked_map = MapTexture::new(2 * w, 2 * h, |_, _| {
            [
                lm.byte(0.0, 1.0),
                lm.byte(0.0, 1.0),
                lm.byte(0.0, 1.0),
                lm.byte(0.1, 0.35),
            ]
        });
        let realtime_map = MapTexture::new(2 * w, 2 * h, |_, _| {
            [
                lm.byte(0.0, 1.0),
                lm.byte(0.0, 1.0),
                lm.byte(0.0, 1.0),
                lm.byte(0.2, 0.6),
            ]
        });
        let mut dir_map = || {
            MapTexture::new(2 * w, 2 * h, |_, _| {
                [
                    lm.byte(0.0, 1.0),
                    lm.byte(0.0, 1.0),
                    lm.byte(0.0, 1.0),
                    lm.byte(0.3, 1.0),
                ]
            })
        };
        let (baked_dir, realtime_dir) = (dir_map(), dir_map());
        let lightmaps = [baked_map, baked_dir, realtime_map, realtime_dir];
        let lightmap_st = [
            Vec4::new(0.5, 0.5, 0.25, 0.25),
            Vec4::new(0.5, 0.5, 0.5, 0.0),
        ];

        let scene = Scene {
            camera_position: Vec3::new(0.75, -0.5, 6.0),
            sh_r: Vec4::new(0.05, 0.12, 0.20, 0.30),
            sh_g: Vec4::new(0.03, 0.10, 0.18, 0.28),
            sh_b: Vec4::new(0.08, 0.05, 0.22, 0.34),
            light_dir: Vec3::new(-0.3, 0.4, 0.87).normalize(),
            light_color: Vec3::new(0.9, 0.85, 0.75),
            probes: [
                Probe {
                    forward_weight: 0.625,
                    ..probe(
                        Vec3::new(0.25, 0.0, -2.0),
                        Vec3::new(-3.0, -3.5, -0.5),
                        Vec3::new(4.0, 3.0, 5.0),
                        true,
                        Vec3::new(4.0, 1.0, 1.0),
                        1.0,
                        1,
                    )
                },
                probe(
                    Vec3::ZERO,
                    Vec3::splat(-8.0),
                    Vec3::splat(8.0),
                    false,
                    Vec3::new(2.0, 2.2, 1.0),
                    1.0,
                    1,
                ),
            ],
            // RGBM baked lightmaps (desktop, linear colour space); realtime texels through
            // pow(2 · a · rgb, 2.2).
            lightmap_decode: LightmapDecode {
                baked: LightmapDecode::RGBM_LINEAR,
                realtime: Vec4::new(2.0, 2.2, 0.0, 0.0),
            },
            cubes: [
                cube([
                    [230, 60, 40, 128],
                    [40, 200, 70, 96],
                    [60, 90, 240, 160],
                    [220, 210, 50, 64],
                    [180, 180, 200, 112],
                    [90, 40, 150, 200],
                ]),
                cube([
                    [250, 120, 20, 200],
                    [20, 140, 220, 180],
                    [200, 230, 255, 240],
                    [60, 40, 30, 220],
                    [120, 200, 160, 190],
                    [255, 80, 160, 170],
                ]),
            ],
        };

        // Deferred probes (given out of draw order on purpose): a b = 0 box with edges on pixel
        // centres, a large sky box, a medium box with a blend zone, and an important box larger
        // than the medium one that still draws last.
        let deferred_probes = vec![
            (
                probe(
                    Vec3::new(0.75, -0.125, 0.0),
                    Vec3::new(0.125, -0.875, -0.5),
                    Vec3::new(1.375, 0.625, 0.5),
                    false,
                    Vec3::new(2.0, 2.2, 1.0),
                    0.0,
                    1,
                ),
                cube([
                    [255, 255, 255, 128],
                    [255, 0, 0, 255],
                    [0, 255, 0, 255],
                    [0, 0, 255, 255],
                    [255, 160, 40, 200],
                    [128, 128, 128, 255],
                ]),
            ),
            (
                probe(
                    Vec3::new(-0.5, -1.0, -2.0),
                    Vec3::new(-1.25, -2.5, -2.0),
                    Vec3::new(0.5, 0.0, 2.0),
                    true,
                    Vec3::new(1.0, 1.0, 0.0),
                    0.5,
                    2,
                ),
                cube([
                    [40, 220, 220, 255],
                    [220, 40, 220, 255],
                    [220, 220, 40, 255],
                    [40, 40, 220, 255],
                    [230, 140, 180, 255],
                    [30, 30, 30, 255],
                ]),
            ),
            (
                probe(
                    Vec3::new(0.0, 0.0, -3.0),
                    Vec3::new(-10.0, -10.0, -4.0),
                    Vec3::new(10.0, 10.0, 8.0),
                    true,
                    Vec3::new(1.0, 1.0, 0.0),
                    1.0,
                    1,
                ),
                cube([
                    [120, 150, 200, 255],
                    [110, 140, 190, 255],
                    [170, 200, 250, 255],
                    [70, 60, 50, 255],
                    [150, 180, 230, 255],
                    [90, 80, 70, 255],
                ]),
            ),
            (
                probe(
                    Vec3::new(0.25, 0.0, -1.5),
                    Vec3::new(-1.0, -1.0, -1.0),
                    Vec3::new(1.5, 1.25, 1.0),
                    true,
                    Vec3::new(4.0, 1.0, 1.0),
                    0.75,
                    1,
                ),
                cube([
                    [255, 200, 100, 100],
                    [100, 255, 200, 120],
                    [200, 100, 255, 140],
                    [255, 255, 100, 60],
                    [100, 200, 255, 90],
                    [255, 100, 100, 110],
                ]),
            ),
        ];

        // The quad: object space [-1, 1]², scaled by 2 and moved to the centre.
        let centre = Vec2::new(0.5, -0.25);
        let half_size = 2.0;
        let model =
            Mat4::from_translation(centre.extend(0.0)) * Mat4::from_scale(Vec3::splat(half_size));
        let normal_matrix = Mat4::from_scale(Vec3::splat(1.0 / half_size));
        // Orthographic: world (x, y, z) -> clip ((x - cx) / s, (y - cy) / s), depth 0.5 - z / 4
        // (a box 4 deep around the quad, whose plane z = 0 lies at depth 0.5; invertible, so
        // the deferred passes can rebuild positions from depth).
        let view_proj = Mat4::from_cols(
            Vec4::new(1.0 / half_size, 0.0, 0.0, 0.0),
            Vec4::new(0.0, 1.0 / half_size, 0.0, 0.0),
            Vec4::new(0.0, 0.0, -0.25, 0.0),
            Vec4::new(-centre.x / half_size, -centre.y / half_size, 0.5, 1.0),
        );

        let mut scene = TestScene {
            width: w,
            height: h,
            material,
            detail_st,
            maps: Maps {
                main_tex,
                metallic_map,
                normal_map,
                occlusion_map,
                emission_map,
                detail_mask,
                detail_albedo,
                detail_normal,
                shadowmask,
                lightmaps,
                lightmap_st,
            },
            scene,
            deferred_probes,
            model,
            normal_matrix,
            view_proj,
            object_normal: Vec3::new(0.1, -0.05, 1.0),
            object_tangent: Vec4::new(1.0, 0.1, -0.1, -1.0),
            centre,
            half_size,
        };
        scene.keep_reflections_off_edges(&mut rng);
        scene
    }

    /// World position of the centre of pixel `(x, y)` (row 0 at the top), exact in `f32`.
    pub fn world_position(&self, x: u32, y: u32) -> Vec3 {
        let ndc_x = (2 * x + 1) as f32 / self.width as f32 - 1.0;
        let ndc_y = 1.0 - (2 * y + 1) as f32 / self.height as f32;
        Vec3::new(
            self.centre.x + self.half_size * ndc_x,
            self.centre.y + self.half_size * ndc_y,
            0.0,
        )
    }

    /// The texel of the detail maps that pixel `(x, y)` samples: `uv · tiling + offset` in
    /// texels is `2x + 3 + ½`, repeating.
    pub fn detail_texel(&self, x: u32, y: u32) -> (u32, u32) {
        let w = self.maps.detail_albedo.width;
        let h = self.maps.detail_albedo.height;
        let texel = |p: u32, size: u32, tiling: f32, offset: f32| {
            let u = (p as f32 + 0.5) / size as f32 * tiling + offset;
            let t = (u * size as f32).floor() as i64;
            t.rem_euclid(i64::from(size)) as u32
        };
        (
            texel(x, w, self.detail_st.x, self.detail_st.z),
            texel(y, h, self.detail_st.y, self.detail_st.w),
        )
    }

    /// The texel of `map` that pixel `(x, y)` reads at the uv `uv · st.xy + st.zw` (clamped),
    /// as a nearest sampler picks it.
    pub fn st_texel(&self, map: &MapTexture, st: Vec4, x: u32, y: u32) -> Vec4 {
        let texel = |p: u32, pixels: u32, size: u32, scale: f32, offset: f32| {
            let u = (p as f32 + 0.5) / pixels as f32 * scale + offset;
            ((u * size as f32).floor().max(0.0) as u32).min(size - 1)
        };
        map.get(
            texel(x, self.width, map.width, st.x, st.z),
            texel(y, self.height, map.height, st.y, st.w),
        )
    }

    /// The baked occlusion pixel `(x, y)` stores in RT4: the shadowmask at the mesh uv, or at
    /// the lightmap uv with `LIGHTMAP_ON` (the shadowmask shares the lightmap's layout).
    pub fn shadowmask_texel(&self, lightmapped: bool, x: u32, y: u32) -> Vec4 {
        if lightmapped {
            self.st_texel(&self.maps.shadowmask, self.maps.lightmap_st[0], x, y)
        } else {
            self.maps.shadowmask.get(x, y)
        }
    }

    /// The texels pixel `(x, y)` reads.
    pub fn texels(&self, x: u32, y: u32) -> Texels {
        let m = &self.maps;
        let (dx, dy) = self.detail_texel(x, y);
        let [baked, baked_dir, realtime, realtime_dir] = &m.lightmaps;
        let [st, dynamic_st] = m.lightmap_st;
        Texels {
            main_tex: m.main_tex.get(x, y),
            metallic_map: m.metallic_map.get(x, y),
            normal_map: m.normal_map.get(x, y),
            occlusion_map: m.occlusion_map.get(x, y),
            emission_map: m.emission_map.get(x, y),
            detail_mask: m.detail_mask.get(x, y),
            detail_albedo: m.detail_albedo.get(dx, dy),
            detail_normal: m.detail_normal.get(dx, dy),
            lightmap: LightmapTexels {
                baked: self.st_texel(baked, st, x, y),
                baked_dir: self.st_texel(baked_dir, st, x, y),
                realtime: self.st_texel(realtime, dynamic_st, x, y),
                realtime_dir: self.st_texel(realtime_dir, dynamic_st, x, y),
            },
        }
    }

    /// The interpolated vertex data at pixel `(x, y)`: the world position, and the vertex
    /// normal and tangent transformed as the vertex shader does (the quad's frame is constant).
    pub fn geometry(&self, x: u32, y: u32) -> Geometry {
        let normal = (self.normal_matrix * self.object_normal.extend(0.0)).truncate();
        let tangent = (self.model * self.object_tangent.truncate().extend(0.0)).truncate();
        Geometry {
            world_position: self.world_position(x, y),
            normal,
            tangent: tangent.extend(self.object_tangent.w),
        }
    }

    /// Every pixel `(x, y)`, row by row.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        (0..self.height).flat_map(move |y| (0..self.width).map(move |x| (x, y)))
    }

    /// The smallest [`face_margin`] of every cube lookup at pixel `(x, y)` over the normal
    /// keyword combinations: the forward probes (box projection against the un-grown box) and
    /// the deferred probes that reach the pixel (falloff > 0; elsewhere the blend keeps the
    /// previous value whatever the sample), each with the surface normal and with the normal as
    /// the 10-bit RT2 stores it.
    pub fn face_margin_at(&self, x: u32, y: u32) -> f32 {
        let texels = self.texels(x, y);
        let geometry = self.geometry(x, y);
        let p = geometry.world_position;
        let mut margin = f32::INFINITY;
        for (normal_map, detail_normal, detail_mask) in NORMAL_COMBINATIONS {
            let kw = Keywords {
                normal_map,
                detail_normal,
                detail_mask,
                ..Keywords::default()
            };
            let n = surface(&kw, &self.material, &texels, &geometry).normal;
            let stored = encode_normal(n)
                .to_array()
                .map(|c| unorm_to_f32(unorm(c, 10), 10));
            for normal in [n, decode_normal(Vec3::from_array(stored))] {
                let (_, r) = view_and_reflection(self.scene.camera_position, p, normal);
                for probe in &self.scene.probes {
                    margin = margin.min(face_margin(box_project(r, p, probe)));
                }
                for (probe, _) in self
                    .deferred_probes
                    .iter()
                    .filter(|(probe, _)| falloff(p, probe) > 0.0)
                {
                    margin = margin.min(face_margin(box_project_grown(r, p, probe)));
                }
            }
        }
        margin
    }

    /// Redraws normal-map and detail-normal texels until every pixel's lookups are at least
    /// [`MIN_FACE_MARGIN`] from a face edge.
    fn keep_reflections_off_edges(&mut self, rng: &mut Rng) {
        for _attempt in 0..10_000 {
            let Some((x, y)) = self
                .pixels()
                .find(|&(x, y)| self.face_margin_at(x, y) < MIN_FACE_MARGIN)
            else {
                return;
            };
            // Without normal maps the margin depends on the geometry alone.
            let flat = Keywords::default();
            let g = self.geometry(x, y);
            let n = surface(&flat, &self.material, &self.texels(x, y), &g).normal;
            let (_, r) = view_and_reflection(self.scene.camera_position, g.world_position, n);
            assert!(
                self.scene
                    .probes
                    .iter()
                    .map(|p| face_margin(box_project(r, g.world_position, p)))
                    .chain(
                        self.deferred_probes
                            .iter()
                            .filter(|(p, _)| falloff(g.world_position, p) > 0.0)
                            .map(|(p, _)| face_margin(box_project_grown(r, g.world_position, p)))
                    )
                    .all(|m| m >= MIN_FACE_MARGIN),
                "pixel ({x}, {y}) reflects near a cube-face edge without any normal map; move the camera or the probes"
            );
            let texel = normal_texel(rng, 0.45);
            self.maps.normal_map.set(x, y, texel);
            let (dx, dy) = self.detail_texel(x, y);
            let texel = normal_texel(rng, 0.35);
            self.maps.detail_normal.set(dx, dy, texel);
        }
        panic!("could not keep the test scene's reflections away from cube-face edges");
    }

    /// The quad's vertex buffer: 6 vertices (two triangles) with position vec3f @location(0),
    /// normal vec3f @1, tangent vec4f @2 and uv vec2f @3, in object space.
    pub fn quad(&self) -> VertexBuffer {
        let n = self.object_normal;
        let t = self.object_tangent;
        // Object (-1, 1) is the top-left corner (uv 0, 0).
        let corner = |ox: f32, oy: f32| {
            [
                ox,
                oy,
                0.0,
                n.x,
                n.y,
                n.z,
                t.x,
                t.y,
                t.z,
                t.w,
                (ox + 1.0) * 0.5,
                (1.0 - oy) * 0.5,
            ]
        };
        let (tl, tr, bl, br) = (
            corner(-1.0, 1.0),
            corner(1.0, 1.0),
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
        );
        VertexBuffer::from_f32(&[(0, 3), (1, 3), (2, 4), (3, 2)], &[tl, bl, tr, tr, bl, br])
    }

    /// Every resource of the standard shader's passes (bindings of `wgsl/standard/bindings.wgsl`);
    /// a pass binds only those its variant uses.
    pub fn standard_resources(&self) -> Vec<BoundResource> {
        StandardBindings {
            view_proj: self.view_proj,
            scene: &self.scene,
            material: &self.material,
            detail_st: self.detail_st,
            maps: &self.maps,
            model: self.model,
            normal_matrix: self.normal_matrix,
        }
        .resources()
    }

    /// The depth buffer of the scene's camera: each pixel's clip-space `z / w` (the quad
    /// covers every pixel), one `f32` per pixel, row by row — what the deferred reflection pass
    /// rebuilds world positions from.
    pub fn depth_buffer(&self) -> Vec<f32> {
        self.pixels()
            .map(|(x, y)| {
                let clip = self.view_proj * self.world_position(x, y).extend(1.0);
                clip.z / clip.w
            })
            .collect()
    }
}

impl Default for TestScene {
    fn default() -> TestScene {
        TestScene::new(DEFAULT_SEED)
    }
}

/// What one draw of the standard shader binds (`wgsl/standard/bindings.wgsl`): the camera, the
/// per-frame lighting and probes of `scene`, the material with its maps, and the object.
#[derive(Clone, Copy, Debug)]
pub struct StandardBindings<'a> {
    /// World-to-clip transform.
    pub view_proj: Mat4,
    /// Camera position, ambient light, main light, the two probes and their cubes.
    pub scene: &'a Scene,
    /// The material's uniforms.
    pub material: &'a Material,
    /// Detail tiling (xy) and offset (zw).
    pub detail_st: Vec4,
    /// The material's textures.
    pub maps: &'a Maps,
    /// Object-to-world transform.
    pub model: Mat4,
    /// Inverse transpose of `model` (for normals).
    pub normal_matrix: Mat4,
}

impl StandardBindings<'_> {
    /// Every resource of the standard shader's passes; a pass binds only those its variant
    /// uses.
    pub fn resources(&self) -> Vec<BoundResource> {
        let s = self.scene;
        let m = self.material;
        let mut camera = Vec::new();
        push_mat4(&mut camera, self.view_proj);
        push_vec4(&mut camera, s.camera_position.extend(1.0));
        let mut lighting = Vec::new();
        for v in [
            s.sh_r,
            s.sh_g,
            s.sh_b,
            s.light_dir.extend(0.0),
            s.light_color.extend(1.0),
        ] {
            push_vec4(&mut lighting, v);
        }
        let mut probes = Vec::new();
        for p in &s.probes {
            push_probe(&mut probes, p);
        }
        let mut material = Vec::new();
        for v in [
            m.tint,
            m.emission.extend(0.0),
            Vec4::new(m.metallic, m.smoothness, m.cutoff, m.occlusion_strength),
            Vec4::new(m.bump_scale, m.detail_bump_scale, 0.0, 0.0),
            self.detail_st,
        ] {
            push_vec4(&mut material, v);
        }
        let mut object = Vec::new();
        push_mat4(&mut object, self.model);
        push_mat4(&mut object, self.normal_matrix);
        let maps = self.maps;
        let mut lightmap = Vec::new();
        for v in [
            maps.lightmap_st[0],
            maps.lightmap_st[1],
            s.lightmap_decode.baked,
            s.lightmap_decode.realtime,
        ] {
            push_vec4(&mut lightmap, v);
        }
        let [baked, baked_dir, realtime, realtime_dir] = &maps.lightmaps;
        vec![
            BoundResource::new(0, 0, Resource::Uniform(camera)),
            BoundResource::new(0, 1, Resource::Uniform(lighting)),
            BoundResource::new(0, 2, Resource::Uniform(probes)),
            BoundResource::new(0, 3, cube_resource(&s.cubes[0])),
            BoundResource::new(0, 4, cube_resource(&s.cubes[1])),
            BoundResource::new(0, 5, Resource::Sampler { nearest: true }),
            BoundResource::new(1, 0, Resource::Uniform(material)),
            BoundResource::new(
                1,
                1,
                Resource::SamplerAddressed {
                    nearest: true,
                    address_mode: wgpu::AddressMode::Repeat,
                },
            ),
            BoundResource::new(1, 2, maps.main_tex.resource()),
            BoundResource::new(1, 3, maps.metallic_map.resource()),
            BoundResource::new(1, 4, maps.normal_map.resource()),
            BoundResource::new(1, 5, maps.occlusion_map.resource()),
            BoundResource::new(1, 6, maps.emission_map.resource()),
            BoundResource::new(1, 7, maps.detail_mask.resource()),
            BoundResource::new(1, 8, maps.detail_albedo.resource()),
            BoundResource::new(1, 9, maps.detail_normal.resource()),
            BoundResource::new(2, 0, Resource::Uniform(object)),
            BoundResource::new(2, 1, maps.shadowmask.resource()),
            BoundResource::new(2, 2, Resource::Uniform(lightmap)),
            BoundResource::new(2, 3, baked.resource()),
            BoundResource::new(2, 4, baked_dir.resource()),
            BoundResource::new(2, 5, realtime.resource()),
            BoundResource::new(2, 6, realtime_dir.resource()),
            BoundResource::new(2, 7, Resource::Sampler { nearest: true }),
            brdf_lut_resource(),
        ]
    }
}

/// The BRDF3 lookup table (`wgsl/lighting/brdf_lut.wgsl`, group 0 binding 17): the `R16Float`
/// texels of [`wgsl_variants_shaders::brdf_lut::texels_f16`], generated once per process.
pub fn brdf_lut_resource() -> BoundResource {
    use wgsl_variants_shaders::brdf_lut::{HEIGHT, WIDTH, texels_f16};
    static BYTES: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let data = BYTES.get_or_init(|| {
        texels_f16()
            .into_iter()
            .flat_map(u16::to_le_bytes)
            .collect()
    });
    BoundResource::new(
        0,
        17,
        Resource::Texture2d {
            format: wgpu::TextureFormat::R16Float,
            width: WIDTH,
            height: HEIGHT,
            data: data.clone(),
        },
    )
}

/// Appends a `vec4f`.
pub fn push_vec4(out: &mut Vec<u8>, v: Vec4) {
    out.extend(v.to_array().into_iter().flat_map(f32::to_le_bytes));
}

/// Appends a `mat4x4f` (column-major, as WGSL stores it).
pub fn push_mat4(out: &mut Vec<u8>, m: Mat4) {
    out.extend(m.to_cols_array().into_iter().flat_map(f32::to_le_bytes));
}

/// Appends a `Probe` record of `wgsl/deferred/probe.wgsl` (5 × vec4f): position, box_min with
/// the forward weight in w, box_max, hdr `(x, y, 0, w)`, params `(box projection, blend
/// distance, importance, 0)`.
pub fn push_probe(out: &mut Vec<u8>, p: &Probe) {
    push_vec4(out, p.position.extend(0.0));
    push_vec4(out, p.box_min.extend(p.forward_weight));
    push_vec4(out, p.box_max.extend(0.0));
    push_vec4(out, Vec4::new(p.hdr.x, p.hdr.y, 0.0, p.hdr.z));
    push_vec4(
        out,
        Vec4::new(
            if p.box_projection { 1.0 } else { 0.0 },
            p.blend_distance,
            p.importance as f32,
            0.0,
        ),
    );
}

/// A cube texture with one colour per face on every mip level ([`CUBE_SIZE`] down to 1).
pub fn cube_resource(cube: &CubeFaces) -> Resource {
    let levels = (0..)
        .map(|level| (CUBE_SIZE >> level).max(1))
        .take((32 - CUBE_SIZE.leading_zeros()) as usize)
        .map(|size| {
            std::array::from_fn(|face| {
                let colour = cube.0[face].to_array().map(|c| unorm(c, 8) as u8);
                colour.repeat((size * size) as usize)
            })
        })
        .collect();
    Resource::TextureCube {
        format: wgpu::TextureFormat::Rgba8Unorm,
        size: CUBE_SIZE,
        levels,
    }
}

/// A 2D texture resource from target bytes.
pub(crate) fn texture(format: TargetFormat, width: u32, height: u32, data: &[u8]) -> Resource {
    Resource::Texture2d {
        format: format.wgpu_format(),
        width,
        height,
        data: data.to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_is_deterministic_and_off_edges() {
        let a = TestScene::default();
        let b = TestScene::default();
        assert_eq!(a.maps, b.maps);
        let worst = a
            .pixels()
            .map(|(x, y)| a.face_margin_at(x, y))
            .fold(f32::INFINITY, f32::min);
        assert!(worst >= MIN_FACE_MARGIN, "{worst}");
    }

    #[test]
    fn pixel_centres_are_exact() {
        let s = TestScene::default();
        assert_eq!(s.world_position(0, 0), Vec3::new(-1.375, 1.625, 0.0));
        let last = s.width - 1;
        assert_eq!(s.world_position(last, last), Vec3::new(2.375, -2.125, 0.0));
        // Clip space of a pixel centre through view_proj.
        let clip = s.view_proj * s.world_position(3, 5).extend(1.0);
        assert_eq!(clip.x, (2.0 * 3.0 + 1.0) / 16.0 - 1.0);
        assert_eq!(clip.y, 1.0 - (2.0 * 5.0 + 1.0) / 16.0);
        assert_eq!(s.detail_texel(0, 0), (3, 3));
        assert_eq!(s.detail_texel(7, 1), (1, 5));
    }

    #[test]
    fn alpha_never_sits_on_the_cutoff() {
        let s = TestScene::default();
        let mut kept = 0;
        for (x, y) in s.pixels() {
            let alpha = s.material.tint.w * s.texels(x, y).main_tex.w;
            assert!((alpha - s.material.cutoff).abs() >= CUTOFF_MARGIN);
            kept += usize::from(alpha >= s.material.cutoff);
        }
        let n = (s.width * s.height) as usize;
        assert!(kept > n / 2 && kept < n, "{kept} of {n} kept");
    }
}
