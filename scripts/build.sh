#!/usr/bin/env bash
# Configures and builds delcert into build/ (Release). Arguments go to cmake's configure step; names
# after "--" are the targets to build (default: everything, every test and benchmark included):
#   bash scripts/build.sh -DDELCERT_BUILD_BENCH=OFF -- delcert delcert-certify
# ccache is used when installed (scripts/compiler_cache.sh).
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
configure=() targets=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then shift; targets=("$@"); break; fi
  configure+=("$1"); shift
done
source scripts/compiler_cache.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${CACHE_ARGS[@]}" "${werror[@]}" "${python[@]}" "${configure[@]}" >/dev/null
if [ ${#targets[@]} -gt 0 ]; then
  cmake --build build -j "$JOBS" --target "${targets[@]}"
else
  cmake --build build -j "$JOBS"
fi
