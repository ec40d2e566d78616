#!/usr/bin/env bash
# Configures and builds delcert into build/ (Release). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
# DELCERT_WERROR=ON|OFF is passed on only when set, so that the demo and the tests share one build.
werror=()
if [ -n "${DELCERT_WERROR:-}" ]; then werror=(-DDELCERT_WERROR="$DELCERT_WERROR"); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${werror[@]}" "$@" >/dev/null
cmake --build build -j "$JOBS"
