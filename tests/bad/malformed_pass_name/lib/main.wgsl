#shader s
#pass Forward Base
#pragma multi_compile _ A
@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }
#endpass
