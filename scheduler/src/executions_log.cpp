// SPDX-License-Identifier: GPL-3.0-or-later
#include "executions_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>

#include <fmt/format.h>

namespace auvloop::scheduler {

void append_execution(const std::filesystem::path& log, const std::string& key,
                      const std::string& name, double wall_s) {
  if (log.empty()) return;
  const std::string line = fmt::format("{} {} {:.6f}\n", key, name, wall_s);
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
  if (fd < 0) return;
  [[maybe_unused]] const auto n = write(fd, line.data(), line.size());
  close(fd);
}

bool execution_logged(const std::filesystem::path& log, const std::string& key) {
  std::ifstream in(log);
  for (std::string k, rest; in >> k && std::getline(in, rest);)
    if (k == key) return true;
  return false;
}

}  // namespace auvloop::scheduler
