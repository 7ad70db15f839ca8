// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/state_archive.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::engine {

void StateReader::take(void* to, std::size_t n) {
  if (data_.size() - pos_ < n) fail(fmt::format("truncated ({} bytes wanted)", n));
  if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not see
  std::memcpy(to, data_.data() + pos_, n);
  pos_ += n;
}

void StateReader::check_fits(std::int64_t n, std::size_t size) const {
  if (n < 0 || static_cast<std::uint64_t>(n) > (data_.size() - pos_) / size)
    fail(fmt::format("truncated (a vector of {} values)", n));
}

std::string StateReader::get_string() {
  const auto n = get<std::int64_t>();
  if (n < 0 || static_cast<std::uint64_t>(n) > data_.size() - pos_)
    fail(fmt::format("truncated (a text of {} bytes)", n));
  std::string s(static_cast<std::size_t>(n), '\0');
  take(s.data(), s.size());
  return s;
}

void StateReader::expect_tag(std::string_view part) {
  const auto at = pos_;
  std::string found;
  try {
    found = get_string();
  } catch (const std::runtime_error&) {
    pos_ = at;
    fail(fmt::format("expected the state of the {}, found none", part));
  }
  if (found != part) {
    pos_ = at;
    fail(fmt::format("expected the state of the {}, found \"{}\"", part, found.substr(0, 40)));
  }
}

void StateReader::expect_end() const {
  if (pos_ != data_.size()) fail(fmt::format("{} bytes beyond the data", data_.size() - pos_));
}

void StateReader::fail(std::string_view what) const {
  throw CheckpointError(fmt::format("checkpoint {}, byte {}: {}", source_, pos_, what));
}

}  // namespace auvloop::engine
