//! The measured accuracy of the G-buffer normal encodings (README, "Normal encodings"):
//! over 200 000 directions of a Fibonacci sphere, URP's octahedral 12:12 encoding has the
//! lowest mean error, the built-in path's 10-10-10 unorm the lowest largest error (URP's codes
//! are truncated, not rounded), URP's default `Rgba8Snorm` is the worst by both measures, and
//! each stays within the bound its grid allows.

use wgsl_variants_shaders::reference::urp::accuracy::{NormalEncoding, fibonacci_sphere, measure};

#[test]
fn octahedral_normals_are_the_most_accurate() {
    let dirs = fibonacci_sphere(200_000);
    let [oct, unorm10, snorm8, nearest] = NormalEncoding::ALL.map(|e| measure(e, &dirs));
    println!("oct {oct:?}\nunorm10 {unorm10:?}\nsnorm8 {snorm8:?}\nnearest {nearest:?}");
    assert_eq!(oct.count, 200_000);
    assert!(oct.mean_deg < unorm10.mean_deg && unorm10.mean_deg < snorm8.mean_deg);
    assert!(unorm10.max_deg < oct.max_deg && oct.max_deg < snorm8.max_deg);
    // Rounding the same 12-bit codes to nearest would win on both measures.
    assert!(nearest.max_deg < unorm10.max_deg && nearest.mean_deg < oct.mean_deg);
    // Bounds from the grids: a step of 2/4095 in octahedral space moves a direction by at most
    // about 2·2/4095 rad (the map stretches by up to 2) ≈ 0.056°, and truncation costs a full
    // step, not half (up to 0.11°). A 10-bit unorm step is 2/1023, half of it
    // per axis in 3 axes: √3/1023 rad ≈ 0.097°. An 8-bit snorm step is 1/127, half per axis:
    // √3/254 rad ≈ 0.39°.
    assert!(oct.max_deg < 0.12, "{oct:?}");
    assert!(unorm10.max_deg < 0.1, "{unorm10:?}");
    assert!(snorm8.max_deg < 0.4, "{snorm8:?}");
    assert!(
        oct.mean_deg > 0.0 && snorm8.mean_deg > 0.1,
        "the errors are real"
    );
}
