#import demo::a
@fragment fn fs() -> @location(0) vec4f { return vec4f(a::fa()); }
