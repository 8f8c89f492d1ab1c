#shader s
#pass P
#pragma multi_compile _ A
#pragma multi_compile _ B
#pragma multi_compile _ C
#pragma multi_compile _ D
#pragma multi_compile _ E
#endpass
