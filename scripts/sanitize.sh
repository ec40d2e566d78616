#!/usr/bin/env bash
# Builds the suites that exercise the trusted base and the file readers with GCC's AddressSanitizer
# and UndefinedBehaviorSanitizer into build-asan/ and runs them: any out-of-bounds access, use after
# free, leak, signed overflow, invalid shift, misaligned or null access, ... aborts the test that
# triggers it.
#
# Suites (ctest labels = test folders): by default exact, io, topology, certify and fuzz: the
# certifier, everything it links (exact/, io/, topology/) and the fuzz regressions replayed through
# the readers. Only delcert-certify and those test programs are built (not the producer's tests, the
# benchmarks or the examples). DELCERT_SANITIZE_SUITES="core report" picks others; "all" builds and
# runs every suite but the install, Python and browser ones (below).
# Tests that honour DELCERT_TEST_SCALE run at a tenth of their size here (instrumented code is
# several times slower); override with DELCERT_TEST_SCALE=1 bash scripts/sanitize.sh.
# Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# Warnings as errors is scripts/test.sh's job (GCC warns differently with instrumentation).
werror=()
if [ -n "${DELCERT_WERROR:-}" ]; then werror=(-DDELCERT_WERROR="$DELCERT_WERROR"); fi
# RelWithDebInfo at -O1: line numbers in the reports, and fast enough to run the suite.
# No Python module (DELCERT_PYTHON=OFF): an ASan-instrumented extension cannot be loaded into the
# uninstrumented python3, and the module's code is the libraries' code, which the suite covers.
source scripts/compiler_cache.sh
CC=gcc CXX=g++ cmake -S . -B build-asan "${CACHE_ARGS[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DDELCERT_BUILD_BENCH=OFF -DDELCERT_BUILD_EXAMPLES=OFF -DDELCERT_BUILD_TESTS=ON -DDELCERT_PYTHON=OFF "${werror[@]}" "$@" >/dev/null
suites=(${DELCERT_SANITIZE_SUITES:-exact io topology certify fuzz})
if [ "${suites[*]}" = "all" ]; then
  cmake --build build-asan -j "${JOBS:-$(nproc)}"
  labels='.'
else
  cmake --build build-asan -j "${JOBS:-$(nproc)}" --target delcert-certify "${suites[@]/#/test_}"
  labels="^($(IFS='|'; echo "${suites[*]}"))\$"
fi
export DELCERT_TEST_SCALE=${DELCERT_TEST_SCALE:-0.1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd build-asan
# No suite may be silently empty (a typo in DELCERT_SANITIZE_SUITES, a test program not built).
if [ "$labels" != "." ]; then
  for suite in "${suites[@]}"; do
    if ! ctest -N -L "^$suite\$" | grep -q "Total Tests: [1-9]"; then
      echo "sanitize.sh: no tests with label $suite (DELCERT_SANITIZE_SUITES=${suites[*]})" >&2
      exit 1
    fi
  done
fi
# Not the install tests (label install, tests/install/): they check the package, not memory safety,
# and would compile their downstream projects (about 35 translation units) instrumented. Nor the
# Python tests (label python), should "$@" turn the module on again; nor the browser test (label
# browser, tests/report/browser_test.py): it runs Chromium, not our code under test (the report
# writer itself is covered by test_report).
ctest --output-on-failure -j "${JOBS:-$(nproc)}" -L "$labels" -LE 'install|python|browser'
