#shader s
#pass P
#pragma shader_feature _NORMAL_MAP
#pragma multi_compile _ _NORMAL_MAP FOO
#endpass
