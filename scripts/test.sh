#!/usr/bin/env bash
# README command 2: install what is missing, build everything, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ "${CI:-}" = "true" ]; then export DELCERT_WERROR=ON; fi
# delcert-certify as an MPI program too (off by default), so that its 2-rank test runs.
bash scripts/build.sh -DDELCERT_MPI=ON
cd build
# After setup.sh every optional part is there: its tests must be too, not quietly left out.
for label in python docs browser install mpi; do
  if ! ctest -N -L "$label" | grep -q "Total Tests: [1-9]"; then
    echo "test.sh: no tests with label $label were configured (see cmake's status lines in build/)" >&2
    exit 1
  fi
done
ctest --output-on-failure -j "${JOBS:-$(nproc)}"
