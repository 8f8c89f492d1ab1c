fn f() {}
#if A
fn g() {}
