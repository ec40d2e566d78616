#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on the built-in default:
# sample the Clifford torus T^2 in R^4, build its tangential Delaunay complex, refine it until it is
# thick, protected and consistent, and certify the result independently.
# Override with: DELCERT_MANIFOLD=builtin:sphere-3 DELCERT_EPS=0.4 bash scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Only the two programs (the tests and benchmarks are scripts/test.sh's job), in the same build/,
# and the Python module (target delcert_python, into build/python/) when CMake found Python 3,
# pybind11 and numpy: one more file to compile, the libraries are the programs'.
bash scripts/build.sh -- delcert delcert-certify >/dev/null
python_module=no
targets=$(cmake --build build --target help)  # (not piped into grep -q: pipefail would see the broken pipe)
if grep -qw delcert_python <<<"$targets"; then
  cmake --build build -j "${JOBS:-$(nproc)}" --target delcert_python >/dev/null
  python_module=yes
fi
manifold=${DELCERT_MANIFOLD:-builtin:clifford-torus-2}
eps=${DELCERT_EPS:-0.25}
out=${DELCERT_DEMO_OUT:-demo-output}
mkdir -p "$out"
run() { echo; echo "\$ $*"; "$@"; }
run build/delcert sample --manifold "$manifold" --eps "$eps" --seed 1 --out "$out/net.txt"
run build/delcert tangential --manifold "$manifold" --points "$out/net.txt" --out "$out/net-complex.txt" \
    --stats "$out/net-stats.json"
echo
echo "# The unrefined complex is usually not consistent: the certifier says why (exit 1 = REFUTED)."
run build/delcert-certify --manifold "$manifold" --points "$out/net.txt" --complex "$out/net-complex.txt" \
    --out "$out/net-certificate.json" || true
run build/delcert refine --manifold "$manifold" --points "$out/net.txt" --eps "$eps" --seed 1 --out "$out/refined"
run build/delcert-certify --manifold "$manifold" --points "$out/refined/points.txt" \
    --complex "$out/refined/complex.txt" --claims "$out/refined/claims.json" --out "$out/refined/certificate.json"

echo
if [ "$python_module" = yes ]; then
  # The interpreter the module was built for (scripts/build.sh picks Debian's /usr/bin/python3).
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)
  echo "# The Python module is in build/python/. The README's Python example (GUDHI's tangential complex"
  echo "# of an eps-net of S^2, certified; it prints CERTIFIED):"
  echo "PYTHONPATH=build/python ${python:-/usr/bin/python3} examples/python/certify_gudhi.py"
else
  echo "# The Python module was not built: CMake found no Python 3 with pybind11 and numpy (scripts/setup.sh"
  echo "# installs Debian's python3-dev, pybind11-dev and python3-numpy; README.md, the Python example)."
fi
