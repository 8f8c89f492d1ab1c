//! A hand-written SVG chart of an audit, for reports: per pass, the stage counts (log scale)
//! and, per keyword set, how much it multiplies the space and the distinct variants.
//!
//! The output depends only on the audit: same audit, same bytes.

use std::fmt::Write;

use num_bigint::BigUint;
use num_traits::ToPrimitive;

use super::PassAudit;

const WIDTH: u32 = 960;
const LABEL: u32 = 300;
/// Length of the longest stage bar.
const BAR: u32 = 470;
/// Length of the bar of the largest keyword set.
const SET_BAR: u32 = 200;
const ROW: u32 = 18;

/// log2(n) (0 for 0), good to many digits for any size.
fn log2(n: &BigUint) -> f64 {
    let bits = n.bits();
    if bits == 0 {
        0.0
    } else if bits <= 60 {
        n.to_f64().unwrap_or(0.0).log2()
    } else {
        let shift = bits - 60;
        (n >> shift).to_f64().unwrap_or(1.0).log2() + shift as f64
    }
}

/// A count for a label: exact up to 12 digits, else `≈2^k`.
fn short(n: &BigUint) -> String {
    let s = n.to_string();
    if s.len() <= 12 {
        s
    } else {
        format!("≈2^{:.1}", log2(n))
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(n - 1).collect();
        t.push('…');
        t
    }
}

/// The chart of several passes' audits, as an SVG document.
///
/// ```
/// use wgsl_variants::{Library, audit};
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let passes: Vec<_> = lib.passes().collect();
/// let audits = audit::audit_passes(&lib, &passes, &audit::AuditOptions::default()).unwrap();
/// let svg = audit::chart::svg(&audits);
/// assert!(svg.starts_with("<svg") && svg.contains("standard/Deferred"));
/// ```
pub fn svg(audits: &[PassAudit]) -> String {
    let max_log = audits
        .iter()
        .map(|a| log2(&a.full_space))
        .fold(1.0f64, f64::max);
    let max_factor = audits
        .iter()
        .flat_map(|a| a.sets.iter().map(|s| s.factor))
        .max()
        .unwrap_or(1)
        .max(2) as f64;
    let mut body = String::new();
    let mut y = 50u32;
    for a in audits {
        y = pass_section(&mut body, a, y, max_log, max_factor);
    }
    let height = y + 10;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" font-family="sans-serif" font-size="12">"##
    );
    let _ = writeln!(
        out,
        r##"<rect width="{WIDTH}" height="{height}" fill="#ffffff"/>"##
    );
    let _ = writeln!(
        out,
        r##"<text x="16" y="24" font-size="16" font-weight="bold">Variant audit</text>"##
    );
    let _ = writeln!(
        out,
        r##"<text x="16" y="42" fill="#555555">stages on a log scale; per keyword set: grey = options (multiplies the space), blue = multiplies distinct variants, orange = coupled with other sets</text>"##
    );
    out.push_str(&body);
    out.push_str("</svg>\n");
    out
}

fn pass_section(out: &mut String, a: &PassAudit, mut y: u32, max_log: f64, max_factor: f64) -> u32 {
    y += 14;
    let _ = writeln!(
        out,
        r##"<text x="16" y="{y}" font-size="14" font-weight="bold">{}</text>"##,
        escape(&format!("{}/{}", a.shader, a.pass))
    );
    y += 8;
    let distinct_label = if a.distinct.exact {
        "distinct".to_string()
    } else {
        "distinct (bound)".to_string()
    };
    let stages = [
        ("full space", &a.full_space, "#9e9e9e"),
        ("after filtering", &a.after_filtering, "#7986cb"),
        ("build set", &a.build_set, "#3f51b5"),
        (distinct_label.as_str(), &a.distinct.count, "#2e7d32"),
    ];
    for (name, n, color) in stages {
        let w = ((log2(n) / max_log) * BAR as f64).round().max(1.0) as u32;
        let _ = writeln!(
            out,
            r##"<text x="32" y="{}">{}</text><rect x="{LABEL}" y="{}" width="{w}" height="{}" fill="{color}"/><text x="{}" y="{}">{}</text>"##,
            y + 13,
            escape(name),
            y + 3,
            ROW - 6,
            LABEL + w + 6,
            y + 13,
            escape(&short(n))
        );
        y += ROW;
    }
    y += 4;
    for s in &a.sets {
        let space_w = ((s.factor as f64 / max_factor) * SET_BAR as f64).round() as u32;
        let _ = writeln!(
            out,
            r##"<text x="32" y="{}" font-size="11">{}</text><rect x="{LABEL}" y="{}" width="{space_w}" height="7" fill="#bdbdbd"/>"##,
            y + 11,
            escape(&truncate(&s.name, 38)),
            y + 2
        );
        let (w, color, text) = match s.distinct_factor {
            Some(d) => (
                ((d as f64 / max_factor) * SET_BAR as f64).round() as u32,
                "#1e88e5",
                format!(
                    "×{} space, ×{} distinct{}",
                    s.factor,
                    d,
                    if s.dead { " (dead)" } else { "" }
                ),
            ),
            None => {
                let (size, distinct) = s
                    .group
                    .as_ref()
                    .map(|(n, d)| (n.to_string(), d.to_string()))
                    .unwrap_or_else(|| ("?".into(), "?".into()));
                (
                    space_w,
                    "#fb8c00",
                    format!(
                        "×{} space; coupled with {} other set{}: {} variants → {} distinct",
                        s.factor,
                        s.coupled_with.len(),
                        if s.coupled_with.len() == 1 { "" } else { "s" },
                        size,
                        distinct
                    ),
                )
            }
        };
        let _ = writeln!(
            out,
            r##"<rect x="{LABEL}" y="{}" width="{w}" height="7" fill="{color}"/><text x="{}" y="{}" font-size="11" fill="#333333">{}</text>"##,
            y + 9,
            LABEL + space_w.max(w) + 6,
            y + 13,
            escape(&text)
        );
        y += ROW;
    }
    y + 6
}
