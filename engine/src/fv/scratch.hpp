// SPDX-License-Identifier: GPL-3.0-or-later
// Reused work arrays, private to engine/src: Scratch<T> lends an array of n values from a
// process-wide pool and returns it on destruction, so an operator's temporaries (gradients,
// ranges, face values) cost no allocation once the pool holds arrays of the sizes in use. The
// values are left as they were (not initialised): the caller writes every entry it reads.
// Thread-safe; a lease of 0 values takes nothing from the pool.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace auvloop::engine::fv {

template <class T>
class Scratch {
 public:
  explicit Scratch(std::size_t n) : size_(n) {
    if (n == 0) return;
    {
      const std::lock_guard<std::mutex> lock(pool().mutex);
      auto& free = pool().free;
      // the smallest array that holds n values
      std::size_t pick = free.size();
      for (std::size_t i = 0; i < free.size(); ++i)
        if (free[i].capacity >= n &&
            (pick == free.size() || free[i].capacity < free[pick].capacity))
          pick = i;
      if (pick < free.size()) {
        block_ = std::move(free[pick]);
        free.erase(free.begin() + static_cast<std::ptrdiff_t>(pick));
      }
    }
    if (block_.capacity < n) block_ = {std::make_unique_for_overwrite<T[]>(n), n};
  }
  ~Scratch() {
    if (!block_.data) return;
    const std::lock_guard<std::mutex> lock(pool().mutex);
    pool().free.push_back(std::move(block_));
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  std::span<T> operator*() { return {block_.data.get(), size_}; }
  T& operator[](std::size_t i) { return block_.data[i]; }
  const T& operator[](std::size_t i) const { return block_.data[i]; }

 private:
  struct Block {
    std::unique_ptr<T[]> data;
    std::size_t capacity = 0;
  };
  struct Pool {
    std::mutex mutex;
    std::vector<Block> free;
  };
  static Pool& pool() {
    static Pool p;
    return p;
  }
  std::size_t size_;
  Block block_;
};

}  // namespace auvloop::engine::fv
