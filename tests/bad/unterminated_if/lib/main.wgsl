#shader s
#pass P
#pragma multi_compile _ A
#import m
#endpass
