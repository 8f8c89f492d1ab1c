#if defined(A) &&
#endif
