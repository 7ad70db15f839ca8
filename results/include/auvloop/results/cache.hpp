// SPDX-License-Identifier: GPL-3.0-or-later
// The content-addressed result cache: one run directory per content hash (SHA-256 of the
// canonical case and the engine version), under ROOT/ab/abcdef.../. Entries are written like any
// run directory (assembled under a scratch name, renamed into place) and verified on lookup
// against the SHA-256 checksums in their manifest, so a corrupted or partial entry is reported
// and can be recomputed instead of being served.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "auvloop/results/run_directory.hpp"

namespace auvloop::results {

class ResultCache {
 public:
  explicit ResultCache(std::filesystem::path root);

  enum class State { missing, valid, corrupt };
  struct Lookup {
    State state = State::missing;
    std::optional<StoredRun> run;  // when valid
    std::string problem;           // when corrupt: what is wrong
  };

  // Throws std::invalid_argument unless `key` is 64 lower-case hex digits (never a path).
  [[nodiscard]] Lookup lookup(const std::string& key) const;
  // Stores a run under its content hash; returns the key.
  std::string store(const RunReport& report, WriteOptions options = {}) const;
  // Removes an entry (e.g. a corrupt one before recomputing it).
  void remove(const std::string& key) const;
  [[nodiscard]] std::vector<std::string> keys() const;
  [[nodiscard]] std::filesystem::path path_of(const std::string& key) const;

 private:
  std::filesystem::path root_;
};

}  // namespace auvloop::results
