// SPDX-License-Identifier: GPL-3.0-or-later
// Writing files so that readers never see a partial one: a temporary file in the same directory,
// then a rename over the target (atomic on POSIX file systems).
#pragma once

#include <filesystem>
#include <string_view>

namespace auvloop {

// Throws std::runtime_error naming the file when it cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace auvloop
