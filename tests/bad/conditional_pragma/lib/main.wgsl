#shader s
#pass P
#if X
#pragma multi_compile _ A
#endif
#endpass
