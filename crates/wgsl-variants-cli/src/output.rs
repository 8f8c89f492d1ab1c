//! Shared output helpers: exact big counts in JSON, and printing.

use num_bigint::BigUint;
use serde_json::value::RawValue;

/// An exact count as a JSON number of any size (JSON numbers are unbounded; a parser that
/// cannot hold it still sees a number, never a rounded value in our output).
pub fn count(n: &BigUint) -> Box<RawValue> {
    RawValue::from_string(n.to_string()).expect("a decimal integer is valid JSON")
}

/// Prints a JSON value on stdout, pretty, with a trailing newline.
pub fn print_json<T: serde::Serialize>(value: &T) -> Result<(), super::Failed> {
    let text = serde_json::to_string_pretty(value)?;
    println!("{text}");
    Ok(())
}

/// A progress bar on stderr; hidden when stderr is not a terminal.
pub fn progress(len: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(len),
        indicatif::ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({per_sec})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}
