#shader s
#pass P
#pragma multi_compile _ HALF
#import m
#endpass
