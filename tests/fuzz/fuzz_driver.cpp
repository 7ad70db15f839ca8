// SPDX-License-Identifier: GPL-3.0-or-later
// A stand-in for libFuzzer's driver where it is not available (GCC): mutates seed inputs at random
// (byte flips, insertions, deletions, duplications, splices, dictionary tokens) and runs the fuzz
// target on each for a time budget. No coverage feedback, so it finds less than libFuzzer; it is
// deterministic for a given --seed, and it runs in CI under AddressSanitizer and UBSan.
//   fuzz_driver --seconds 20 --seed 1 [--keep-input FILE] [--crash-file FILE] SEED_FILE...
// A fatal signal saves the input that caused it to the crash file (default fuzz-crash.bin).
// --keep-input writes each input to FILE before running it, so a crash leaves its input behind.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {
// The input being run, for the fatal-signal handler to save (async-signal-safe calls only).
const char* g_input = nullptr;
std::size_t g_input_size = 0;
const char* g_crash_file = "fuzz-crash.bin";

void save_input_and_die(int sig) {
  const int fd = open(g_crash_file, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd >= 0) {
    [[maybe_unused]] const auto n = write(fd, g_input, g_input_size);
    close(fd);
  }
  const char msg[] = "fuzz_driver: fatal signal; the input is saved in the crash file\n";
  [[maybe_unused]] const auto m = write(2, msg, sizeof msg - 1);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void run(const std::string& input) {
  g_input = input.data();
  g_input_size = input.size();
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

const std::vector<std::string> kDictionary{
    "[",          "]",    "[[",        "]]",        "=",         "\"",   "'",          "\n",
    ",",          "{",    "}",         "inf",       "nan",       "-0",   "1e309",      "-1e309",
    "0x7fffffff", "true", "\"\"\"",    "#",         ".",         "name", "vehicle",    "preset:",
    "../",        "time", "dt",        "duration",  "manoeuvre", "type", "controller", "kp",
    "problem",    "case", "parameter", "optimizer", "\xff",      "\x00"};

std::string mutate(std::string s, const std::vector<std::string>& seeds, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  const int edits = 1 + static_cast<int>(rng() % 8);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!s.empty()) s[pick(s.size())] ^= static_cast<char>(1U << (rng() % 8));
        break;
      case 1:
        s.insert(at, 1, static_cast<char>(rng() % 256));
        break;
      case 2:
        s.erase(at, pick(16) + 1);
        break;
      case 3:
        if (!s.empty()) s.insert(at, s.substr(pick(s.size()), pick(64) + 1));
        break;
      case 4: {
        const std::string& other = seeds[pick(seeds.size())];
        s = s.substr(0, at) + other.substr(pick(other.size() + 1));
        break;
      }
      default:
        s.insert(at, kDictionary[pick(kDictionary.size())]);
    }
  }
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  double seconds = 10;
  std::uint64_t seed = 1;
  std::vector<std::string> seeds;
  std::string keep;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (a == "--crash-file" && i + 1 < argc) {
      g_crash_file = argv[++i];
    } else if (a == "--keep-input" && i + 1 < argc) {
      keep = argv[++i];
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::ifstream in(a, std::ios::binary);
      std::stringstream ss;
      ss << in.rdbuf();
      seeds.push_back(ss.str());
    }
  }
  if (seeds.empty()) seeds.emplace_back();
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, save_input_and_die);
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  long runs = 0;
  for (const auto& s : seeds) {
    run(s);
    ++runs;
  }
  std::string current = seeds[0];
  while (std::chrono::steady_clock::now() < end) {
    current = (rng() % 4 == 0) ? seeds[rng() % seeds.size()] : current;
    current = mutate(current, seeds, rng);
    if (current.size() > (1U << 16)) current.resize(1U << 16);
    if (!keep.empty()) std::ofstream(keep, std::ios::binary | std::ios::trunc) << current;
    run(current);
    ++runs;
  }
  std::printf("fuzz_driver: %ld inputs in %.0f s (seed %llu), no failure\n", runs, seconds,
              static_cast<unsigned long long>(seed));
  return 0;
}
