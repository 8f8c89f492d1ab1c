// The pass has no `RAIN` keyword: the key has no field for it.
use bindings_compile_fail::keys::{Key, Keywords};

const RAIN: Key = Key::checked(Keywords {
    rain: true,
    ..Keywords::DEFAULT
});

fn main() {
    let _ = RAIN;
}
