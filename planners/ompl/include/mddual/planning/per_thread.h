// PerThread<T>: one T per (instance, thread), for the caches of the checkers'
// const methods (warm starts, FCL query objects). OMPL calls a validity
// checker from several threads at once; each thread gets its own T, so a T is
// only ever touched by the thread that owns it.
//
// Keys are per-instance ids drawn from a global counter, never `this`: a new
// checker created at the address of a destroyed one must not inherit its
// caches. Each thread keeps its most recently used kSlots instances (least
// recently used evicted), so a thread that outlives many checkers holds a
// bounded amount of memory. local() hands out a shared_ptr: a caller holding
// it keeps its T alive even if a nested call evicts the slot.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace mddual::planning {

namespace detail {
/// Process-wide source of instance ids (never reused).
inline std::uint64_t nextInstanceId() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace detail

template <typename T>
class PerThread {
 public:
  /// Instances of this type a thread keeps before evicting the least recently
  /// used. An arm's FCL baseline queries one FclScene per checked link pair
  /// (FclArmScene: 50 on arm7) in turn, and with 8 slots rebuilt a private
  /// copy of a link's mesh hierarchy at nearly every query.
  static constexpr std::size_t kSlots = 128;

  PerThread() : id_(detail::nextInstanceId()) {}
  PerThread(const PerThread&) = delete;
  PerThread& operator=(const PerThread&) = delete;

  /// This thread's T for this instance; `make()` (returning std::shared_ptr<T>)
  /// creates it on the thread's first call.
  template <typename Make>
  std::shared_ptr<T> local(Make&& make) const {
    thread_local std::vector<std::pair<std::uint64_t, std::shared_ptr<T>>> slots;
    for (std::size_t i = 0; i < slots.size(); ++i) {
      if (slots[i].first != id_) continue;
      if (i != 0)
        std::rotate(slots.begin(), slots.begin() + static_cast<std::ptrdiff_t>(i),
                    slots.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      return slots.front().second;
    }
    std::shared_ptr<T> created = make();
    if (slots.size() == kSlots) slots.pop_back();
    slots.insert(slots.begin(), {id_, created});
    return created;
  }

  std::uint64_t id() const { return id_; }

 private:
  std::uint64_t id_;
};

}  // namespace mddual::planning
