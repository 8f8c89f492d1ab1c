fn f() -> f32 {
#if HALF
    let x: i32 = 1;
    return x;
#else
    return 1.0;
#endif
}
