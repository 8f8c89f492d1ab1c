#shader s
#pass P
#pragma shader_feature _ _NORMAL_MAP
#pragma shader_feature _ _DETAIL_NORMAL_MAP
#pragma require _DETAIL_NORMAL_MAP _NORMAL_MAP
#pragma exclude _DETAIL_NORMAL_MAP _NORMAL_MAP
#endpass
