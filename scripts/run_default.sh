#!/usr/bin/env bash
# Installs dependencies (Debian packages), builds, and runs the main job on the built-in default:
# a procedural bedroom, written to ./objscan-out/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
mkdir -p objscan-out
./build/objscan scene --scene procedural:bedroom:1 --info --topview objscan-out/topview.png
echo "wrote objscan-out/topview.png" >&2
