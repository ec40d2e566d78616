#!/usr/bin/env bash
# delcert-certify under mpirun with 2 ranks writes the single-process certificate, byte for byte
# (--no-times), prints the same lines and exits with the same status; bad input is reported once,
# with exit status 2 and no certificate. Registered by tests/CMakeLists.txt when DELCERT_MPI=ON.
#   mpi_test.sh MPIEXEC BINARY_DIR FIXTURES_DIR
set -euo pipefail
mpiexec=$1 bin=$2 fixtures=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Two ranks on any machine (--oversubscribe: even on one core), and as root in CI containers.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cd "$work"
"$bin/delcert" sample --manifold builtin:sphere-2 --eps 0.12 --seed 3 --out s2.pts > /dev/null
"$bin/delcert" tangential --manifold builtin:sphere-2 --points s2.pts --threads 1 --out s2.complex > /dev/null
"$bin/delcert" sample --manifold builtin:clifford-torus-3 --eps 0.35 --seed 4 --out t3.pts > /dev/null

failures=0
same() {  # NAME EXPECTED_STATUS ARGS...: one process (2 threads) against 2 ranks (1 thread each)
  local name=$1 want=$2; shift 2
  local a=0 b=0
  "$bin/delcert-certify" "$@" --no-times --threads 2 --out "$name.1.json" > "$name.1.txt" 2> "$name.1.err" || a=$?
  "$mpiexec" -n 2 "$bin/delcert-certify" "$@" --no-times --threads 1 --out "$name.2.json" > "$name.2.txt" 2> "$name.2.err" || b=$?
  sed -i '/^certificate /d' "$name.1.txt" "$name.2.txt"
  if [ "$a" != "$want" ] || [ "$b" != "$want" ]; then
    echo "FAIL $name: exit $a (one process) and $b (2 ranks), expected $want"; failures=$((failures + 1)); cat "$name.2.err"
  elif ! cmp -s "$name.1.json" "$name.2.json"; then
    echo "FAIL $name: the certificates differ"; diff <(tr ',' '\n' < "$name.1.json") <(tr ',' '\n' < "$name.2.json") | head -20
    failures=$((failures + 1))
  elif ! cmp -s "$name.1.txt" "$name.2.txt"; then
    echo "FAIL $name: the printed lines differ"; diff "$name.1.txt" "$name.2.txt"; failures=$((failures + 1))
  else
    echo "ok   $name (exit $a, $(wc -c < "$name.1.json") bytes)"
  fi
}
# Every check, check 7 with insecure simplices (witnesses), the covering and Del_M.
same sphere2-verify 0 --manifold builtin:sphere-2 --points s2.pts --complex s2.complex
same sphere2-audit 0 --manifold builtin:sphere-2 --points s2.pts
# m = 3, an inconsistent Del_TM: REFUTED, with witnesses from the split stars.
same torus3-audit 1 --manifold builtin:clifford-torus-3 --points t3.pts --skip-restricted
# A broken complex: two triangles replaced (check 3's witnesses come from both ranks' stars).
same octahedron-flipped 1 --manifold builtin:sphere-2 --points "$fixtures/points/octahedron.off" \
  --complex "$fixtures/certify/octahedron-flipped.complex"
# Exact ties (never CERTIFIED).
same cocircular 1 --manifold builtin:sphere-2 --points "$fixtures/certify/sphere-cocircular.txt"

# Rank 1 holds its block and a halo only. A fixed halo far too small (two cells): check 7's
# neighbourhoods (5 eps) leave it, and rank 0 reports those simplices as not evaluated, with the
# reason (check 7 is not claimed here, so the verdict stands on the other checks; the in-process
# test Distributed.HaloTooSmallIsUndecidedUnlessWidened also makes stars leave it: UNDECIDED).
status=0
"$mpiexec" -n 2 "$bin/delcert-certify" --manifold builtin:sphere-2 --points s2.pts --skip-restricted --halo 1e-6 \
  --threads 1 --out halo.json > halo.txt 2> halo.err || status=$?
if [ "$status" != 0 ] || ! grep -q '"not_evaluated_halo_too_small"' halo.json || ! grep -q "halo too small" halo.txt; then
  echo "FAIL fixed halo too small: exit $status, or check 7 does not report the halo"; cat halo.err halo.txt
  failures=$((failures + 1))
else
  echo "ok   fixed halo too small (check 7: $(grep -o '[0-9]* not evaluated (an MPI rank.s halo too small)' halo.txt))"
fi

# Bad input: exit 2 from every rank, the message once, no certificate.
status=0
"$mpiexec" -n 2 "$bin/delcert-certify" --manifold builtin:sphere-2 --points "$fixtures/bad/points-nan.txt" \
  --out bad.json > bad.txt 2> bad.err || status=$?
if [ "$status" != 2 ] || [ -e bad.json ] || [ "$(grep -c "points-nan.txt:4:" bad.err)" != 1 ]; then
  echo "FAIL bad input: exit $status, certificate $( [ -e bad.json ] && echo written || echo absent)"; cat bad.err
  failures=$((failures + 1))
else
  echo "ok   bad input (exit 2, one message, no certificate)"
fi
exit $((failures > 0))
