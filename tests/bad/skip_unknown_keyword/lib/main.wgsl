#shader s
#pass P
#pragma multi_compile _ A
#pragma skip_variants B
#endpass
