// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/grid_binary_io.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "auvloop/geometry/file_io.hpp"

namespace auvloop::mesher {

static_assert(std::endian::native == std::endian::little,
              "the .agrid writer stores native little-endian values");

namespace {
constexpr char kMagic[8] = {'A', 'U', 'V', 'L', 'G', 'R', 'I', 'D'};
constexpr char kEnd[8] = {'G', 'R', 'I', 'D', 'E', 'N', 'D', '!'};
constexpr std::uint32_t kByteOrder = 0x01020304;

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    out_.append(p, sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(static_cast<std::int64_t>(v.size()));
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(static_cast<std::int64_t>(s.size()));
    out_ += s;
  }
  void raw(const char (&bytes)[8]) { out_.append(bytes, 8); }
  [[nodiscard]] const std::string& data() const { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(std::string data, std::filesystem::path file)
      : in_(std::move(data)), file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error(
        fmt::format("{}: not a readable .agrid file: {}", file_.string(), why));
  }
  void need(std::size_t n) const {
    if (in_.size() - pos_ < n) fail(fmt::format("truncated at byte {}", pos_));
  }
  template <class T>
  T value() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::int64_t count() {
    const auto n = value<std::int64_t>();
    if (n < 0 || static_cast<std::uint64_t>(n) > in_.size()) fail(fmt::format("bad count {}", n));
    return n;
  }
  template <class T>
  std::vector<T> array() {
    const auto n = static_cast<std::size_t>(count());
    need(n * sizeof(T));
    std::vector<T> v(n);
    std::memcpy(v.data(), in_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  std::string text() {
    const auto n = static_cast<std::size_t>(count());
    need(n);
    std::string s = in_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  void expect(const char (&bytes)[8], const char* what) {
    if (in_.size() - pos_ < 8 || std::memcmp(in_.data() + pos_, bytes, 8) != 0) fail(what);
    pos_ += 8;
  }
  [[nodiscard]] bool at_end() const { return pos_ == in_.size(); }

 private:
  std::string in_;
  std::filesystem::path file_;
  std::size_t pos_ = 0;
};
}  // namespace

void write_grid_binary(const std::filesystem::path& file, const Grid& g) {
  Writer w;
  w.raw(kMagic);
  w.value(kGridFormatVersion);
  w.value(kByteOrder);
  w.text(g.name);
  const Eigen::Matrix4d m = g.placement.matrix();
  for (int k = 0; k < 16; ++k) w.value(m.data()[k]);
  std::vector<double> xyz;
  xyz.reserve(3 * g.points.size());
  for (const auto& p : g.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  w.array(xyz);
  w.array(g.face_offsets);
  w.array(g.face_points);
  w.array(g.owner);
  w.array(g.neighbour);
  w.value(static_cast<std::int64_t>(g.cells));
  w.value(static_cast<std::int64_t>(g.patches.size()));
  for (const auto& p : g.patches) {
    w.text(p.name);
    w.value(static_cast<std::int32_t>(p.type));
    w.value(static_cast<std::int32_t>(p.start));
    w.value(static_cast<std::int32_t>(p.size));
    w.value(static_cast<std::int32_t>(p.neighbour_patch));
  }
  w.value(static_cast<std::int64_t>(g.zones.size()));
  for (const auto& z : g.zones) {
    w.text(z.name);
    w.array(z.cells);
  }
  w.raw(kEnd);
  write_file_atomically(file, w.data());
}

Grid read_grid_binary(const std::filesystem::path& file) {
  Reader r(read_file_text(file), file);
  r.expect(kMagic, "missing the AUVLGRID header");
  const auto version = r.value<std::uint32_t>();
  if (version != kGridFormatVersion) {
    r.fail(fmt::format("format version {} (this build reads version {})", version,
                       kGridFormatVersion));
  }
  if (r.value<std::uint32_t>() != kByteOrder) r.fail("written with another byte order");
  Grid g;
  g.name = r.text();
  Eigen::Matrix4d m;
  for (int k = 0; k < 16; ++k) m.data()[k] = r.value<double>();
  g.placement.matrix() = m;
  const auto xyz = r.array<double>();
  if (xyz.size() % 3 != 0) r.fail("point array is not a multiple of 3");
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    g.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  g.face_offsets = r.array<int>();
  g.face_points = r.array<int>();
  g.owner = r.array<int>();
  g.neighbour = r.array<int>();
  g.cells = static_cast<int>(r.value<std::int64_t>());
  const auto patches = r.count();
  for (std::int64_t i = 0; i < patches; ++i) {
    Patch p;
    p.name = r.text();
    const auto type = r.value<std::int32_t>();
    if (type < 0 || type > static_cast<std::int32_t>(PatchType::overset))
      r.fail(fmt::format("patch {} has unknown type {}", p.name, type));
    p.type = static_cast<PatchType>(type);
    p.start = r.value<std::int32_t>();
    p.size = r.value<std::int32_t>();
    p.neighbour_patch = r.value<std::int32_t>();
    g.patches.push_back(p);
  }
  const auto zones = r.count();
  for (std::int64_t i = 0; i < zones; ++i) {
    Zone z;
    z.name = r.text();
    z.cells = r.array<int>();
    g.zones.push_back(std::move(z));
  }
  r.expect(kEnd, "missing the closing GRIDEND! marker");
  if (!r.at_end()) r.fail("trailing bytes after the grid");
  // Cheap structural checks, so a damaged file cannot index out of bounds downstream.
  if (g.face_offsets.size() != g.owner.size() + 1 ||
      g.face_offsets.back() != static_cast<int>(g.face_points.size()))
    r.fail("face arrays do not match");
  for (int p : g.face_points)
    if (p < 0 || p >= static_cast<int>(g.points.size())) r.fail("face point index out of range");
  return g;
}

}  // namespace auvloop::mesher
