#shader s
#pass P
#pragma target 3.0
#endpass
