fn emission() -> vec3f {
#ifdef _EMISSION_MAP
    return vec3f(1.0, 2.0);
#else
    return vec3f(0.0);
#endif
}
