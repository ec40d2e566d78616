// Where the tests find the fixtures, the source tree and the built programs.
//
// The paths are defined in one generated translation unit (tests/test_paths.cpp.in, configured into
// the build tree), not as compile definitions of every test: a definition holding an absolute path
// would make every test object depend on the folder the repository was cloned into, and a compiler
// cache (scripts/build.sh uses ccache) could then never reuse an object across clones.
#pragma once

namespace delcert::test_paths {
const char* fixtures_dir();  // <source>/fixtures
const char* source_dir();    // the repository root
const char* binary_dir();    // the build tree (delcert, delcert-certify)
}  // namespace delcert::test_paths

#define DELCERT_FIXTURES_DIR (::delcert::test_paths::fixtures_dir())
#define DELCERT_SOURCE_DIR (::delcert::test_paths::source_dir())
#define DELCERT_BINARY_DIR (::delcert::test_paths::binary_dir())
