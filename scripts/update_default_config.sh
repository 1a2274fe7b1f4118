#!/usr/bin/env bash
# Regenerates config/default.yaml from the options structs (the code holds the defaults).
set -euo pipefail
cd "$(dirname "$0")/.."
./build/objscan run --print-config > config/default.yaml.tmp
mv config/default.yaml.tmp config/default.yaml
echo "updated config/default.yaml"
