//! Nearest-texel addressing with repeat: which texel a nearest sampler with repeat addressing
//! reads at a texture coordinate, and which texels it may read where the coordinate lies so
//! close to a texel's edge that the math does not decide (a GPU's texel addressing is fixed
//! point). The cookies read this way: the built-in lights' ([`super::light::Cookie2d`]) and
//! URP's ([`super::urp::cookie`]).
//!
//! Along one axis of `size` texels, coordinate `t` reads texel `floor(t · size)` wrapped into
//! `0..size` (`t = 1` is texel 0 again).

/// The texel, in `0..size`, a nearest sampler with repeat addressing reads at `t`. A non-finite
/// `t` reads texel 0; `size` must not be 0.
///
/// ```
/// use wgsl_variants_shaders::reference::texel::nearest_repeat;
/// assert_eq!(nearest_repeat(0.2, 2), 0);
/// assert_eq!(nearest_repeat(0.7, 2), 1);
/// assert_eq!(nearest_repeat(-0.2, 2), 1); // repeat
/// assert_eq!(nearest_repeat(3.5, 4), 2);
/// assert_eq!(nearest_repeat(f32::NAN, 4), 0);
/// ```
pub fn nearest_repeat(t: f32, size: u32) -> u32 {
    if !t.is_finite() {
        return 0;
    }
    ((t * size as f32).floor() as i64).rem_euclid(i64::from(size)) as u32
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

/// The texels a nearest sampler with repeat addressing may read at `t`: [`nearest_repeat`]'s,
/// and its neighbour across the edge when `t` lies within `band` texels of that edge (in
/// `0..size`, wrapped).
///
/// ```
/// use wgsl_variants_shaders::reference::texel::nearest_repeat_within;
/// assert_eq!(nearest_repeat_within(0.3, 2, 1.0 / 64.0), vec![0]);
/// assert_eq!(nearest_repeat_within(0.499, 2, 1.0 / 64.0), vec![0, 1]);
/// assert_eq!(nearest_repeat_within(1.0, 2, 1.0 / 64.0), vec![0, 1]); // the wrap's edge
/// ```
pub fn nearest_repeat_within(t: f32, size: u32, band: f32) -> Vec<u32> {
    let first = nearest_repeat(t, size);
    let mut out = vec![first];
    if !t.is_finite() {
        return out;
    }
    let x = t * size as f32;
    let f = x - x.floor();
    let wrap = |i: i64| i.rem_euclid(i64::from(size)) as u32;
    if f < band {
        out.push(wrap(i64::from(first) - 1));
    }
    if f > 1.0 - band {
        out.push(wrap(i64::from(first) + 1));
    }
    out.dedup();
    out
}
