#shader s
#pass P
#pragma multi_compile _ A B
#endpass
