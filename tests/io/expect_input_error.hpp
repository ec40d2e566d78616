// Shared assertion of the io tests: reading a malformed file must throw io::InputError naming the
// file and the line, with a message that starts "FILE:LINE: " ("FILE: " when not tied to a line).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "io/input_error.hpp"

namespace delcert::test {

template <class Read>
void expect_input_error(Read&& read, const std::string& path, long line, const std::string& message_part) {
  try {
    read(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const io::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << what;
    EXPECT_NE(what.find(message_part), std::string::npos) << what;
    const std::string prefix = line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
  }
}

}  // namespace delcert::test
