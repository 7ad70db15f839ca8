// SPDX-License-Identifier: GPL-3.0-or-later
// Exact state for checkpoints (the closed loop's and the flow's): values as they are in memory
// (IEEE doubles, the machine's byte order), so that a restored run continues bitwise. A record is
// a sequence of put() calls read back by the same sequence of get() calls; tag() marks the start
// of a part (a plant, the sensors, ...) so that a reader meeting another part, or a file written
// by another build, fails naming the part and the byte instead of reading garbage.
// Invariants: a StateReader never reads past its data (std::runtime_error naming the source and
// the byte); vectors and strings carry their length unless read with raw() into a sized buffer.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace auvloop::engine {

// What StateReader throws: a record that is not what the reader expects (truncated, another
// part, another grid or version).
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class StateWriter {
 public:
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void put(const T& v) { bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T)); }
  template <class Derived>
  requires(Derived::SizeAtCompileTime > 0) void put(const Eigen::MatrixBase<Derived>& m) {
    const typename Derived::PlainObject plain = m;
    bytes_.append(reinterpret_cast<const char*>(plain.data()),
                  sizeof(typename Derived::Scalar) * static_cast<std::size_t>(plain.size()));
  }
  void put(const Eigen::Quaterniond& q) { put(q.coeffs()); }
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void put(const std::vector<T>& v) {  // with its length
    put(static_cast<std::int64_t>(v.size()));
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(std::string_view s) {
    put(static_cast<std::int64_t>(s.size()));
    bytes_.append(s);
  }
  void raw(const std::vector<double>& v) {  // without its length
    if (!v.empty())
      bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
  void tag(std::string_view part) { put(part); }
  [[nodiscard]] const std::string& bytes() const { return bytes_; }
  [[nodiscard]] std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class StateReader {
 public:
  // `source` names the data in errors (a file name).
  StateReader(std::string data, std::string source)
      : data_(std::move(data)), source_(std::move(source)) {}
  template <class T>
  requires std::is_trivially_copyable_v<T> T get() {
    T v;
    take(&v, sizeof(T));
    return v;
  }
  template <class Derived>
  requires(Derived::SizeAtCompileTime > 0) void get(Eigen::MatrixBase<Derived>& m) {
    typename Derived::PlainObject plain;
    take(plain.data(), sizeof(typename Derived::Scalar) * static_cast<std::size_t>(plain.size()));
    m = plain;
  }
  void get(Eigen::Quaterniond& q) { get(q.coeffs()); }
  template <class T = double>
  requires std::is_trivially_copyable_v<T> std::vector<T> get_vector() {
    const auto n = get<std::int64_t>();
    check_fits(n, sizeof(T));
    std::vector<T> v(static_cast<std::size_t>(n));
    take(v.data(), v.size() * sizeof(T));
    return v;
  }
  std::string get_string();
  void raw(std::vector<double>& v) { take(v.data(), v.size() * sizeof(double)); }  // v sized
  // Throws unless the next part is `part`.
  void expect_tag(std::string_view part);
  // Throws unless every byte was read.
  void expect_end() const;
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] std::size_t position() const { return pos_; }
  // Throws CheckpointError "checkpoint SOURCE, byte N: what".
  [[noreturn]] void fail(std::string_view what) const;

 private:
  void take(void* to, std::size_t n);
  void check_fits(std::int64_t n, std::size_t size) const;  // n values of `size` bytes left
  std::string data_, source_;
  std::size_t pos_ = 0;
};

}  // namespace auvloop::engine
