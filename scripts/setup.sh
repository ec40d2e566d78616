#!/usr/bin/env bash
# Installs the Debian packages delcert needs, if any is missing. ccache is the compiler cache
# scripts/build.sh, sanitize.sh and fuzz.sh use (scripts/compiler_cache.sh).
# Idempotent and quiet when everything is present; runs `apt-get update` only when something is missing.
# Then fetches the pinned three.js for the HTML report (scripts/fetch_threejs.sh), once.
set -euo pipefail
# clang and libclang-rt-14-dev (libFuzzer and clang's sanitizer runtimes) are for scripts/fuzz.sh;
# GCC's sanitizer runtimes (libasan8, libubsan1, for scripts/sanitize.sh) come with build-essential.
# python3-dev, pybind11-dev, python3-pybind11 and python3-numpy build the Python module (python/),
# python3-pytest tests it, python3-gudhi runs its GUDHI example (tests/python/).
# chromium (headless) opens the HTML report in its test (tests/report/, label browser; python3 runs it); curl, ca-certificates
# and openssl fetch and check the pinned three.js the report inlines (scripts/fetch_threejs.sh, after the packages).
# libopenmpi-dev and openmpi-bin (mpirun) build and test delcert-certify as an MPI program (-DDELCERT_MPI=ON).
PACKAGES=(build-essential cmake pkg-config ccache libcgal-dev libeigen3-dev libboost-dev libgmp-dev libmpfr-dev
          libgtest-dev libtbb-dev nlohmann-json3-dev libcli11-dev libmpfi-dev libgudhi-dev regina-normal-dev
          clang libclang-rt-14-dev
          python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-gudhi
          chromium python3 curl ca-certificates openssl libopenmpi-dev openmpi-bin)
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
bash "$(dirname "$0")/fetch_threejs.sh"
