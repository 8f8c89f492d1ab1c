//! The frame's scene, made by code: a floor, two spheres and two boxes, each with its own
//! keyword set and material (the floor lightmapped with a directional baked lightmap, one box
//! with a realtime lightmap), and two semi-transparent objects (a `Fade` sphere, a
//! `Transparent` box) drawn after them, seen by a perspective camera; the ambient light, the
//! directional main light (with a hard screen-space shadow) and the two reflection probes of
//! [`Scene`]; and four per-pixel lights (a directional light with a 2D cookie and a soft
//! screen-space shadow, a point light with a cube shadow, a point light with a cube cookie, a
//! spot with a soft shadow).
//!
//! Every map of an object (its lightmaps too) is one texel (`Rgba8Unorm`, exact in 8 bits), so
//! a sample does not depend on the uv the rasterizer interpolates: the keywords still change
//! the surface (a tilted normal map, a detail albedo, a metallic map …), and the only
//! per-pixel inputs left are the interpolated position, normal and tangent — which the CPU
//! reference gets by casting the pixel's ray against the same triangles
//! ([`FrameScene::cast_through`]).

use glam::{DMat4, DVec3, Mat4, Vec3, Vec4};

use super::super::camera::{deferred_camera, pixel_ray};
use super::super::scene::{MapTexture, Maps, Rng, StandardBindings, cube, cube_resource, probe};
use super::super::skybox::Sky;
use super::shadow::ShadowSpec;
use crate::{BoundResource, Resource, VertexBuffer};
use wgsl_variants_shaders::reference::brdf::Brdf;
use wgsl_variants_shaders::reference::cascades::CascadeCamera;
use wgsl_variants_shaders::reference::cube::CubeFaces;
use wgsl_variants_shaders::reference::light::{
    Cookie2d, Light, LightError, LightParams, LightShape, LightType, look_at_rh, perspective_rh,
};
use wgsl_variants_shaders::reference::lightmap::{LightmapDecode, LightmapTexels};
use wgsl_variants_shaders::reference::probe::Probe;
use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
use wgsl_variants_shaders::reference::shadow_fade::{FadeDistance, ShadowFade};
use wgsl_variants_shaders::reference::skybox::Skybox;
use wgsl_variants_shaders::reference::surface::{
    Geometry, Keywords, Material, RenderingMode, Scene, SmoothnessSource, Texels,
};

/// Width of the frame in pixels.
pub const FRAME_WIDTH: u32 = 64;

/// Height of the frame in pixels.
pub const FRAME_HEIGHT: u32 = 48;

/// One vertex as the standard shader reads it: position (3), normal (3), tangent (4, w the
/// bitangent sign), uv (2), in object space.
pub type Vertex = [f32; 12];

/// One object of the frame.
#[derive(Clone, Debug)]
pub struct FrameObject {
    /// A name for reports.
    pub name: &'static str,
    /// The material keywords (opaque or cutout; HDR and reflection buffers are the frame's).
    pub keywords: Keywords,
    /// The material's uniforms.
    pub material: Material,
    /// The one texel of each map.
    pub texels: [[u8; 4]; 8],
    /// The one texel of each lightmap: baked, its directional map, realtime, its directional
    /// map ([`NO_LIGHTMAPS`] for an object without lightmap keywords).
    pub lightmaps: [[u8; 4]; 4],
    /// The object's layer (0–31, Unity's `GameObject.layer`; 0 is `Default`): the lights whose
    /// [`FrameLight::culling_mask`] leaves it out do not light it.
    pub layer: u32,
    /// Object-to-world transform (rotation, uniform scale and translation).
    pub model: Mat4,
    /// The triangle list, three vertices per triangle.
    pub vertices: Vec<Vertex>,
}

impl FrameObject {
    /// Inverse transpose of `model`.
    pub fn normal_matrix(&self) -> Mat4 {
        self.model.inverse().transpose()
    }

    /// The texels as the reference reads them (`code / 255`).
    pub fn reference_texels(&self) -> Texels {
        let value = |c: [u8; 4]| Vec4::from_array(c.map(|x| unorm_to_f32(u32::from(x), 8)));
        let t = self.texels.map(value);
        let lm = self.lightmaps.map(value);
        Texels {
            main_tex: t[0],
            metallic_map: t[1],
            normal_map: t[2],
            occlusion_map: t[3],
            emission_map: t[4],
            detail_mask: t[5],
            detail_albedo: t[6],
            detail_normal: t[7],
            lightmap: LightmapTexels {
                baked: lm[0],
                baked_dir: lm[1],
                realtime: lm[2],
                realtime_dir: lm[3],
            },
        }
    }

    /// The maps as textures of one texel each.
    pub fn maps(&self) -> Maps {
        let map = |i: usize| MapTexture::new(1, 1, |_, _| self.texels[i]);
        let lightmaps = self.lightmaps.map(|c| MapTexture::new(1, 1, |_, _| c));
        // One texel: any scale and offset read it.
        let lightmap_st = [Vec4::new(1.0, 1.0, 0.0, 0.0); 2];
        Maps {
            main_tex: map(0),
            metallic_map: map(1),
            normal_map: map(2),
            occlusion_map: map(3),
            emission_map: map(4),
            detail_mask: map(5),
            detail_albedo: map(6),
            detail_normal: map(7),
            // Unoccluded: the frame's materials do not use the Shadowmask modes.
            shadowmask: MapTexture::new(1, 1, |_, _| [255; 4]),
            lightmaps,
            lightmap_st,
        }
    }

    /// The mesh as a vertex buffer (`@location` 0 to 3).
    pub fn mesh(&self) -> VertexBuffer {
        VertexBuffer::from_f32(&[(0, 3), (1, 3), (2, 4), (3, 2)], &self.vertices)
    }
}

/// One per-pixel light of the frame (drawn by ForwardAdd forward, by a Lighting draw deferred).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameLight {
    /// A name for reports.
    pub name: &'static str,
    /// Its light keyword.
    pub light_type: LightType,
    /// The light as a renderer describes it (its volume comes from this).
    pub light: Light,
    /// What the shaders read (`light.params()`).
    pub params: LightParams,
    /// Its shadow, if it casts one (spot and point lights).
    pub shadow: Option<ShadowSpec>,
    /// The layers it lights, one bit per layer (Unity's `Light.cullingMask`; every bit set:
    /// `Everything`). The mask decides what the light illuminates; every opaque object casts
    /// into its shadow map regardless.
    pub culling_mask: u32,
}

impl FrameLight {
    /// The light `light` of type `light_type`.
    ///
    /// # Errors
    /// The light's [`LightError`] when its parameters make the math undefined.
    pub fn new(
        name: &'static str,
        light_type: LightType,
        light: Light,
    ) -> Result<FrameLight, LightError> {
        Ok(FrameLight {
            name,
            light_type,
            params: light.params()?,
            light,
            shadow: None,
            culling_mask: u32::MAX,
        })
    }

    /// The light leaving out the objects on `layers` (its culling mask without their bits).
    pub fn excluding(mut self, layers: &[u32]) -> FrameLight {
        for layer in layers {
            self.culling_mask &= !(1u32 << layer);
        }
        self
    }

    /// Whether the light lights `object` (its culling mask has the object's layer).
    ///
    /// ```
    /// # use wgsl_variants_gpu::check::frame::FrameScene;
    /// let frame = FrameScene::new();
    /// let glowing = &frame.objects[2];
    /// assert!(frame.lights[0].lights(glowing) && !frame.lights[2].lights(glowing));
    /// ```
    pub fn lights(&self, object: &FrameObject) -> bool {
        self.culling_mask & (1u32 << object.layer) != 0
    }

    /// The light casting `shadow`.
    pub fn with_shadow(mut self, shadow: ShadowSpec) -> FrameLight {
        self.shadow = Some(shadow);
        self
    }
}

/// What a pixel's ray hits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The object's index in [`FrameScene::objects`].
    pub object: usize,
    /// The interpolated vertex data at the hit, in world space.
    pub geometry: Geometry,
}

/// The whole frame: camera, per-frame lighting, objects and lights.
#[derive(Clone, Debug)]
pub struct FrameScene {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// World-to-clip transform (perspective, depth 0 at the near plane).
    pub view_proj: Mat4,
    /// Camera position, ambient light, the main (directional) light, the probes and cubes.
    pub scene: Scene,
    /// The main light as a `DIRECTIONAL` light (the deferred path's first Lighting draw).
    pub main_light: LightParams,
    /// The main light as a renderer describes it (for its shadow map).
    pub main_light_source: Light,
    /// The main light's shadow (`SHADOWS_SCREEN`: ForwardBase and the deferred path's first
    /// Lighting draw read its screen-space mask).
    pub main_shadow: Option<ShadowSpec>,
    /// The layers the main light lights, one bit per layer (as [`FrameLight::culling_mask`]):
    /// an object it leaves out keeps its ForwardBase draw with a black main light (ambient,
    /// probes, lightmaps and emission stay), and the deferred path's main-light draw skips
    /// its pixels through the stencil ([`FrameScene::main_lights`]).
    pub main_culling_mask: u32,
    /// The view depths that cut the camera's view into the directional shadows' four
    /// cascades ([`FRAME_SPLITS`]; the last is the shadow distance, where the fade ends).
    pub cascade_splits: Vec<f32>,
    /// The shadow distance fade every shadowed light's receivers read (Unity's one per
    /// camera): by view depth, from [`FRAME_FADE`]'s start to its end.
    pub shadow_fade: ShadowFade,
    /// The per-pixel lights.
    pub lights: Vec<FrameLight>,
    /// The opaque and cutout objects, drawn in this order (they cast shadows).
    pub objects: Vec<FrameObject>,
    /// The semi-transparent objects (`Fade` and `Transparent`), drawn after the opaque ones
    /// in [`FrameScene::transparent_order`] with blending and no depth writes; they neither
    /// cast nor receive shadows (Unity's transparent queue).
    pub transparent: Vec<FrameObject>,
    /// The background (`skybox/Cubemap`) where no surface is drawn: after the opaque objects,
    /// before the semi-transparent ones; `None` leaves the background empty.
    pub sky: Option<Sky>,
    /// The 2D cookie of `DIRECTIONAL_COOKIE` lights (`Rgba8Unorm`, alpha read; nearest,
    /// repeating).
    pub cookie: MapTexture,
    /// The cube cookie of `POINT_COOKIE` lights (one alpha per face).
    pub cube_cookie: CubeFaces,
    /// The Standard BRDF's tier of every lit draw: one per frame, as Unity's graphics tier
    /// ([`FrameScene::with_brdf`]; default BRDF1).
    pub brdf: Brdf,
}

/// The layer of the frame's glowing sphere, which the light culling masks of the main light
/// and the cookie sun (drawn full screen deferred) and of the cool point light (drawn as its
/// volume) leave out.
pub const LAYER_SHELTERED: u32 = 8;

/// The layer of the frame's glass sphere, which the warm point light's culling mask leaves
/// out (a semi-transparent object: its ForwardAdd draw for that light is skipped).
pub const LAYER_GLASS: u32 = 9;

/// The view depths where the frame's shadows start to fade and where they are gone (the
/// shadow distance, [`FRAME_SPLITS`]'s last): the view's centre lies at depth 7.5, so the
/// nearer half of the frame keeps its realtime shadows and the farther half fades part of them.
pub const FRAME_FADE: (f32, f32) = (7.0, 12.0);

/// The cascade splits of the frame's directional shadows: the near plane, three splits, and
/// the shadow distance. Each cascade holds part of the visible surfaces (a unit test counts
/// them), so the frame crosses every seam.
pub const FRAME_SPLITS: [f32; 5] = [1.0, 5.5, 6.8, 8.3, 12.0];

/// A unit normal's tangent-space texel (8-bit codes of `n · 0.5 + 0.5`).
fn normal_texel(tx: f32, ty: f32) -> [u8; 4] {
    let tz = (1.0 - tx * tx - ty * ty).sqrt();
    let code = |v: f32| ((v * 0.5 + 0.5) * 255.0).round() as u8;
    [code(tx), code(ty), code(tz), 255]
}

/// The default texels: white maps, flat normals.
const WHITE: [u8; 4] = [255; 4];

/// The lightmaps of an object without lightmap keywords (never read): black RGBM texels and
/// flat directional maps.
pub const NO_LIGHTMAPS: [[u8; 4]; 4] = [
    [0, 0, 0, 255],
    [128, 128, 128, 255],
    [0, 0, 0, 255],
    [128, 128, 128, 255],
];
const FLAT: [u8; 4] = [128, 128, 255, 255];

/// A UV sphere of radius 1 around the origin: `stacks × slices` quads, smooth normals, tangents
/// along increasing longitude.
fn sphere(stacks: u32, slices: u32) -> Vec<Vertex> {
    let vertex = |i: u32, j: u32| -> Vertex {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        let phi = std::f32::consts::TAU * j as f32 / slices as f32;
        let n = Vec3::new(
            phi.cos() * theta.sin(),
            theta.cos(),
            phi.sin() * theta.sin(),
        );
        let t = Vec3::new(-phi.sin(), 0.0, phi.cos());
        [
            n.x,
            n.y,
            n.z,
            n.x,
            n.y,
            n.z,
            t.x,
            t.y,
            t.z,
            1.0,
            j as f32 / slices as f32,
            i as f32 / stacks as f32,
        ]
    };
    let mut out = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i, j + 1),
                vertex(i + 1, j + 1),
            );
            // Counter-clockwise seen from outside (wgpu's front faces): the semi-transparent
            // objects cull their back faces.
            out.extend([a, c, b, c, d, b]);
        }
    }
    out
}

/// The unit cube `[−1, 1]³`: six flat faces, each two triangles, tangent along the face's u.
fn cube_mesh() -> Vec<Vertex> {
    let mut out = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let mut u = Vec3::ZERO;
            u[(axis + 1) % 3] = 1.0;
            let v = n.cross(u);
            let corner = |a: f32, b: f32| -> Vertex {
                let p = n + u * a + v * b;
                [
                    p.x,
                    p.y,
                    p.z,
                    n.x,
                    n.y,
                    n.z,
                    u.x,
                    u.y,
                    u.z,
                    1.0,
                    (a + 1.0) * 0.5,
                    (b + 1.0) * 0.5,
                ]
            };
            let (p00, p10, p01, p11) = (
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(-1.0, 1.0),
                corner(1.0, 1.0),
            );
            out.extend([p00, p10, p11, p00, p11, p01]);
        }
    }
    out
}

/// The floor: the square `[−1, 1]²` in the plane `y = 0`, facing +y.
fn floor_mesh() -> Vec<Vertex> {
    let corner = |x: f32, z: f32| -> Vertex {
        [
            x,
            0.0,
            z,
            0.0,
            1.0,
            0.0,
            1.0,
            0.0,
            0.0,
            1.0,
            (x + 1.0) * 0.5,
            (z + 1.0) * 0.5,
        ]
    };
    let (a, b, c, d) = (
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(-1.0, 1.0),
        corner(1.0, 1.0),
    );
    vec![a, c, b, b, c, d]
}

/// Rotation about y by `degrees`, uniform `scale`, then translation to `at`.
fn placed(at: Vec3, scale: f32, degrees: f32) -> Mat4 {
    Mat4::from_translation(at)
        * Mat4::from_rotation_y(degrees.to_radians())
        * Mat4::from_scale(Vec3::splat(scale))
}

impl FrameScene {
    /// The frame the checks and pictures use ([`FRAME_WIDTH`] × [`FRAME_HEIGHT`]).
    pub fn new() -> FrameScene {
        FrameScene::sized(FRAME_WIDTH, FRAME_HEIGHT)
    }

    /// The frame at `width × height` pixels (the same view, the aspect ratio adjusted).
    pub fn sized(width: u32, height: u32) -> FrameScene {
        let eye = Vec3::new(0.5, 5.0, 5.6);
        let target = Vec3::new(0.4, 0.3, -0.2);
        let view_proj = perspective_rh(0.9, width as f32 / height as f32, 1.0, 24.0)
            * look_at_rh(eye, target, Vec3::Y);
        let to_main = Vec3::new(0.35, 0.8, 0.45).normalize();
        let main_color = Vec3::new(0.5, 0.47, 0.44);
        let scene = Scene {
            camera_position: eye,
            sh_r: Vec4::new(0.02, 0.06, 0.03, 0.18),
            sh_g: Vec4::new(0.02, 0.07, 0.02, 0.2),
            sh_b: Vec4::new(0.03, 0.09, 0.01, 0.26),
            light_dir: to_main,
            light_color: main_color,
            probes: [
                Probe {
                    forward_weight: 0.65,
                    ..probe(
                        Vec3::new(0.0, 1.5, 0.0),
                        Vec3::new(-8.5, -0.5, -8.5),
                        Vec3::new(8.5, 6.0, 8.5),
                        true,
                        Vec3::new(2.0, 1.0, 1.0),
                        1.0,
                        1,
                    )
                },
                probe(
                    Vec3::new(-2.0, 1.0, 0.0),
                    Vec3::splat(-10.0),
                    Vec3::splat(10.0),
                    false,
                    Vec3::new(1.5, 1.0, 1.0),
                    1.0,
                    1,
                ),
            ],
            lightmap_decode: LightmapDecode::default(),
            cubes: [
                cube([
                    [200, 170, 140, 160],
                    [120, 150, 190, 128],
                    [150, 190, 240, 200],
                    [90, 80, 60, 96],
                    [170, 160, 150, 140],
                    [110, 130, 100, 120],
                ]),
                cube([
                    [240, 200, 120, 180],
                    [80, 120, 200, 160],
                    [200, 220, 255, 220],
                    [60, 50, 40, 200],
                    [130, 180, 150, 170],
                    [230, 110, 150, 150],
                ]),
            ],
        };
        let main_light_source = Light::directional(-to_main, main_color);
        let main_light = main_light_source
            .params()
            .expect("the main light's parameters are valid");
        let light = |name, light_type, light: Light| {
            FrameLight::new(name, light_type, light).expect("the frame's lights are valid")
        };
        let lights = vec![
            light(
                "warm point (cube shadow)",
                LightType::Point,
                Light::point(Vec3::new(-0.4, 1.6, 1.8), 3.5, Vec3::new(3.0, 1.5, 0.6)),
            )
            .with_shadow(ShadowSpec {
                strength: 1.0,
                bias: 0.0,
                soft: false,
                split_spheres: false,
            })
            .excluding(&[LAYER_GLASS]),
            light(
                "cookie sun",
                LightType::DirectionalCookie,
                Light {
                    shape: LightShape::Directional {
                        direction: Vec3::new(-0.3, -1.0, -0.2),
                        cookie_size: 2.5,
                        cookie_origin: Vec3::new(0.3, 0.0, 0.1),
                    },
                    color: Vec3::new(0.22, 0.2, 0.26),
                },
            )
            .with_shadow(ShadowSpec {
                strength: 0.8,
                bias: 0.004,
                soft: true,
                split_spheres: true,
            })
            .excluding(&[LAYER_SHELTERED]),
            light(
                "cool point (cube cookie)",
                LightType::PointCookie,
                Light::point(Vec3::new(2.3, 1.4, 0.4), 3.0, Vec3::new(0.25, 0.6, 1.3)),
            )
            .excluding(&[LAYER_SHELTERED]),
            light(
                "spot (soft shadow)",
                LightType::Spot,
                Light::spot(
                    Vec3::new(3.6, 3.2, 0.8),
                    Vec3::new(-3.6, -3.2, -1.2),
                    60.0,
                    7.0,
                    Vec3::new(5.0, 5.0, 4.4),
                ),
            )
            .with_shadow(ShadowSpec {
                strength: 0.85,
                bias: 0.002,
                soft: true,
                split_spheres: false,
            }),
        ];
        let lift = 0.02;
        let objects = vec![
            FrameObject {
                name: "floor",
                // Static: a baked lightmap with its directional map (RGBM, decoding to about
                // 0.6 · rgb, a dominant direction up and to the side).
                keywords: Keywords {
                    lightmap: true,
                    dirlightmap: true,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(0.7, 0.7, 0.65, 1.0),
                    smoothness: 0.35,
                    ..Material::default()
                },
                texels: [WHITE, WHITE, FLAT, WHITE, WHITE, WHITE, WHITE, FLAT],
                lightmaps: [
                    [230, 200, 160, 40],
                    [166, 230, 140, 200],
                    NO_LIGHTMAPS[2],
                    NO_LIGHTMAPS[3],
                ],
                layer: 0,
                model: Mat4::from_scale(Vec3::new(8.0, 1.0, 8.0)),
                vertices: floor_mesh(),
            },
            FrameObject {
                name: "metal sphere",
                keywords: Keywords {
                    normal_map: true,
                    metallic_map: true,
                    smoothness: SmoothnessSource::Metallic,
                    ..Keywords::NONE
                },
                material: Material {
                    smoothness: 0.9,
                    bump_scale: 0.8,
                    ..Material::default()
                },
                texels: [
                    [200, 120, 90, 255],
                    [180, 0, 0, 200],
                    normal_texel(0.3, -0.2),
                    WHITE,
                    WHITE,
                    WHITE,
                    WHITE,
                    FLAT,
                ],
                lightmaps: NO_LIGHTMAPS,
                layer: 0,
                model: placed(Vec3::new(-1.7, 1.0 + lift, 0.2), 1.0, 0.0),
                vertices: sphere(12, 24),
            },
            FrameObject {
                name: "glowing sphere",
                keywords: Keywords {
                    emission_map: true,
                    occlusion_map: true,
                    detail_albedo: true,
                    detail_mask: true,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(0.9, 0.95, 1.0, 1.0),
                    emission: Vec3::new(0.3, 0.2, 0.05),
                    smoothness: 0.6,
                    occlusion_strength: 0.7,
                    ..Material::default()
                },
                texels: [
                    [90, 160, 220, 255],
                    WHITE,
                    FLAT,
                    [0, 150, 0, 255],
                    [255, 200, 120, 255],
                    [0, 0, 0, 170],
                    [200, 120, 90, 255],
                    FLAT,
                ],
                lightmaps: NO_LIGHTMAPS,
                layer: LAYER_SHELTERED,
                model: placed(Vec3::new(1.6, 0.75 + lift, 1.2), 0.75, 0.0),
                vertices: sphere(12, 24),
            },
            FrameObject {
                name: "detail box",
                // Lit by Enlighten's realtime lightmap.
                keywords: Keywords {
                    smoothness: SmoothnessSource::Albedo,
                    detail_normal: true,
                    dynamic_lightmap: true,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(0.8, 0.7, 0.9, 1.0),
                    metallic: 0.3,
                    smoothness: 0.8,
                    detail_bump_scale: 0.7,
                    ..Material::default()
                },
                texels: [
                    [230, 220, 200, 180],
                    WHITE,
                    FLAT,
                    WHITE,
                    WHITE,
                    WHITE,
                    WHITE,
                    normal_texel(-0.25, 0.3),
                ],
                lightmaps: [
                    NO_LIGHTMAPS[0],
                    NO_LIGHTMAPS[1],
                    [120, 150, 210, 110],
                    NO_LIGHTMAPS[3],
                ],
                layer: 0,
                model: placed(Vec3::new(0.3, 0.6 + lift, -1.6), 0.6, 35.0),
                vertices: cube_mesh(),
            },
            FrameObject {
                name: "cutout box",
                keywords: Keywords {
                    rendering: RenderingMode::Cutout,
                    normal_map: true,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(0.5, 0.8, 0.6, 1.0),
                    smoothness: 0.5,
                    ..Material::default()
                },
                texels: [
                    [240, 240, 240, 230],
                    WHITE,
                    normal_texel(0.0, 0.35),
                    WHITE,
                    WHITE,
                    WHITE,
                    WHITE,
                    FLAT,
                ],
                lightmaps: NO_LIGHTMAPS,
                layer: 0,
                model: placed(Vec3::new(2.6, 0.45 + lift, -0.9), 0.45, -20.0),
                vertices: cube_mesh(),
            },
        ];
        // In front of the opaque objects: each over two of them.
        let transparent = vec![
            FrameObject {
                name: "glass sphere (Fade)",
                keywords: Keywords {
                    rendering: RenderingMode::Fade,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(0.55, 0.8, 1.0, 0.45),
                    smoothness: 0.9,
                    ..Material::default()
                },
                texels: [WHITE, WHITE, FLAT, WHITE, WHITE, WHITE, WHITE, FLAT],
                lightmaps: NO_LIGHTMAPS,
                layer: LAYER_GLASS,
                model: placed(Vec3::new(-0.5, 1.3, 1.6), 0.55, 0.0),
                vertices: sphere(12, 24),
            },
            FrameObject {
                name: "tinted box (Transparent)",
                keywords: Keywords {
                    rendering: RenderingMode::Transparent,
                    ..Keywords::NONE
                },
                material: Material {
                    tint: Vec4::new(1.0, 0.6, 0.4, 0.35),
                    smoothness: 0.8,
                    metallic: 0.2,
                    ..Material::default()
                },
                texels: [WHITE, WHITE, FLAT, WHITE, WHITE, WHITE, WHITE, FLAT],
                lightmaps: NO_LIGHTMAPS,
                layer: 0,
                model: placed(Vec3::new(0.6, 1.0, 0.7), 0.45, 25.0),
                vertices: cube_mesh(),
            },
        ];
        // A 4 × 4 pattern of alphas, and one alpha per cube face.
        let alpha = [
            255u8, 60, 190, 120, 30, 230, 90, 160, 210, 140, 255, 0, 110, 180, 50, 245,
        ];
        let cookie = MapTexture::new(4, 4, |x, y| [255, 255, 255, alpha[(y * 4 + x) as usize]]);
        let face = |a: u8| Vec4::new(1.0, 1.0, 1.0, unorm_to_f32(u32::from(a), 8));
        let cube_cookie = CubeFaces([
            face(255),
            face(90),
            face(200),
            face(40),
            face(150),
            face(230),
        ]);
        FrameScene {
            width,
            height,
            view_proj,
            scene,
            main_light,
            main_light_source,
            main_culling_mask: !(1 << LAYER_SHELTERED),
            main_shadow: Some(ShadowSpec {
                strength: 1.0,
                bias: 0.004,
                soft: false,
                split_spheres: false,
            }),
            cascade_splits: FRAME_SPLITS.to_vec(),
            shadow_fade: ShadowFade::new(
                eye,
                target - eye,
                FadeDistance::ViewDepth,
                FRAME_FADE.0,
                FRAME_FADE.1,
            )
            .expect("the frame's fade is a valid ramp"),
            lights,
            objects,
            transparent,
            sky: Some(Sky {
                skybox: Skybox {
                    tint: Vec3::new(0.45, 0.5, 0.6),
                    exposure: 0.5,
                    rotation_degrees: 20.0,
                    decode: Vec4::new(2.0, 2.2, 0.0, 1.0),
                    ..Skybox::default()
                },
                faces: [
                    [200, 170, 150, 160],
                    [150, 170, 200, 150],
                    [170, 200, 255, 190],
                    [90, 80, 70, 120],
                    [180, 190, 210, 140],
                    [210, 180, 160, 170],
                ],
            }),
            cookie,
            cube_cookie,
            brdf: Brdf::Brdf1,
        }
    }

    /// The frame drawn in BRDF tier `brdf`: every object's variants and the lighting pass's.
    pub fn with_brdf(mut self, brdf: Brdf) -> FrameScene {
        self.brdf = brdf;
        for object in self.objects.iter_mut().chain(&mut self.transparent) {
            object.keywords.brdf = brdf;
        }
        self
    }

    /// The frame with `n` point lights instead of its four per-pixel lights (the main light
    /// stays, unshadowed) and without its sky and semi-transparent objects (a forward part
    /// both paths share), so that the paths differ by the lights' cost: the benchmark's light
    /// count.
    /// The lights are placed by a fixed pseudo-random sequence over the floor in view, 0.6 to
    /// 1.8 above it, with ranges of 1.2 to 2.2 (so each is drawn as its volume in the deferred
    /// path) and varied colours.
    pub fn with_point_lights(mut self, n: usize) -> FrameScene {
        let mut rng = Rng::new(0x1167_5EED);
        self.main_shadow = None;
        self.transparent.clear();
        self.sky = None;
        self.lights = (0..n)
            .map(|_| {
                let position = Vec3::new(
                    rng.range(-4.0, 4.5),
                    rng.range(0.6, 1.8),
                    rng.range(-3.0, 2.5),
                );
                let color = Vec3::new(
                    rng.range(0.2, 1.0),
                    rng.range(0.2, 1.0),
                    rng.range(0.2, 1.0),
                );
                let light = Light::point(position, rng.range(1.2, 2.2), color);
                FrameLight::new("point", LightType::Point, light).expect("valid point lights")
            })
            .collect();
        self
    }

    /// Whether the main light lights `object` (its culling mask has the object's layer).
    ///
    /// ```
    /// use wgsl_variants_gpu::check::frame::{FrameScene, LAYER_SHELTERED};
    /// let frame = FrameScene::new();
    /// let glowing = frame.objects.iter().find(|o| o.layer == LAYER_SHELTERED).unwrap();
    /// assert!(!frame.main_lights(glowing) && frame.main_lights(&frame.objects[0]));
    /// assert_eq!(frame.scene_for(glowing).light_color, glam::Vec3::ZERO);
    /// ```
    pub fn main_lights(&self, object: &FrameObject) -> bool {
        self.main_culling_mask & (1u32 << object.layer) != 0
    }

    /// The per-frame lighting `object` is drawn with: [`FrameScene::scene`], with a black main
    /// light where the main light's culling mask leaves the object out.
    pub fn scene_for(&self, object: &FrameObject) -> Scene {
        if self.main_lights(object) {
            self.scene
        } else {
            self.scene.with_main_shadow(0.0)
        }
    }

    /// The standard shader's resources for drawing `object`.
    pub fn object_resources(&self, object: &FrameObject) -> Vec<BoundResource> {
        StandardBindings {
            view_proj: self.view_proj,
            scene: &self.scene_for(object),
            material: &object.material,
            detail_st: Vec4::new(1.0, 1.0, 0.0, 0.0),
            maps: &object.maps(),
            model: object.model,
            normal_matrix: object.normal_matrix(),
        }
        .resources()
    }

    /// The cookies as the reference samples them.
    pub fn cookies(&self) -> (Cookie2d, &CubeFaces) {
        let texture = Cookie2d {
            width: self.cookie.width,
            height: self.cookie.height,
            alpha: (0..self.cookie.height)
                .flat_map(|y| (0..self.cookie.width).map(move |x| (x, y)))
                .map(|(x, y)| self.cookie.get(x, y).w)
                .collect(),
        };
        (texture, &self.cube_cookie)
    }

    /// The bindings of one per-pixel light (`lighting/light_bindings`): its uniform, the
    /// frame's cookies and their sampler (nearest, repeating). (BRDF3's lookup table comes
    /// with the objects' bindings in the forward path, with the lighting pass's in the
    /// deferred one.)
    pub fn light_resources(&self, params: &LightParams) -> Vec<BoundResource> {
        let uniform = params
            .uniform()
            .into_iter()
            .flat_map(f32::to_le_bytes)
            .collect();
        vec![
            BoundResource::new(0, 6, Resource::Uniform(uniform)),
            BoundResource::new(0, 7, self.cookie.resource()),
            BoundResource::new(0, 8, cube_resource(&self.cube_cookie)),
            BoundResource::new(
                0,
                9,
                Resource::SamplerAddressed {
                    nearest: true,
                    address_mode: wgpu::AddressMode::Repeat,
                },
            ),
        ]
    }

    /// The camera the directional shadows' cascades are fitted to.
    pub fn cascade_camera(&self) -> CascadeCamera {
        CascadeCamera::from_view_proj(self.scene.camera_position, self.view_proj)
    }

    /// The `DeferredCamera` uniform of the full-screen passes: inverse view-projection,
    /// camera position, view-projection.
    pub fn deferred_camera(&self) -> Vec<u8> {
        deferred_camera(self.view_proj, self.scene.camera_position)
    }

    /// Every pixel `(x, y)`, row by row.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        (0..self.height).flat_map(move |y| (0..self.width).map(move |x| (x, y)))
    }

    /// What opaque object the ray through the point `(px, py)` of the target (in pixels,
    /// `(x + 0.5, y + 0.5)` is pixel `(x, y)`'s centre) hits first, in `f64`: the object and
    /// its vertex data interpolated at the hit (barycentric in world space, which is what
    /// perspective-correct interpolation computes).
    pub fn cast(&self, px: f64, py: f64) -> Option<Hit> {
        cast_into(&self.objects, self.view_proj, self.size(), px, py).map(|(_, hit)| hit)
    }

    /// The semi-transparent objects in drawing order: back to front by the distance from the
    /// camera to each one's centre (Unity's default sort of the transparent queue for a
    /// perspective camera), as indices into [`FrameScene::transparent`].
    pub fn transparent_order(&self) -> Vec<usize> {
        let camera = self.scene.camera_position;
        let distance = |o: &FrameObject| o.model.w_axis.truncate().distance(camera);
        let mut order: Vec<usize> = (0..self.transparent.len()).collect();
        order.sort_by(|&a, &b| {
            distance(&self.transparent[b]).total_cmp(&distance(&self.transparent[a]))
        });
        order
    }

    /// What the ray through `(px, py)` sees: the first opaque hit ([`FrameScene::cast`]) and
    /// the semi-transparent surfaces in front of it in drawing order
    /// ([`FrameScene::transparent_order`]; their `object` indexes
    /// [`FrameScene::transparent`]). A transparent object contributes the surface nearest the
    /// camera (its back faces are culled; the frame's are convex).
    pub fn cast_through(&self, px: f64, py: f64) -> (Option<Hit>, Vec<Hit>) {
        let size = self.size();
        let opaque = cast_into(&self.objects, self.view_proj, size, px, py);
        let limit = opaque.as_ref().map_or(f64::INFINITY, |(t, _)| *t);
        let layers = self
            .transparent_order()
            .into_iter()
            .filter_map(|o| {
                let object = std::slice::from_ref(&self.transparent[o]);
                let (t, hit) = cast_into(object, self.view_proj, size, px, py)?;
                (t < limit).then_some(Hit { object: o, ..hit })
            })
            .collect();
        (opaque.map(|(_, hit)| hit), layers)
    }

    fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

/// The first hit of the ray through the target point `(px, py)` among `objects` (see
/// [`FrameScene::cast`]), with its ray parameter.
fn cast_into(
    objects: &[FrameObject],
    view_proj: Mat4,
    size: (u32, u32),
    px: f64,
    py: f64,
) -> Option<(f64, Hit)> {
    let (origin, dir) = pixel_ray(view_proj, size, px, py);
    let mut best: Option<(f64, usize, [f64; 3], usize)> = None;
    for (o, object) in objects.iter().enumerate() {
        let model = object.model.as_dmat4();
        for (t_index, tri) in object.vertices.chunks_exact(3).enumerate() {
            let p = |v: &Vertex| {
                model.transform_point3(DVec3::new(v[0].into(), v[1].into(), v[2].into()))
            };
            let (a, b, c) = (p(&tri[0]), p(&tri[1]), p(&tri[2]));
            if let Some((t, w)) = intersect(origin, dir, a, b, c)
                && best.is_none_or(|(bt, ..)| t < bt)
            {
                best = Some((t, o, w, t_index));
            }
        }
    }
    let (t, o, w, t_index) = best?;
    let object = &objects[o];
    let tri = &object.vertices[t_index * 3..t_index * 3 + 3];
    let model = object.model.as_dmat4();
    let normal_matrix = object.normal_matrix().as_dmat4();
    let world =
        |v: &Vertex| model.transform_point3(DVec3::new(v[0].into(), v[1].into(), v[2].into()));
    let position = world(&tri[0]) * w[0] + world(&tri[1]) * w[1] + world(&tri[2]) * w[2];
    // The vertex shader transforms per vertex; the rasterizer interpolates the results.
    let per_vertex = |m: DMat4, range: std::ops::Range<usize>| {
        let at = |v: &Vertex| {
            m.transform_vector3(DVec3::new(
                v[range.start].into(),
                v[range.start + 1].into(),
                v[range.start + 2].into(),
            ))
        };
        at(&tri[0]) * w[0] + at(&tri[1]) * w[1] + at(&tri[2]) * w[2]
    };
    let normal = per_vertex(normal_matrix, 3..6);
    let tangent = per_vertex(model, 6..9);
    // The bitangent sign is the same at the three vertices of every triangle here.
    let sign = tri[0][9];
    Some((
        t,
        Hit {
            object: o,
            geometry: Geometry {
                world_position: position.as_vec3(),
                normal: normal.as_vec3(),
                tangent: tangent.as_vec3().extend(sign),
            },
        },
    ))
}

impl Default for FrameScene {
    fn default() -> FrameScene {
        FrameScene::new()
    }
}

/// Möller–Trumbore: the ray `origin + t · dir` against triangle `abc` (either side); `t` and
/// the barycentric weights of `a`, `b`, `c` where it hits with `t > 0`.
fn intersect(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<(f64, [f64; 3])> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = origin - a;
    let u = s.dot(p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) / det;
    (t > 0.0).then_some((t, [1.0 - u - v, u, v]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mesh_faces_outward() {
        // Counter-clockwise seen from outside: each triangle's winding normal points along
        // its vertex normals (degenerate triangles at the sphere's poles have none).
        for (name, mesh) in [("sphere", sphere(12, 24)), ("cube", cube_mesh())] {
            for tri in mesh.chunks_exact(3) {
                let p = |v: &Vertex| Vec3::new(v[0], v[1], v[2]);
                let winding = (p(&tri[1]) - p(&tri[0])).cross(p(&tri[2]) - p(&tri[0]));
                let normal: Vec3 = tri.iter().map(|v| Vec3::new(v[3], v[4], v[5])).sum();
                assert!(
                    winding.length() < 1e-6 || winding.dot(normal) > 0.0,
                    "{name}: {winding} against {normal}"
                );
            }
        }
    }

    #[test]
    fn transparent_objects_are_seen_over_two_opaque_objects_each() {
        let f = FrameScene::new();
        let mut over = vec![std::collections::BTreeMap::new(); f.transparent.len()];
        for (x, y) in f.pixels() {
            let (hit, layers) = f.cast_through(f64::from(x) + 0.5, f64::from(y) + 0.5);
            for l in layers {
                let under = hit.map_or("background", |h| f.objects[h.object].name);
                *over[l.object].entry(under).or_insert(0) += 1;
            }
        }
        for (o, under) in over.iter().enumerate() {
            let name = f.transparent[o].name;
            assert!(under.values().sum::<usize>() > 40, "{name}: {under:?}");
            assert!(
                under.values().filter(|&&n| n > 5).count() >= 2,
                "{name}: {under:?}"
            );
        }
    }

    #[test]
    fn rays_hit_what_the_camera_sees() {
        let f = FrameScene::new();
        // The image centre looks at the floor or an object near the look-at point.
        let hit = f.cast(32.0, 24.0).expect("the centre sees something");
        let clip = f.view_proj * hit.geometry.world_position.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        assert!(ndc.x.abs() < 1e-4 && ndc.y.abs() < 1e-4, "{ndc}");
        // The bottom row sees the floor, facing up.
        let floor = f.cast(32.5, 47.5).expect("the floor");
        assert_eq!(f.objects[floor.object].name, "floor");
        assert!((floor.geometry.normal - Vec3::Y).length() < 1e-6);
        assert!(floor.geometry.world_position.y.abs() < 1e-5);
    }

    #[test]
    fn sphere_normals_point_away_from_the_centre() {
        let f = FrameScene::new();
        let mut seen = 0;
        for (x, y) in f.pixels() {
            if let Some(hit) = f.cast(f64::from(x) + 0.5, f64::from(y) + 0.5)
                && f.objects[hit.object].name == "metal sphere"
            {
                seen += 1;
                let centre = f.objects[hit.object].model.w_axis.truncate();
                let radial = (hit.geometry.world_position - centre).normalize();
                // Interpolated normals of a 12 × 24 sphere stay within a few degrees.
                assert!(radial.dot(hit.geometry.normal.normalize()) > 0.99);
            }
        }
        assert!(seen > 50, "{seen} pixels of the metal sphere");
    }

    /// The frame is deep enough for its directional shadows' four cascades: picked by view
    /// depth and by split spheres, every cascade holds over 5 % of the visible pixels, so both
    /// paths' masks cross every seam.
    #[test]
    fn every_cascade_holds_part_of_the_frame() {
        use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades, MAX_CASCADES};
        let f = FrameScene::new();
        let sun = Light::directional(-f.scene.light_dir, f.scene.light_color);
        let cascades = Cascades::fit(&sun, 1.0, 0.004, &f.cascade_camera(), &f.cascade_splits)
            .expect("the frame's splits fit");
        for split_spheres in [false, true] {
            let keywords = CascadeKeywords {
                split_spheres,
                ..CascadeKeywords::default()
            };
            let mut counts = [0usize; MAX_CASCADES + 2];
            for (x, y) in f.pixels() {
                if let Some(hit) = f.cast(f64::from(x) + 0.5, f64::from(y) + 0.5) {
                    let p = hit.geometry.world_position;
                    if let [Some(w)] = cascades.candidates(keywords, p).as_slice() {
                        counts[Cascades::picked(*w)] += 1;
                    }
                }
            }
            eprintln!(
                "split spheres {split_spheres}: pixels per cascade 0-3 / none / several {counts:?}"
            );
            let hits: usize = counts.iter().sum();
            for (i, &n) in counts[..MAX_CASCADES].iter().enumerate() {
                assert!(
                    n * 20 > hits,
                    "cascade {i} holds {n} of {hits} pixels: {counts:?}"
                );
            }
            assert_eq!(counts[MAX_CASCADES + 1], 0, "{counts:?}");
        }
    }
}
