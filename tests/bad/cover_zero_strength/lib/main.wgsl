#shader s
#pass P
#pragma multi_compile _ A
#pragma multi_compile _ B
#endpass
