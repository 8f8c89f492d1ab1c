//! `check-gpu` and `render` on the command line: a bad adapter filter is a clear error.

#[test]
fn check_gpu_with_an_adapter_that_is_not_there_is_a_clear_error() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args([
            "check-gpu",
            "--adapter",
            "no-such-adapter-anywhere",
            "--pass",
            "Final",
        ])
        .output()
        .expect("run check-gpu");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        !stderr.contains("panicked") && stderr.contains("no-such-adapter-anywhere"),
        "{stderr}"
    );
}

/// `check-gpu --shard K/3` in three processes, merged: the counts and verdict of one run.
#[test]
fn check_gpu_shards_merge_to_the_counts_of_one_run() {
    let tmp = tempfile::tempdir().unwrap();
    let check = |pass: &str, extra: &[&str]| -> Vec<u8> {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args([
                "check-gpu",
                "--json",
                "--shader",
                "standard",
                "--pass",
                pass,
            ])
            // Every 2048th variant of the full space (the passes are past the default covering
            // threshold since the BRDF tiers): ForwardBase's 55296 give 27, 9 per shard, and
            // Deferred's 110592 54. Sharding and merging do not depend on the count; every
            // 270th (205 and 410) made this binary the slowest GPU one with a cold Mesa cache.
            .args(["--full", "--sample", "2048", "--workers", "1"])
            .args(extra)
            .output()
            .expect("run check-gpu");
        assert!(
            out.status.code().is_some_and(|c| c <= 1),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        out.stdout
    };
    let whole: serde_json::Value = serde_json::from_slice(&check("ForwardBase", &[])).unwrap();
    let mut paths = Vec::new();
    for k in 1..=3 {
        let path = tmp.path().join(format!("check-{k}.json"));
        std::fs::write(&path, check("ForwardBase", &["--shard", &format!("{k}/3")])).unwrap();
        paths.push(path.display().to_string());
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("merge")
        .args(&paths)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let merged: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(merged.get("shard").is_none());
    assert_eq!(merged["fingerprint"], whole["fingerprint"]);
    let (a, b) = (&whole["passes"][0], &merged["passes"][0]);
    for key in [
        "variants_run",
        "distinct_shaders",
        "draws",
        "pixels_compared",
        "discarded_compared",
        "mismatches",
    ] {
        assert_eq!(a[key], b[key], "{key}");
    }
    assert_eq!(
        a["variants_run"].as_u64().unwrap(),
        55_296u64.div_ceil(2048)
    );
    // Another pass's report is from another selection: refused, naming it.
    let other = tmp.path().join("other.json");
    std::fs::write(&other, check("Deferred", &["--shard", "2/3"]).as_slice()).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["merge", &paths[0], other.to_str().unwrap(), &paths[2]])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr.contains("other.json` has fingerprint"), "{stderr}");
}

/// `check-gpu --cover 2` renders the pairwise covering sets of the standard passes (12 of
/// Deferred's 110592 variants, 13 of ForwardBase's 55296), each with a partner per keyword (18
/// each) so keyword coverage is judged, and compares them with the reference.
#[test]
fn check_gpu_cover_renders_the_covering_sets() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["check-gpu", "--cover", "2", "--shader", "standard"])
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("run check-gpu");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("ok   standard/Deferred: 30 variants"),
        "{stdout}"
    );
    assert!(
        stdout.contains("ok   standard/ForwardBase: 31 variants"),
        "{stdout}"
    );
    assert!(
        stdout.contains("2-wise covering set of 12 variants")
            && stdout.contains("plus 18 partners"),
        "{stdout}"
    );
}

/// A sample step that shares a factor with the shard count still splits the sample evenly:
/// `--full --sample 384` of ForwardBase's 55296 variants is 144, and shard 2/2 runs 72 of them
/// (it ran none when shards were taken by the index in the space).
#[test]
fn check_gpu_sample_and_shard_with_a_common_factor() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["check-gpu", "--json", "--shader", "standard", "--pass"])
        .args([
            "ForwardBase",
            "--full",
            "--sample",
            "384",
            "--shard",
            "2/2",
            "--workers",
            "1",
        ])
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("run check-gpu");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["passes"][0]["variants_run"], 72, "{report}");
}

/// URP's UniversalGBuffer: by default a 3-wise covering set plus one partner per keyword
/// (every keyword proven); `--full --sample N` walks the full space instead; `--cover` and
/// `--full` together are refused.
#[test]
fn check_gpu_universal_gbuffer_default_cover_and_full() {
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args(["check-gpu", "--json", "--pass", "UniversalGBuffer"])
            .args(extra)
            .env("NODEVICE_SELECT", "1")
            .output()
            .expect("run check-gpu")
    };
    let out = run(&[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let pass = &report["passes"][0];
    assert_eq!(pass["mismatches"], 0);
    let run_count = pass["variants_run"].as_u64().unwrap();
    let lib = wgsl_variants_shaders::library().unwrap();
    let urp = lib.pass("universal_lit", "UniversalGBuffer").unwrap();
    let cover = wgsl_variants::Space::full(urp).covering(3).unwrap().len() as u64;
    assert!((cover..=cover + 16).contains(&run_count), "{run_count}");
    assert_eq!(pass["untested_keywords"].as_array().unwrap().len(), 0);

    let out = run(&["--full", "--sample", "4096"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // Every 4096th of the 49,152 variants.
    assert_eq!(report["passes"][0]["variants_run"], 49_152 / 4096);

    let out = run(&["--full", "--cover", "2"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `render --frame` writes the reference, forward, deferred and difference pictures of the
/// whole frame in HDR and LDR; a shader or keywords next to `--frame` is a usage error.
#[test]
fn render_frame_writes_the_seven_pictures() {
    let tmp = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["render", "--frame", "--json", "--scale", "1", "--out"])
        .arg(tmp.path())
        .output()
        .expect("run render");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let written: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = written
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "frame_reference",
            "frame_forward_ldr",
            "frame_deferred_ldr",
            "frame_difference_ldr",
            "frame_forward_hdr",
            "frame_deferred_hdr",
            "frame_difference_hdr"
        ]
    );
    for name in names {
        let image = image::open(tmp.path().join(format!("{name}.png"))).unwrap();
        assert_eq!((image.width(), image.height()), (64, 48), "{name}");
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["render", "--frame", "standard", "Deferred", "--out"])
        .arg(tmp.path())
        .output()
        .expect("run render");
    assert_eq!(out.status.code(), Some(2));
}

/// `render --frame urp` writes URP's frame: the reference, forward, deferred and their
/// difference; a frame that does not exist is a usage error naming the ones that do.
#[test]
fn render_frame_urp_writes_the_four_pictures() {
    let tmp = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args([
            "render", "--frame", "urp", "--json", "--scale", "1", "--out",
        ])
        .arg(tmp.path())
        .output()
        .expect("run render");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let written: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = written
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "urp_frame_reference",
            "urp_frame_forward",
            "urp_frame_deferred",
            "urp_frame_difference"
        ]
    );
    for name in names {
        let image = image::open(tmp.path().join(format!("{name}.png"))).unwrap();
        assert_eq!((image.width(), image.height()), (64, 48), "{name}");
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["render", "--frame", "hdrp", "--out"])
        .arg(tmp.path())
        .output()
        .expect("run render");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("builtin") && stderr.contains("urp"),
        "{stderr}"
    );
}

/// `render standard ForwardBase --keywords SHADOWS_SCREEN` binds the main light's screen-space
/// mask (the check's directional light's), and the shadow darkens some pixels.
#[test]
fn render_forward_base_with_the_main_light_shadow() {
    let tmp = tempfile::tempdir().unwrap();
    let render = |keywords: &str, dir: &str| -> Vec<u8> {
        let out_dir = tmp.path().join(dir);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args(["render", "standard", "ForwardBase", "--keywords", keywords])
            .arg("--out")
            .arg(&out_dir)
            .env("NODEVICE_SELECT", "1")
            .output()
            .expect("run render");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read(out_dir.join("final.png")).expect("final.png")
    };
    let lit = render("_NORMAL_MAP", "lit");
    let shadowed = render("_NORMAL_MAP,SHADOWS_SCREEN", "shadowed");
    assert_ne!(lit, shadowed, "the mask changes the picture");
}

/// `check-gpu --timeout`: nonsense is refused before any GPU work, and a bound far below any
/// draw's time stops the check with the timeout error and the hint, without a panic.
#[test]
fn check_gpu_timeout_is_an_option_and_its_expiry_a_clear_error() {
    let run = |timeout: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args([
                "check-gpu",
                "--shader",
                "standard",
                "--pass",
                "ForwardBase",
                "--sample",
                "4096",
                &format!("--timeout={timeout}"),
            ])
            .output()
            .expect("run check-gpu")
    };
    for bad in ["0", "-1", "soon", "inf"] {
        let out = run(bad);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--timeout {bad}: {stderr}");
        assert!(
            stderr.contains("not a positive number of seconds"),
            "{stderr}"
        );
    }
    let out = run("0.000001");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("did not finish within 0.000001 s")
            && stderr.contains("raise `--timeout`")
            && !stderr.contains("panicked"),
        "{stderr}"
    );
}
