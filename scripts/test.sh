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
# Mesa's device-select layer complains about XDG_RUNTIME_DIR on headless machines; harmless.
export NODEVICE_SELECT=1

# --nocapture: the GPU tests print how much they compared.
cargo test --release -- --nocapture
