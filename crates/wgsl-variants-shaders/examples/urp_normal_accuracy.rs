//! Prints the README's table of G-buffer normal encodings: max and mean angular round-trip
//! error over a Fibonacci sphere, each encoding through its CPU quantizer
//! (`wgsl_variants_shaders::reference::urp::accuracy`).
//!
//! ```text
//! cargo run --release --example urp_normal_accuracy [directions]   # default 1000000
//! ```

fn main() {
    let count = match std::env::args().nth(1) {
        None => 1_000_000,
        Some(arg) => match arg.parse::<usize>() {
            Ok(n) if n > 0 => n,
            _ => {
                eprintln!(
                    "error: the number of directions must be a positive integer, not `{arg}`"
                );
                std::process::exit(2);
            }
        },
    };
    print!(
        "{}",
        wgsl_variants_shaders::reference::urp::accuracy::table(count)
    );
}
