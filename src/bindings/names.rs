//! Rust names for WGSL names: what the key and the structs both write, below both.

/// A WGSL name as a Rust type name: `light_data` → `LightData`, `PerMaterial` unchanged.
pub(crate) fn camel(name: &str) -> String {
    let mut out = String::new();
    for w in name.split(|c: char| !c.is_ascii_alphanumeric()) {
        let mut chars = w.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.push_str(chars.as_str());
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, 'S');
    }
    out
}

/// A field name Rust accepts for a WGSL member name.
pub(crate) fn field_name(name: &str) -> String {
    const RESERVED: &[&str] = &[
        "as", "async", "await", "box", "break", "const", "continue", "crate", "dyn", "else",
        "enum", "extern", "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match",
        "mod", "move", "mut", "pub", "ref", "return", "static", "struct", "trait", "true", "try",
        "type", "unsafe", "use", "where", "while", "yield",
    ];
    if RESERVED.contains(&name) {
        format!("r#{name}")
    } else if name.is_empty() {
        "unnamed".to_string()
    } else {
        name.to_string()
    }
}
