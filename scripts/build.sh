#!/usr/bin/env bash
# Configures and builds FiberPLI out of source in build/ (Release, shared libraries).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON
cmake --build build -j"$(nproc)"
