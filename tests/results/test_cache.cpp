// SPDX-License-Identifier: GPL-3.0-or-later
// The result cache: a stored run is found by its content hash; tampered, partial or mislabelled
// entries are reported as corrupt; keys can never be paths.
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/results/cache.hpp"
#include "temp_dir.hpp"

using namespace auvloop;
using results::ResultCache;
using ::testing::HasSubstr;

namespace {
results::RunReport report(double gain) {
  results::RunReport r;
  r.name = "cached";
  r.canonical_case = {{"kp", gain}};
  const auto t = r.series.add("t", "s");
  for (int k = 0; k < 3; ++k) r.series.push(t, 0.1 * k);
  r.metrics = {{"itae_deg_s2", 10 * gain}};
  r.plant = "derivative";
  return r;
}
}  // namespace

TEST(ResultCache, StoresAndFindsByContentHash) {
  test::TempDir tmp;
  const ResultCache cache(tmp.path() / "cache");
  const std::string key = cache.store(report(1.5));
  EXPECT_EQ(key, results::content_hash(report(1.5).canonical_case));
  const auto hit = cache.lookup(key);
  ASSERT_EQ(hit.state, ResultCache::State::valid) << hit.problem;
  EXPECT_EQ(hit.run->metrics["itae_deg_s2"], 15.0);
  EXPECT_EQ(cache.lookup(results::content_hash(report(1.6).canonical_case)).state,
            ResultCache::State::missing);
  cache.store(report(1.6));
  EXPECT_EQ(cache.keys().size(), 2U);
}

TEST(ResultCache, DetectsCorruptAndPartialEntries) {
  test::TempDir tmp;
  const ResultCache cache(tmp.path() / "cache");
  const std::string key = cache.store(report(2.0));
  std::ofstream(cache.path_of(key) / "timeseries.csv", std::ios::app) << "9,9\n";  // tampered
  auto r = cache.lookup(key);
  EXPECT_EQ(r.state, ResultCache::State::corrupt);
  EXPECT_THAT(r.problem, HasSubstr("timeseries.csv"));
  cache.remove(key);
  EXPECT_EQ(cache.lookup(key).state, ResultCache::State::missing);
  const std::string again = cache.store(report(2.0));  // recomputed
  std::filesystem::remove(cache.path_of(again) / "metrics.json");
  EXPECT_EQ(cache.lookup(again).state, ResultCache::State::corrupt);
}

TEST(ResultCache, KeysAreNeverPaths) {
  test::TempDir tmp;
  const ResultCache cache(tmp.path() / "cache");
  for (const std::string& bad :
       std::vector<std::string>{"../../etc/passwd", "ab/cd", std::string(64, 'g'),
                                std::string(63, 'a'), std::string(64, 'A')}) {
    EXPECT_THROW((void)cache.lookup(bad), std::invalid_argument) << bad;
  }
}
