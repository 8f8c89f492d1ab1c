#shader s
#pass P
#pragma shader_feature _NORMAL_MAP
#endpass
