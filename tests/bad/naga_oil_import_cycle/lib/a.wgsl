#define_import_path demo::a
#import demo::b
fn fa() -> f32 { return b::fb(); }
