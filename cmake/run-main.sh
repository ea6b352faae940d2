#!/usr/bin/env bash
# Installs the dependencies, builds panelrad (Release) and runs the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash cmake/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPANELRAD_BUILD_TESTS=OFF
cmake --build build -j "$(nproc)" --target panelrad_cli
./build/cli/panelrad check examples/meshes/hexagonal_prism.off
./build/cli/panelrad cube --levels 5
