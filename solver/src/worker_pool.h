// SPDX-License-Identifier: MIT
// Worker threads for the parts of a step whose work splits into independent tasks.
//
// A task is a fixed block of bodies (or one axis), never a share of the threads: which task
// computes what does not depend on how many threads run them, and each task writes only its own
// outputs, which the caller combines in task order. So every thread count gives the same bits.
// The workers are started once, with the world, and a run allocates nothing.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace chain::detail {

class WorkerPool {
 public:
  // `threads` counts the calling thread: 1 starts no worker and runs every task on the caller.
  explicit WorkerPool(int threads = 1);
  // A copy starts workers of its own, as many.
  WorkerPool(const WorkerPool& other) : WorkerPool(other.threads()) {}
  WorkerPool& operator=(const WorkerPool& other);
  ~WorkerPool();

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  // Stops the workers and starts `threads` - 1 anew, unless there are as many already.
  void reset(int threads);

  // Calls fn(k) once for every k in [0, tasks), on the caller and the workers, and returns when
  // every call has returned. The calls may run in any order and at once: each must touch only
  // what is its own.
  template <class Fn>
  void run(std::uint32_t tasks, Fn&& fn) {
    if (workers_.empty() || tasks <= 1) {
      for (std::uint32_t k = 0; k < tasks; ++k)
        fn(k);
      return;
    }
    auto call = [](void* arg, std::uint32_t k) {
      (*static_cast<std::remove_reference_t<Fn>*>(arg))(k);
    };
    run_tasks(tasks, call, &fn);
  }

 private:
  using Call = void (*)(void* arg, std::uint32_t task);
  struct Shared {
    std::mutex mutex;
    std::condition_variable start, done;
    std::uint64_t generation = 0;  // runs started; a worker joins each once
    bool stop = false;
    Call call = nullptr;
    void* arg = nullptr;
    std::uint32_t tasks = 0;
    std::uint32_t next = 0;      // the next task to claim
    std::uint32_t finished = 0;  // tasks returned
  };
  void run_tasks(std::uint32_t tasks, Call call, void* arg);
  // Claims and runs tasks of the current run until none is left; call with the lock held.
  static void drain(Shared& s, std::unique_lock<std::mutex>& lock);
  static void work(Shared* s);
  void start(int threads);
  void join();

  std::unique_ptr<Shared> shared_;
  std::vector<std::thread> workers_;
};

}  // namespace chain::detail
