#shader s
#pass P
#import lighting/brdff
#endpass
