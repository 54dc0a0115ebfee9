// The visited-key set of the searches over M (search.cpp, penetration_rays.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mddual::detail {

/// Open-addressing hash set of 64-bit keys (faces or facets of M) for the
/// searches' visited sets: a std::unordered_set allocates a node per insert,
/// which dominated the searches. Reused across queries of one thread: clear()
/// is O(1) by a generation stamp.
class KeySet {
 public:
  /// `min_capacity`: slots allocated at the first insert (a power of two).
  explicit KeySet(std::size_t min_capacity = 64) : min_capacity_(min_capacity) {}

  void clear() {
    if (++generation_ == 0) {
      std::fill(stamps_.begin(), stamps_.end(), 0u);
      generation_ = 1;
    }
    size_ = 0;
  }
  /// Inserts key; true when it was not there yet.
  bool insert(std::uint64_t key) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
      if (stamps_[i] != generation_) {
        stamps_[i] = generation_;
        keys_[i] = key;
        ++size_;
        return true;
      }
      if (keys_[i] == key) return false;
    }
  }

 private:
  static std::size_t mix(std::uint64_t x) {  // splitmix64 finaliser
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return static_cast<std::size_t>(x);
  }
  void grow() {
    std::vector<std::uint64_t> old_keys;
    std::vector<std::uint32_t> old_stamps;
    old_keys.swap(keys_);
    old_stamps.swap(stamps_);
    const std::size_t capacity = std::max(min_capacity_, 2 * old_keys.size());
    keys_.assign(capacity, 0);
    stamps_.assign(capacity, 0);
    const std::uint32_t live = generation_;
    size_ = 0;
    for (std::size_t i = 0; i < old_keys.size(); ++i) {
      if (old_stamps[i] == live) insert(old_keys[i]);
    }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> stamps_;
  std::uint32_t generation_ = 1;
  std::size_t size_ = 0;
  std::size_t min_capacity_;
};

}  // namespace mddual::detail
