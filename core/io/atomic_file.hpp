// Writes a whole file or nothing: the content goes to a temporary file beside the target,
// which is renamed over it only once everything was written and flushed.
#pragma once

#include <string>

namespace delcert::io {

// Throws InputError (naming `path`) if the directory is not writable or the write fails.
void write_file_atomically(const std::string& path, const std::string& content);

// Reads a whole file; throws InputError if it cannot be opened.
std::string read_file(const std::string& path);

}  // namespace delcert::io
