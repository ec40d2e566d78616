#!/usr/bin/env bash
# Configures and builds delcert into build/ (Release). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDELCERT_WERROR="${DELCERT_WERROR:-OFF}" "$@" >/dev/null
cmake --build build -j "$JOBS"
