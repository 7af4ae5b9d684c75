#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release). The CLI lands in build/bin/ccdlab.
set -euo pipefail
cd "$(dirname "$0")/../.."
preset="${1:-release}"
# CCDLAB_WERROR=1 (the test command sets it): every compiler warning is an error, so a new one fails CI.
cmake --preset "$preset" -DCMAKE_COMPILE_WARNING_AS_ERROR="$([ "${CCDLAB_WERROR:-0}" = 1 ] && echo ON || echo OFF)" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
