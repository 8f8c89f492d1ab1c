// `SOFT` requires `SHADOWS`, and `SOFT` excludes `FOG`: neither constant compiles.
use bindings_compile_fail::keys::{Key, Keywords};

const SOFT_WITHOUT_SHADOWS: Key = Key::checked(Keywords {
    soft: true,
    ..Keywords::DEFAULT
});

const SOFT_WITH_FOG: Key = Key::checked(Keywords {
    shadows: true,
    soft: true,
    fog: true,
});

fn main() {
    let _ = (SOFT_WITHOUT_SHADOWS, SOFT_WITH_FOG);
}
