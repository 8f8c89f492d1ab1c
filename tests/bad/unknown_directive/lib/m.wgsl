fn f() {}
#iff A
