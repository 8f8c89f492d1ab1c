@fragment fn fs() -> @location(0) vec4f {
#ifdef A
    return vec4f(1.0);
#else whenever B
    return vec4f(0.0);
#endif
}
