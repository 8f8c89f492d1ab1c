// deferred/ldr: the logarithmic LDR encoding of RT3 (docs/shading.md §3).
//
// With UNITY_HDR_ON off, RT3 (Rgb10a2Unorm) holds exp2(-c) instead of the light colour c, so
// that lights multiplied into it (DstColor / Zero blending) add up in the exponent:
// 2^-a · 2^-b = 2^-(a+b). The final deferred pass decodes c = -log2(stored).
//
// Provides (pure functions, no bindings; callable from any stage):
//   fn ldr_encode(c: vec3f) -> vec3f                       exp2(-max(c, 0)); NaN counts as 0
//   fn ldr_decode(s: vec3f) -> vec3f                       max(-log2(s), 0); s == 0 gives +inf
//   fn ldr_accumulate(stored: vec3f, light: vec3f) -> vec3f stored · ldr_encode(light)

// true per channel where x is a NaN (a bit test: comparisons may be folded by NaN-ignoring compilers).
fn ldr_is_nan(x: vec3f) -> vec3<bool> {
    return (bitcast<vec3u>(x) & vec3u(0x7fffffffu)) > vec3u(0x7f800000u);
}

// exp2(-max(c, 0)) per channel: c < 0 (and -inf) -> 1, NaN -> 1 (treated as 0), +inf -> 0.
fn ldr_encode(c: vec3f) -> vec3f {
    let x = select(max(c, vec3f(0.0)), vec3f(0.0), ldr_is_nan(c));
    // 2^-200 rounds to 0 in f32, so limiting the exponent changes no result and keeps +inf
    // away from exp2 (whose behaviour at infinity Vulkan leaves open).
    return exp2(-min(x, vec3f(200.0)));
}

// -log2(s) per channel, clamped to >= 0:
//   0 < s < 1 -> -log2(s);  s == 0 (either sign) -> +inf;  s >= 1 (and +inf) -> 0;
//   s < 0 and NaN -> 0 (the clamp drops the NaN of log2 of a negative, as max(NaN, 0) = 0).
fn ldr_decode(s: vec3f) -> vec3f {
    let in_range = (s > vec3f(0.0)) & (s < vec3f(1.0));
    // log2 is only evaluated on (0, 1): Vulkan leaves log2(x <= 0) undefined.
    let decoded = max(-log2(select(vec3f(1.0), s, in_range)), vec3f(0.0));
    // +inf where s == 0, built at run time (a constant +inf is a WGSL shader-creation error).
    let at_zero = bitcast<vec3f>(select(vec3u(0u), vec3u(0x7f800000u), s == vec3f(0.0)));
    return select(at_zero, decoded, in_range);
}

// What a DstColor · src + Zero · dst blend of ldr_encode(light) does to an LDR-encoded value:
// stored · exp2(-max(light, 0)), i.e. the decoded colours add.
fn ldr_accumulate(stored: vec3f, light: vec3f) -> vec3f {
    return stored * ldr_encode(light);
}
