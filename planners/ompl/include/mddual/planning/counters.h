// CheckerCounters: what a checker did, counted from any number of threads at
// once (relaxed atomics: each total is exact once the threads are done; a read
// during checks sees some recent value of each counter).
#pragma once

#include <ompl/base/MotionValidator.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>

namespace mddual::planning {

/// A snapshot of CheckerCounters.
struct CheckerCounts {
  std::uint64_t state_checks = 0;   ///< isValid() calls
  std::uint64_t motion_checks = 0;  ///< checkMotion() calls (both overloads)
  std::uint64_t pair_queries = 0;   ///< narrow-phase queries on a (robot piece, world piece) pair
  std::uint64_t sub_edges = 0;      ///< rotating-edge sub-edges swept (MDD motion validator)
  /// Time inside the checker's methods, summed over threads (0 when timing is
  /// off). A call made inside another checker's timed call (the state checks
  /// of a motion validator) is the outer call's time only: the counts of
  /// several checkers add up without counting a nested call twice.
  double seconds = 0.0;
};

/// Thread-safe counters; the checkers own one each.
class CheckerCounters {
 public:
  void addStateCheck() { state_checks_.fetch_add(1, std::memory_order_relaxed); }
  void addMotionCheck() { motion_checks_.fetch_add(1, std::memory_order_relaxed); }
  void addPairQueries(std::uint64_t n) { pair_queries_.fetch_add(n, std::memory_order_relaxed); }
  void addSubEdges(std::uint64_t n) { sub_edges_.fetch_add(n, std::memory_order_relaxed); }
  void addNanoseconds(std::uint64_t n) { nanoseconds_.fetch_add(n, std::memory_order_relaxed); }

  CheckerCounts read() const {
    CheckerCounts c;
    c.state_checks = state_checks_.load(std::memory_order_relaxed);
    c.motion_checks = motion_checks_.load(std::memory_order_relaxed);
    c.pair_queries = pair_queries_.load(std::memory_order_relaxed);
    c.sub_edges = sub_edges_.load(std::memory_order_relaxed);
    c.seconds = static_cast<double>(nanoseconds_.load(std::memory_order_relaxed)) * 1e-9;
    return c;
  }
  /// Timing costs two clock reads per call (about 40 ns): on by default, off
  /// for benchmarks that time the checkers from outside.
  void setTiming(bool on) { timing_.store(on, std::memory_order_relaxed); }
  bool timing() const { return timing_.load(std::memory_order_relaxed); }

  void reset() {
    state_checks_.store(0, std::memory_order_relaxed);
    motion_checks_.store(0, std::memory_order_relaxed);
    pair_queries_.store(0, std::memory_order_relaxed);
    sub_edges_.store(0, std::memory_order_relaxed);
    nanoseconds_.store(0, std::memory_order_relaxed);
  }

  /// Adds the time from construction to destruction to `counters`, unless
  /// another timing Timer is alive on this thread (the outer one counts it).
  /// A scope: constructed and destroyed on the same thread.
  class Timer {
   public:
    explicit Timer(CheckerCounters& counters)
        : counters_(counters), depth_(counters.timing() ? depth()++ : -1), on_(depth_ == 0) {
      if (on_) start_ = std::chrono::steady_clock::now();
    }
    ~Timer() {
      if (depth_ >= 0) --depth();
      if (!on_) return;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_);
      counters_.addNanoseconds(static_cast<std::uint64_t>(ns.count()));
    }
    Timer(const Timer&) = delete;
    Timer& operator=(const Timer&) = delete;

   private:
    static int& depth() {
      thread_local int d = 0;
      return d;
    }
    CheckerCounters& counters_;
    int depth_;  ///< timing Timers alive on this thread before this one (-1: timing off)
    bool on_;
    std::chrono::steady_clock::time_point start_;
  };

 private:
  std::atomic<std::uint64_t> state_checks_{0};
  std::atomic<std::uint64_t> motion_checks_{0};
  std::atomic<std::uint64_t> pair_queries_{0};
  std::atomic<std::uint64_t> sub_edges_{0};
  std::atomic<std::uint64_t> nanoseconds_{0};
  std::atomic<bool> timing_{true};
};

/// The base of our motion validators: our CheckerCounters, and OMPL's own
/// valid/invalid motion counts (plain members of ompl::base::MotionValidator)
/// updated under a mutex, since OMPL may call checkMotion from several
/// threads.
class CountedMotionValidator : public ompl::base::MotionValidator {
 public:
  using ompl::base::MotionValidator::MotionValidator;
  CheckerCounts counts() const { return counters_.read(); }
  void resetCounts() { counters_.reset(); }
  /// Whether counts().seconds is measured (see CheckerCounters::setTiming).
  void setTiming(bool on) { counters_.setTiming(on); }

 protected:
  /// Counts one checkMotion result in OMPL's counters.
  void countOmpl(bool valid) const {
    std::lock_guard<std::mutex> lock(ompl_counters_mutex_);
    if (valid) {
      ++valid_;
    } else {
      ++invalid_;
    }
  }
  mutable CheckerCounters counters_;

 private:
  mutable std::mutex ompl_counters_mutex_;
};

}  // namespace mddual::planning
