// SPDX-License-Identifier: GPL-3.0-or-later
// The native binary grid format (.agrid): fast to write and read, exact (doubles as stored).
//
// Layout, little-endian: magic "AUVLGRID", uint32 format version (kGridFormatVersion), uint32
// 0x01020304 (byte-order check), then the grid: name, placement (4x4 doubles, column-major),
// points, face offsets and points, owner, neighbour, cell count, patches, zones, and the closing
// magic "GRIDEND!". Counts are int64, indices int32, strings an int64 length and the bytes.
// Readers reject other versions, byte orders and truncated files with a message naming the file.
#pragma once

#include <cstdint>
#include <filesystem>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

inline constexpr std::uint32_t kGridFormatVersion = 1;

void write_grid_binary(const std::filesystem::path& file, const Grid& g);  // atomic
Grid read_grid_binary(const std::filesystem::path& file);  // throws std::runtime_error

}  // namespace auvloop::mesher
