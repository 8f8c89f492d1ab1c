//! Nearest-texel addressing: which texel a nearest sampler reads at a texture coordinate, with
//! repeat or clamp-to-edge addressing, and which texels it may read where the coordinate lies
//! so close to a texel's edge that the math does not decide (a GPU's texel addressing is fixed
//! point). The cookies read this way: the built-in lights' ([`super::light::Cookie2d`], repeat)
//! and URP's ([`super::urp::cookie`]: the main light's repeats, the additional lights' atlas
//! clamps).
//!
//! Along one axis of `size` texels, coordinate `t` reads texel `floor(t · size)`, wrapped into
//! `0..size` under [`Address::Repeat`] (`t = 1` is texel 0 again) and clamped to it under
//! [`Address::ClampToEdge`].

/// How a coordinate outside [0, 1) finds a texel (wgpu's address modes of those names).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Address {
    /// The texture tiles: the index wraps.
    Repeat,
    /// The edge texels extend outwards: the index clamps.
    ClampToEdge,
}

impl Address {
    fn apply(self, i: i64, size: u32) -> u32 {
        match self {
            Address::Repeat => i.rem_euclid(i64::from(size)) as u32,
            Address::ClampToEdge => i.clamp(0, i64::from(size) - 1) as u32,
        }
    }
}

/// The texel, in `0..size`, a nearest sampler reads at `t` under `address`. A non-finite `t`
/// reads texel 0; `size` must not be 0.
///
/// ```
/// use wgsl_variants_shaders::reference::texel::{Address, nearest};
/// assert_eq!(nearest(0.2, 2, Address::Repeat), 0);
/// assert_eq!(nearest(0.7, 2, Address::Repeat), 1);
/// assert_eq!(nearest(-0.2, 2, Address::Repeat), 1); // wraps
/// assert_eq!(nearest(3.5, 4, Address::Repeat), 2);
/// assert_eq!(nearest(1.0, 4, Address::ClampToEdge), 3); // clamps
/// assert_eq!(nearest(-0.2, 4, Address::ClampToEdge), 0);
/// assert_eq!(nearest(f32::NAN, 4, Address::Repeat), 0);
/// ```
pub fn nearest(t: f32, size: u32, address: Address) -> u32 {
    if !t.is_finite() {
        return 0;
    }
    address.apply((t * size as f32).floor() as i64, size)
}

/// Distance, in texels, from `t` to the nearest texel edge along an axis of `size` texels (how
/// far a lookup is from reading another texel).
///
/// ```
/// use wgsl_variants_shaders::reference::texel::edge_distance;
/// assert!((edge_distance(0.1, 4) - 0.4).abs() < 1e-6);
/// assert!((edge_distance(0.24, 4) - 0.04).abs() < 1e-6);
/// ```
pub fn edge_distance(t: f32, size: u32) -> f32 {
    let x = t * size as f32;
    let f = x - x.floor();
    f.min(1.0 - f)
}

/// The texels a nearest sampler may read at `t` under `address`: [`nearest`]'s, and its
/// neighbour across the edge when `t` lies within `band` texels of that edge (in `0..size`,
/// each once).
///
/// ```
/// use wgsl_variants_shaders::reference::texel::{Address, nearest_within};
/// let band = 1.0 / 64.0;
/// assert_eq!(nearest_within(0.3, 2, band, Address::Repeat), vec![0]);
/// assert_eq!(nearest_within(0.499, 2, band, Address::Repeat), vec![0, 1]);
/// assert_eq!(nearest_within(1.0, 2, band, Address::Repeat), vec![0, 1]); // the wrap's edge
/// assert_eq!(nearest_within(1.0, 2, band, Address::ClampToEdge), vec![1]); // the last texel
/// ```
pub fn nearest_within(t: f32, size: u32, band: f32, address: Address) -> Vec<u32> {
    let mut out = vec![nearest(t, size, address)];
    if !t.is_finite() {
        return out;
    }
    let x = t * size as f32;
    let base = x.floor();
    let f = x - base;
    if f < band {
        out.push(address.apply(base as i64 - 1, size));
    }
    if f > 1.0 - band {
        out.push(address.apply(base as i64 + 1, size));
    }
    out.sort_unstable();
    out.dedup();
    out
}
