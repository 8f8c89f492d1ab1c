#import b
fn a() {}
