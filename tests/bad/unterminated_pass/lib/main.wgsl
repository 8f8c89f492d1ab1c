#shader s
#pass P
fn f() {}
