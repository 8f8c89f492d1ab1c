#shader s
#pass P
#pragma multi_compile LOW HIGH
#pragma multi_compile _ SHADOWS
#pragma require LOW SHADOWS
#pragma require HIGH SHADOWS
#pragma skip_variants SHADOWS
#endpass
