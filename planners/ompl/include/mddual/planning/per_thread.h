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
#include <unordered_map>
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
    // A hash lookup, not a scan of a recency list: an arm's FCL baseline
    // looks up one of ~50 instances per pair query, and moving the list's
    // entries was 8% of its state checks (perf, mddual_bench_arm_edges).
    struct Slot {
      std::shared_ptr<T> value;
      std::uint64_t used = 0;
    };
    thread_local std::unordered_map<std::uint64_t, Slot> slots;
    thread_local std::uint64_t clock = 0;
    const auto found = slots.find(id_);
    if (found != slots.end()) {
      found->second.used = ++clock;
      return found->second.value;
    }
    std::shared_ptr<T> created = make();
    if (slots.size() >= kSlots) {
      const auto oldest = std::min_element(slots.begin(), slots.end(),
                                           [](const auto& x, const auto& y) { return x.second.used < y.second.used; });
      slots.erase(oldest);
    }
    slots.emplace(id_, Slot{created, ++clock});
    return created;
  }
  std::uint64_t id() const { return id_; }

 private:
  std::uint64_t id_;
};

}  // namespace mddual::planning
