fn f() {}
  #endif
