//! Synthetic keyword shaders for the audit's tests (API and CLI) and its bench.

/// `n` two-way multi_compile sets K0..K{n-1}. With `grouped`, keywords come in fours: K4g
/// guards code of its own, K4g+1 and K4g+2 guard code only together, K4g+3 is never read.
/// Otherwise every keyword guards a function of its own.
pub fn keyword_shader(n: usize, grouped: bool) -> Vec<(String, String)> {
    let mut pass = String::from("#shader synth\n#pass P\n");
    for i in 0..n {
        pass.push_str(&format!("#pragma multi_compile _ K{i}\n"));
    }
    pass.push_str("#import lib/features\n#endpass\n");
    let mut lib = String::new();
    for i in 0..n {
        let condition = match (grouped, i % 4) {
            (false, _) | (true, 0) => format!("defined(K{i})"),
            (true, 1) => format!("defined(K{i}) && defined(K{})", i + 1),
            (true, _) => continue,
        };
        lib.push_str(&format!(
            "#if {condition}\nfn feature_{i}() -> f32 {{ return {i}.0; }}\n#endif\n"
        ));
    }
    vec![
        ("synth.wgsl".to_string(), pass),
        ("lib/features.wgsl".to_string(), lib),
    ]
}

/// `n` two-way multi_compile sets K0..K{n-1}, each guarding a function of its own, and a
/// planted interaction fault: a function with a WGSL error (an unknown identifier) that is
/// compiled only when every `(set, on)` of `fault` holds (K{set} defined, or not).
pub fn planted_fault_shader(n: usize, fault: &[(usize, bool)]) -> Vec<(String, String)> {
    let mut files = keyword_shader(n, false);
    let condition: Vec<String> = fault
        .iter()
        .map(|&(set, on)| {
            if on {
                format!("defined(K{set})")
            } else {
                format!("!defined(K{set})")
            }
        })
        .collect();
    files[1].1.push_str(&format!(
        "#if {}\nfn planted() -> f32 {{ return not_declared; }}\n#endif\n",
        condition.join(" && ")
    ));
    files
}
