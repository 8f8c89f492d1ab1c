#!/usr/bin/env bash
# The test command (README): installs what the tests need, then runs every test.
#
# - Mesa's lavapipe (software Vulkan, Debian `mesa-vulkan-drivers`) for the GPU tests, when no
#   Vulkan driver is installed.
# - Tests run on the release profile so they share one build with the main job
#   (`cargo run --release -- validate --all`).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1; then
    echo "== installing Mesa lavapipe (mesa-vulkan-drivers) for the GPU tests"
    sudo=""
    if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq mesa-vulkan-drivers >/dev/null
fi
# SPIRV-Tools' spirv-val and glslang's glslangValidator check the SPIR-V and GLSL that `emit`
# writes (tests/emit.rs).
if ! command -v spirv-val >/dev/null 2>&1 || ! command -v glslangValidator >/dev/null 2>&1; then
    echo "== installing spirv-tools and glslang-tools for the emit tests"
    sudo=""
    if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq spirv-tools glslang-tools >/dev/null
fi
# Mesa's device-select layer complains about XDG_RUNTIME_DIR on headless machines; harmless.
export NODEVICE_SELECT=1

# Every crate of the workspace (library, command line, GPU harness, the bindings' compile-fail
# tests). --nocapture: the GPU tests print how much they compared.
cargo test --release --ignore-rust-version --workspace -- --nocapture

# The examples (README "Using the shaders in your renderer"), both built by `cargo test` above
# with the workspace's features (running the binaries avoids a second build of the library):
# - render_variant: a wgpu program that draws a built-in and a URP G-buffer through generated
#   bindings (typed keys, structs, layouts) and writes PNGs (render_variant.png,
#   render_variant-urp.png);
# - examples/baked: a renderer crate whose build.rs bakes the library with typed bindings; it
#   looks baked variants up and draws two with wgpu (baked-deferred.png, baked-urp-gbuffer.png).
#   Its tests (tests/gpu_check.rs, run above) hold those draws to the GPU check's.
echo "== example: render_variant"
target/release/examples/render_variant target/render_variant.png
echo "== example crate: examples/baked"
target/release/wgsl-variants-baked-example target
