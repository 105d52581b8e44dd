#!/usr/bin/env bash
# Installs everything SuperDex needs to build and test on a Debian/Ubuntu machine.
# Safe to run again: it installs only what is missing. Run as root (or with sudo available).
set -euo pipefail

# Debian packages: compiler toolchain and the C++ libraries the engine links against.
APT_PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev nlohmann-json3-dev libtinyxml2-dev libhdf5-dev libtbb-dev
  libsuitesparse-dev libopenblas-dev libspectra-dev libqhull-dev libassimp-dev libccd-dev
  libgtest-dev libgmock-dev libbenchmark-dev libboost-dev
  # the fuzz targets (tools/fuzz.sh): clang and its libFuzzer and sanitizer runtimes
  clang libclang-rt-14-dev
)
# the debugger page: Node.js and npm build it, chromium runs its tests (playwright-core); a
# machine may already have them from elsewhere (a Node.js package that bundles npm)
command -v node >/dev/null 2>&1 || APT_PACKAGES+=(nodejs)
command -v npm >/dev/null 2>&1 || APT_PACKAGES+=(npm)
command -v chromium >/dev/null 2>&1 || APT_PACKAGES+=(chromium)

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]})); then
  echo "[bootstrap] installing Debian packages: ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# uv manages the Python environment; install it with pip when absent.
if ! command -v uv >/dev/null 2>&1; then
  echo "[bootstrap] installing uv"
  python3 -m pip install --quiet uv
fi
command -v uv >/dev/null 2>&1 || { echo "[bootstrap] uv is not on PATH after install" >&2; exit 1; }
