#!/usr/bin/env bash
# Installs dependencies (Debian packages), builds, and runs every test. This is what CI runs.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"${jobs}" --timeout 600
