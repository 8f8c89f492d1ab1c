fn b() {}
#import a
