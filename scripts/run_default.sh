#!/usr/bin/env bash
# Installs dependencies (Debian packages), builds, and runs the main job on the built-in default:
# `objscan run` scans procedural:bedroom:1 with the built-in procedural model database (built on
# first use and cached in ~/.cache/objscan) and writes ./objscan-out/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
./build/objscan run
