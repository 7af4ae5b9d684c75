#!/usr/bin/env bash
# Runs every test: install dependencies, build (release preset), GoogleTest + CLI tests via ctest,
# then the pytest suite of analysis/.
set -euo pipefail
cd "$(dirname "$0")/../.."
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
ctest --preset release
/usr/bin/python3 -m pytest -q analysis/tests
