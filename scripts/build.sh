#!/usr/bin/env bash
# Configures and builds FiberPLI out of source in build/ (Release, shared libraries).
# Uses ccache when it is installed (not required).
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON "${launcher[@]}"
cmake --build build -j"$(nproc)"
