#shader s
#pass P
#pragma multi_compile _ LOW HIGH
#pragma require HIGH LOW
#endpass
