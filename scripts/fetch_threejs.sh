#!/usr/bin/env bash
# Fetches the pinned three.js release from the npm registry for `delcert-certify --report`
# (docs/formats.md, "The HTML report") and keeps the two files the report inlines:
#   third_party/three-VERSION/three.module.min.js              (build/ of the npm package)
#   third_party/three-VERSION/examples/jsm/controls/OrbitControls.js
# and the package's LICENSE. third_party/ is not in git (.gitignore): nothing fetched is committed.
# The tarball is checked against the registry's pinned sha512 integrity before anything is kept.
# Idempotent: does nothing when the files are there. Called by scripts/setup.sh; needs curl, tar and openssl. The build (CMake cache variable DELCERT_THREEJS_DIR) embeds the files into delcert-certify.
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=0.160.0
INTEGRITY="sha512-DLU8lc0zNIPkM7rH5/e1Ks1Z8tWCGRq6g8mPowdDJpw1CFBJMU7UoJjC6PefXW7z//SSl0b2+GCw14LB+uDhng=="
DEST="third_party/three-$VERSION"
FILES=(build/three.module.min.js examples/jsm/controls/OrbitControls.js LICENSE)
if [ -f "$DEST/three.module.min.js" ] && [ -f "$DEST/examples/jsm/controls/OrbitControls.js" ] && [ -f "$DEST/LICENSE" ]; then
  exit 0
fi
echo "setup: fetching three@$VERSION from the npm registry" >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
curl -fsSL --retry 3 -o "$tmp/three.tgz" "https://registry.npmjs.org/three/-/three-$VERSION.tgz"
actual="sha512-$(openssl dgst -sha512 -binary "$tmp/three.tgz" | base64 -w0)"
if [ "$actual" != "$INTEGRITY" ]; then
  echo "setup: three-$VERSION.tgz does not match the pinned integrity ($actual); nothing installed" >&2
  exit 1
fi
tar -xzf "$tmp/three.tgz" -C "$tmp" "${FILES[@]/#/package/}"
mkdir -p "$DEST.tmp/examples/jsm/controls"
cp "$tmp/package/build/three.module.min.js" "$DEST.tmp/"
cp "$tmp/package/examples/jsm/controls/OrbitControls.js" "$DEST.tmp/examples/jsm/controls/"
cp "$tmp/package/LICENSE" "$DEST.tmp/"
rm -rf "$DEST"
mv "$DEST.tmp" "$DEST"
