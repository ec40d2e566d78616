#!/usr/bin/env bash
# Configures and builds delcert into build/ (Release). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
# DELCERT_WERROR=ON|OFF is passed on only when set, so that the demo and the tests share one build.
werror=()
if [ -n "${DELCERT_WERROR:-}" ]; then werror=(-DDELCERT_WERROR="$DELCERT_WERROR"); fi
# The Python module is built for Debian's interpreter, the one setup.sh's python3-numpy and pybind11
# belong to (a python3 found first on PATH, e.g. pyenv's or a venv's, may lack them);
# -DPython3_EXECUTABLE=... among the arguments picks another.
python=()
if [ -x /usr/bin/python3 ]; then python=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${werror[@]}" "${python[@]}" "$@" >/dev/null
cmake --build build -j "$JOBS"
