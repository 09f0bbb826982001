// Runs the `metrica` command as a user does (a child process, stdout and
// stderr together) and tells how it ended.
#pragma once

#include <doctest/doctest.h>

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace metrica::test {

struct Run {
  int code = -1;
  bool signalled = false;
  std::string output;  // stdout and stderr together
};

// The command run through `prefix` (e.g. "env VAR=value").
inline Run metrica_cli_in_env(const std::string& prefix, const std::string& args) {
  Run r;
  const std::string cmd = prefix + " " + std::string(METRICA_CLI) + " " + args + " 2>&1";
  std::FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.signalled = WIFSIGNALED(status);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline Run metrica_cli(const std::string& args) { return metrica_cli_in_env("", args); }

inline bool has(const Run& r, const std::string& s) { return r.output.find(s) != std::string::npos; }

// " --concurrency serial" where the command has the serial pipeline, else
// (the AddressSanitizer build compiles the speculative one only) one
// thread: a run that gives the same mesh each time.
inline std::string serial_option() { return METRICA_SPECULATIVE_ONLY ? " --threads 1" : " --concurrency serial"; }

}  // namespace metrica::test
