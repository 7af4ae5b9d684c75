#!/usr/bin/env bash
# Installs every build, test and analysis dependency of ccdlab from Debian packages (clang-14 with libomp and
# libFuzzer: the sanitizer builds and the fuzz targets; three.js for the teaching page, read at export time, and
# chromium for its headless test).
# Idempotent: skips apt-get when all packages are already present. Needs root (or sudo).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
  libyaml-cpp-dev libbenchmark-dev libgtest-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  python3 python3-venv python3-pip python3-setuptools python3-wheel python3-meshio python3-matplotlib python3-numpy python3-pandas python3-scipy python3-pytest
  libhwy-dev libembree-dev pybind11-dev python3-dev
  clang-14 libomp-14-dev libclang-rt-14-dev libfuzzer-14-dev llvm-14
  libjs-three chromium fonts-dejavu-core
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
