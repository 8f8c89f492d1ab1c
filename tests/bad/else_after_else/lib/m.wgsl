#ifdef A
#else
fn f() {}
#else
#endif
