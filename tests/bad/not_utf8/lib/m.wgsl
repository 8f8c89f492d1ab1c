fn f() {}
// café
