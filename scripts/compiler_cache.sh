# Sourced by scripts/build.sh, sanitize.sh and fuzz.sh: use ccache when it is installed (setup.sh
# installs it), so that a rebuild, or a clean clone in another folder, compiles only what changed.
# Sets the array CACHE_ARGS (cmake configure arguments, empty without ccache).
#
# CCACHE_BASEDIR makes ccache hash the paths under the repository as relative paths, so two clones
# in different folders share every object; CCACHE_NOHASHDIR keeps the working directory out of the
# hash of objects with debug information (the sanitizer and fuzz builds: -g). The cache itself is
# ccache's own, in the user's cache directory (~/.cache/ccache), never in the repository.
# DELCERT_CCACHE=0 turns it off.
CACHE_ARGS=()
if [ "${DELCERT_CCACHE:-1}" != "0" ] && command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(pwd -P)}
  export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
  # ccache's own size limit (5 GB by default) holds the three builds (Release, ASan + UBSan, fuzz)
  # several times over: they take about 0.6 GB compressed (docs/development.md).
  CACHE_ARGS=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
else
  # An earlier configure of the same build folder may have recorded the launcher.
  CACHE_ARGS=(-UCMAKE_CXX_COMPILER_LAUNCHER -UCMAKE_C_COMPILER_LAUNCHER)
fi
