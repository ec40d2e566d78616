#!/usr/bin/env bash
# Fuzzes every file reader with libFuzzer + ASan + UBSan (clang) for SECONDS_PER_TARGET seconds
# each (default 60) and exits non-zero if any target found a crash, an undocumented exception,
# a broken round trip, a sanitizer report, a timeout (-timeout=5 s per input) or an out-of-memory
# (-rss_limit_mb=2048). Targets and what counts as a failure: fuzz/readers.hpp.
#
# The build goes to build-fuzz/ (cmake -DDELCERT_FUZZ=ON: exact/ and io/ only).
# Each run starts from a fresh scratch corpus, build-fuzz/corpus/TARGET/, seeded from fixtures/ (and,
# for the spec reader, from its kept corpus fuzz/corpus/spec/);
# crashing inputs are written to build-fuzz/artifacts/TARGET/. Keep every crash as a regression:
# copy it to fuzz/regressions/TARGET/ (replayed by tests/fuzz/fuzz_regression_test.cpp).
#
# Environment: DELCERT_FUZZ_TARGETS="points spec" (a subset), DELCERT_FUZZ_SEED (libFuzzer's
# -seed, default 1), DELCERT_FUZZ_MAX_LEN (-max_len, default 4096), JOBS (build parallelism).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
targets=(${DELCERT_FUZZ_TARGETS:-points complex spec claims polynomial})
seed=${DELCERT_FUZZ_SEED:-1}
max_len=${DELCERT_FUZZ_MAX_LEN:-4096}
bash scripts/setup.sh
source scripts/compiler_cache.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz "${CACHE_ARGS[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDELCERT_FUZZ=ON >/dev/null
cmake --build build-fuzz -j "${JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}" >/dev/null

# Seeds: every text fixture for the two text readers (each detects its format from the first
# line), every JSON fixture for the two JSON readers, every quoted polynomial of the JSON
# fixtures for the polynomial parser.
seed_corpus() {
  local target=$1 dir=$2
  case $target in
    points|complex) find fixtures -type f ! -name '*.json' ! -name '*.md' -exec cp {} "$dir/" \; ;;
    spec|claims)    find fixtures -type f -name '*.json' -exec cp --backup=numbered {} "$dir/" \;
                    # The spec target's own corpus of earlier campaigns (named by content hash).
                    if [ "$target" = spec ]; then find fuzz/corpus/spec -type f -exec cp {} "$dir/" \; ; fi ;;
    polynomial)
      local i=0
      while IFS= read -r p; do
        i=$((i + 1)); printf '%s' "$p" > "$dir/seed-$i"
      done < <(find fixtures -type f -name '*.json' -exec grep -ho '"[^"]*x[0-9][^"]*"' {} + | tr -d '"' | sort -u)
      printf '3;x1^2 + x2^2 + x3^2 - 1' > "$dir/seed-n3"
      printf '2.5e-3' > "$dir/seed-rational"
      printf '1/3' > "$dir/seed-fraction" ;;
  esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
failed=()
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t artifacts=build-fuzz/artifacts/$t log=build-fuzz/fuzz_$t.log
  rm -rf "$corpus" "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  seed_corpus "$t" "$corpus"
  dict=()
  if [ -f "fuzz/$t.dict" ]; then dict=(-dict="fuzz/$t.dict"); fi
  status=0
  build-fuzz/fuzz/fuzz_"$t" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -max_len="$max_len" \
      -seed="$seed" -print_final_stats=1 "${dict[@]}" -artifact_prefix="$artifacts/" "$corpus" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\1 runs in \2 s/p' "$log" | tail -1)
  found=$(find "$artifacts" -type f | sort)
  if [ "$status" -ne 0 ] || [ -n "$found" ]; then
    failed+=("$t")
    echo "fuzz_$t: FAILED (exit $status) after ${runs:-an unknown number of runs}; log: $log"
    grep -E "^(==[0-9]+==ERROR|SUMMARY|delcert fuzz|.*runtime error)" "$log" | head -5 | sed 's/^/  /'
    for f in $found; do echo "  crashing input: $f"; done
  else
    echo "fuzz_$t: ok, $runs (seed $seed)"
  fi
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  echo "fuzz: reproduce with build-fuzz/fuzz/fuzz_TARGET FILE; keep each input in fuzz/regressions/TARGET/" >&2
  exit 1
fi
