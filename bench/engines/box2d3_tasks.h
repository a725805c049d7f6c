// SPDX-License-Identifier: MIT
// The box2d3 adapter's task system: what Box2D v3 calls through b2WorldDef's enqueueTask and
// finishTask when it is given more than one worker. A fixed pool of threads - 1 std::threads plus
// the calling thread runs parallel-for tasks; the results depend only on Box2D, which partitions
// its work so that its answer is the same for any worker count.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace chainbench {

// b2TaskCallback's signature: run items [begin, end) as worker `worker` (< threads).
using TaskFunction = void(int begin, int end, std::uint32_t worker, void* context);

class TaskPool {
 public:
  // `threads` >= 1 workers in all, the calling thread being worker 0.
  explicit TaskPool(int threads);
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  int threads() const { return threads_; }
  // Starts `count` items in chunks of at least `min_range` (but the last); returns the task to
  // finish. Called from the thread that created the pool only, as Box2D does.
  void* enqueue(TaskFunction* fn, int count, int min_range, void* context);
  // Returns once every chunk of `task` has run; the caller runs chunks meanwhile.
  void finish(void* task);

  // The adapters' callbacks for b2WorldDef (user context: the pool).
  static void* enqueue_callback(TaskFunction* fn, int count, int min_range, void* context,
                                void* pool);
  static void finish_callback(void* task, void* pool);

 private:
  struct Task {
    TaskFunction* fn = nullptr;
    void* context = nullptr;
    int count = 0;
    int chunks = 0;
    int next = 0;              // the next chunk to claim (under the mutex)
    std::atomic<int> done{0};  // chunks run
  };

  // Claims a chunk of `only` (or of the oldest task with one left, when null): its task and index,
  // or {nullptr, 0}.
  std::pair<Task*, int> claim(Task* only);
  void run(Task& task, int chunk, std::uint32_t worker);
  void work(std::uint32_t worker);

  int threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Task*> open_;  // tasks with unclaimed chunks, oldest first
  std::vector<std::unique_ptr<Task>> owned_;
  std::vector<Task*> free_;  // finished tasks, to reuse
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace chainbench
