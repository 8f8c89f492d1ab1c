#shader s
#pass P
#pragma shader_feature _ _NORMAL_MAP
#pragma exclude _NORMAL_MAP
#endpass
