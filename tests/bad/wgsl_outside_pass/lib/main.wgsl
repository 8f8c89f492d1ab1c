#shader s
fn f() {}
#pass P
#endpass
