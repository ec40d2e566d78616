// Writes a whole file or nothing: the content goes to a temporary file beside the target,
// which is renamed over it only once everything was written and flushed.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace delcert::io {

// Throws InputError (naming `path`) if the directory is not writable or the write fails.
void write_file_atomically(const std::string& path, const std::string& content);

// Several files, all or nothing as far as the file system allows: every content is first written
// and flushed to a temporary file beside its target; only when all of them are complete are they
// renamed over their targets (renames within a directory do not fail for lack of space). If any
// write fails, every temporary is removed and no target has changed.
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files);

// Refuses (InputError naming `path`, exit 2) an output path that cannot be written or that is
// one of the inputs: its directory must exist (unless `directory_may_be_created`), it must not be
// an existing directory, and it must not be the same file as any of `inputs` or `other_outputs`.
// Identity is by file system (std::filesystem::equivalent when both exist, else
// weakly_canonical paths), not by spelling. "builtin:NAME" inputs are not files and are skipped.
// Call it for every output before any work is done.
void check_output_path(const std::string& path, const std::string& option, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& other_outputs = {}, bool directory_may_be_created = false);

// Reads a whole file; throws InputError if it cannot be opened.
std::string read_file(const std::string& path);

}  // namespace delcert::io
