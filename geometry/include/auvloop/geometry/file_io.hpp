// SPDX-License-Identifier: GPL-3.0-or-later
// Whole-file reads and atomic writes. A write goes to a temporary file in the same directory,
// then is renamed over the target (atomic on POSIX file systems), so readers never see a partial
// file. (Input files that users write are read through input::read_file, whose errors carry
// file:line for the command line.)
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace auvloop {

// Throws std::runtime_error naming the file when it cannot be read.
std::string read_file_text(const std::filesystem::path& path);

// Throws std::runtime_error naming the file when it cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace auvloop
