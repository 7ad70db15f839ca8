// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/results/cache.hpp"

#include "auvloop/geometry/file_io.hpp"

#include <stdexcept>

namespace auvloop::results {
namespace fs = std::filesystem;

namespace {
bool valid_key(const std::string& key) {
  return key.size() == 64 && key.find_first_not_of("0123456789abcdef") == std::string::npos;
}

}  // namespace

ResultCache::ResultCache(fs::path root) : root_(std::move(root)) {
  fs::create_directories(root_);
}

fs::path ResultCache::path_of(const std::string& key) const {
  if (!valid_key(key)) {
    throw std::invalid_argument("result cache: \"" + key.substr(0, 80) +
                                "\" is not a content hash (64 hex digits)");
  }
  return root_ / key.substr(0, 2) / key;
}

ResultCache::Lookup ResultCache::lookup(const std::string& key) const {
  const fs::path dir = path_of(key);
  Lookup out;
  if (!fs::exists(dir)) return out;
  out.state = State::corrupt;
  StoredRun run;
  try {
    run = read_run_directory(dir);
  } catch (const std::exception& e) {
    out.problem = e.what();
    return out;
  }
  if (run.manifest.value("content_hash", "") != key) {
    out.problem = "the manifest's content hash does not match the entry's key";
    return out;
  }
  const auto& sums = run.manifest.value("checksums_sha256", nlohmann::json::object());
  for (const char* file : {"timeseries.csv", "metrics.json"}) {
    if (!sums.contains(file)) {
      out.problem = std::string("the manifest has no checksum for ") + file;
      return out;
    }
    if (!fs::exists(dir / file) ||
        sha256_hex(read_file_text(dir / file)) != sums[file].get<std::string>()) {
      out.problem = std::string(file) + " is missing or does not match its checksum";
      return out;
    }
  }
  out.state = State::valid;
  out.run = std::move(run);
  return out;
}

std::string ResultCache::store(const RunReport& report, WriteOptions options) const {
  const std::string key = content_hash(report.canonical_case);
  fs::create_directories(path_of(key).parent_path());
  write_run_directory(path_of(key), report, options);
  return key;
}

void ResultCache::remove(const std::string& key) const {
  fs::remove_all(path_of(key));
}

std::vector<std::string> ResultCache::keys() const {
  std::vector<std::string> out;
  for (const auto& shard : fs::directory_iterator(root_)) {
    if (!shard.is_directory()) continue;
    for (const auto& entry : fs::directory_iterator(shard.path())) {
      const std::string name = entry.path().filename().string();
      if (entry.is_directory() && valid_key(name)) out.push_back(name);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace auvloop::results
