#!/usr/bin/env bash
# Builds the fuzz targets (clang, ASan + UBSan, libFuzzer) in build-fuzz/. .ci/setup runs it.
set -euo pipefail
cd "$(dirname "$0")/../.."
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLWCPORT_FUZZ=ON -DLWCPORT_HOST=ON > /dev/null
cmake --build build-fuzz -j"$(nproc)" --target lwcport_fuzz lwcport_lsp_fuzz lwcport_host_fuzz
