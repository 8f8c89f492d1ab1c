#shader s
#pass P
#pragma shader_feature _EMISSION_MAP
#import surface
#endpass
