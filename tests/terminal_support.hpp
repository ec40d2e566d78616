// Running a built program with a pseudo-terminal as its stderr (the progress line, issue 13 §5).
// Apart from tests/test_support.hpp so that the tests that do not use it need not be recompiled.
#pragma once

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <string>

#include "tests/test_support.hpp"

namespace delcert::test {

// Runs a shell command line with a pseudo-terminal as its stdin, stdout and stderr (redirect
// stdout inside `command` to keep it apart); `output` is what the terminal showed.
inline CommandResult run_on_terminal(const std::string& command) {
  CommandResult r;
  int master = -1;
  const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
  if (pid < 0) return r;
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::array<char, 4096> buf;
  for (;;) {  // until the child's side is closed (EIO on Linux)
    const ssize_t n = ::read(master, buf.data(), buf.size());
    if (n > 0)
      r.output.append(buf.data(), static_cast<std::size_t>(n));
    else if (n < 0 && errno == EINTR)
      continue;
    else
      break;
  }
  ::close(master);
  int st = 0;
  ::waitpid(pid, &st, 0);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

}  // namespace delcert::test
