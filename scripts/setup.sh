#!/usr/bin/env bash
# Installs the Debian packages delcert needs, if any is missing.
# Idempotent and quiet when everything is present; runs `apt-get update` only when something is missing.
set -euo pipefail
# clang and libclang-rt-14-dev (libFuzzer and clang's sanitizer runtimes) are for scripts/fuzz.sh;
# GCC's sanitizer runtimes (libasan8, libubsan1, for scripts/sanitize.sh) come with build-essential.
PACKAGES=(build-essential cmake pkg-config libcgal-dev libeigen3-dev libboost-dev libgmp-dev libmpfr-dev
          libgtest-dev libtbb-dev nlohmann-json3-dev libcli11-dev libmpfi-dev libgudhi-dev regina-normal-dev
          clang libclang-rt-14-dev)
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
