#!/usr/bin/env bash
# Records what the two programs write — output files, stdout, stderr and exit status — for a fixed
# set of runs, so that a refactoring can be shown to change no byte of behaviour:
#
#   bash scripts/snapshot.sh build /tmp/before     # on the old tree
#   bash scripts/snapshot.sh build /tmp/after      # on the new tree
#   diff -r /tmp/before /tmp/after                 # must print nothing
#
# Wall-clock times are left out where the programs offer it (--no-times) and masked in the
# tangential --stats summary, which always has them. Runs in a few minutes on 2 cores.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: snapshot.sh BUILD_DIR OUT_DIR}
out=${2:?usage: snapshot.sh BUILD_DIR OUT_DIR}
dc=$build/delcert
cert=$build/delcert-certify
[ -x "$dc" ] && [ -x "$cert" ] || { echo "snapshot: build $dc and $cert first" >&2; exit 2; }
rm -rf "$out" && mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# run NAME CMD... : records stdout, stderr and the exit status of CMD under $out/NAME/.
# The temporary directory's name is replaced by "TMP" so that messages naming files compare.
run() {
  local name=$1; shift
  mkdir -p "$out/$name"
  "$@" >"$out/$name/stdout" 2>"$out/$name/stderr"
  echo $? >"$out/$name/status"
}
keep() { # keep NAME FILE... : copies output files into the record
  local name=$1; shift
  mkdir -p "$out/$name"
  local f
  for f in "$@"; do [ -e "$f" ] && cp -r "$f" "$out/$name/"; done
}

# --- delcert: sample, tangential, refine on several manifolds -----------------------------------
for case in clifford-torus-2:0.25 sphere-2:0.3 sphere-3:0.5 torus-of-revolution:0.3; do
  m=${case%%:*} eps=${case#*:}
  run "sample-$m" "$dc" sample --manifold "builtin:$m" --eps "$eps" --seed 1 --out "$tmp/$m.txt"
  keep "sample-$m" "$tmp/$m.txt"
  run "tangential-$m" "$dc" tangential --manifold "builtin:$m" --points "$tmp/$m.txt" \
      --out "$tmp/$m-complex.txt" --stats "$tmp/$m-stats.json" --threads 2
  keep "tangential-$m" "$tmp/$m-complex.txt" "$tmp/$m-stats.json"
  run "certify-net-$m" "$cert" --manifold "builtin:$m" --points "$tmp/$m.txt" \
      --complex "$tmp/$m-complex.txt" --out "$tmp/$m-net-cert.json" --no-times --threads 2
  keep "certify-net-$m" "$tmp/$m-net-cert.json"
done
for case in clifford-torus-2:practical sphere-2:paper sphere-3:practical; do
  m=${case%%:*} mode=${case#*:}
  eps=$(case $m in clifford-torus-2) echo 0.25;; sphere-2) echo 0.3;; *) echo 0.5;; esac)
  run "refine-$m-$mode" "$dc" refine --manifold "builtin:$m" --points "$tmp/$m.txt" --eps "$eps" \
      --mode "$mode" --seed 1 --threads 2 --out "$tmp/refined-$m-$mode"
  keep "refine-$m-$mode" "$tmp/refined-$m-$mode"
  d=$tmp/refined-$m-$mode
  run "certify-refined-$m-$mode" "$cert" --manifold "builtin:$m" --points "$d/points.txt" \
      --complex "$d/complex.txt" --claims "$d/claims.json" --out "$d/certificate.json" --no-times --threads 2
  keep "certify-refined-$m-$mode" "$d/certificate.json"
done
# refine from an eps-net it builds itself, with a cap that is hit (exit 4, partial output)
run refine-net-so3 "$dc" refine --manifold builtin:so3 --eps 0.9 --seed 3 --threads 2 --out "$tmp/so3"
keep refine-net-so3 "$tmp/so3"
run refine-capped "$dc" refine --manifold builtin:sphere-2 --points "$tmp/sphere-2.txt" --eps 0.3 \
    --max-inserted 3 --threads 2 --out "$tmp/capped"
keep refine-capped "$tmp/capped"
# audit mode (no complex): the certifier computes the tangential complex itself
run audit-sphere-2 "$cert" --manifold builtin:sphere-2 --points "$tmp/sphere-2.txt" --no-times \
    --out "$tmp/audit.json"
keep audit-sphere-2 "$tmp/audit.json"

# --- delcert-certify on the fixtures ------------------------------------------------------------
oct=(--points fixtures/points/octahedron.off)
i=0
certify_case() { # a certificate and the messages of one certifier run
  i=$((i + 1))
  run "fixture-$i" "$cert" "$@" --no-times --out "$tmp/fixture-$i.json"
  keep "fixture-$i" "$tmp/fixture-$i.json"
}
for c in fixtures/certify/*.complex fixtures/complexes/*.off; do
  certify_case --manifold builtin:sphere-2 "${oct[@]}" --complex "$c"
done
for cl in fixtures/certify/*claims*.json; do
  certify_case --manifold builtin:sphere-2 "${oct[@]}" --complex fixtures/certify/octahedron.complex --claims "$cl"
done
for s in fixtures/certify/spec-*.json fixtures/bad/spec-*.json; do
  certify_case --manifold "$s" "${oct[@]}" --complex fixtures/certify/octahedron.complex
done
for p in fixtures/bad/points-*.txt fixtures/certify/points-off-manifold.txt; do
  certify_case --manifold builtin:sphere-2 --points "$p" --complex fixtures/certify/octahedron.complex
done
for c in fixtures/bad/complex-*; do
  certify_case --manifold builtin:sphere-2 "${oct[@]}" --complex "$c"
done
certify_case --manifold builtin:clifford-torus-2 --points fixtures/certify/clifford-square-grid.txt
certify_case --manifold builtin:so3 --points fixtures/certify/so3-wrong-component.txt
S=fixtures/soundness
certify_case --manifold $S/overflow/spec.json --points $S/overflow/points.txt --complex $S/overflow/complex.txt
certify_case --manifold $S/hang/spec-plane.json --points $S/hang/pts-subnormal.txt
certify_case --manifold builtin:sphere-2 --points $S/hang/fib40.txt --complex $S/hang/complex-32simplex.txt
certify_case --manifold $S/hang/spec-exponent-hang.json --points $S/hang/pts-sphere6.txt
for s in $S/parse/spec-*.json; do
  certify_case --manifold "$s" "${oct[@]}" --complex fixtures/certify/octahedron.complex
done
for cl in $S/parse/claims-*.json; do
  certify_case --manifold builtin:sphere-2 "${oct[@]}" --complex fixtures/certify/octahedron.complex --claims "$cl"
done
certify_case --manifold builtin:clifford-torus-2 --points fixtures/points/clifford-square.noff
# usage errors
run usage-certify "$cert" --manifold builtin:sphere-2
run usage-refine "$dc" refine --manifold builtin:sphere-2 --eps -1 --out "$tmp/never"
run usage-sample "$dc" sample --manifold builtin:nothing --eps 0.1 --out "$tmp/never"
# Final pass over everything recorded: the temporary directory's name becomes TMP, and wall-clock
# figures become T (numbers inside a JSON object whose key names a time, "0.012 s" in messages).
python3 - "$out" "$tmp" <<'PY'
import os, re, sys
root, tmp = sys.argv[1], sys.argv[2]
number = re.compile(r'-?[0-9][0-9.eE+-]*')
def mask_json_times(text):
    out, i = [], 0
    for m in re.finditer(r'"[A-Za-z_]*(?:time|seconds)[A-Za-z_]*"\s*:\s*', text):
        if m.start() < i: continue
        j = m.end()
        if text[j:j+1] == '{':
            k = text.index('}', j)
            out.append(text[i:j]); out.append(number.sub('T', text[j:k])); i = k
        else:
            n = number.match(text, j)
            if n: out.append(text[i:j]); out.append('T'); i = n.end()
    out.append(text[i:])
    return ''.join(out)
for d, _, files in os.walk(root):
    for f in files:
        p = os.path.join(d, f)
        with open(p, 'rb') as fh: b = fh.read()
        try: t = b.decode()
        except UnicodeDecodeError: continue
        t = t.replace(tmp, 'TMP')
        t = mask_json_times(t)
        t = re.sub(r'\b[0-9]+\.[0-9]+ s\b', 'T s', t)
        with open(p, 'w') as fh: fh.write(t)
PY
echo "snapshot: $(ls "$out" | wc -l) runs recorded in $out"
