#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on the built-in default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
out=${DELCERT_DEMO_OUT:-demo-output}
mkdir -p "$out"
echo "== delcert sample --manifold builtin:clifford-torus-2 --eps 0.25 --seed 1"
build/delcert sample --manifold builtin:clifford-torus-2 --eps 0.25 --seed 1 --out "$out/clifford-torus-2.points"
