#define_import_path demo::b
#import demo::a
fn fb() -> f32 { return a::fa(); }
