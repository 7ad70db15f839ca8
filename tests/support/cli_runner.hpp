// SPDX-License-Identifier: GPL-3.0-or-later
// Runs the auvloop program as a user would, capturing its output and exit code.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace auvloop::test {

struct CliResult {
  int exit_code;
  std::string output;  // stdout and stderr together
};

inline CliResult run_cli(const std::string& args) {
  FILE* pipe = popen((std::string(AUVLOOP_CLI) + " " + args + " 2>&1").c_str(), "r");
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) out += buffer.data();
  return {WEXITSTATUS(pclose(pipe)), out};
}

}  // namespace auvloop::test
