fn a() {}
#import a
