// The bake's one material uses NORMAL_MAP without DETAIL (baked/materials.toml): a key naming
// a combination the bake left out does not compile.
use bindings_compile_fail::baked::{Key, Keywords};

const WITH_DETAIL: Key = Key::checked(Keywords {
    normal_map: true,
    detail: true,
    ..Keywords::DEFAULT
});

fn main() {
    let _ = WITH_DETAIL;
}
