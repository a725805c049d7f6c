// SPDX-License-Identifier: MIT
#include "engines/box2d3_tasks.h"

#include <algorithm>
#include <stdexcept>

namespace chainbench {

TaskPool::TaskPool(int threads) : threads_(threads) {
  if (threads < 1) throw std::invalid_argument("TaskPool: threads must be >= 1");
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int w = 1; w < threads; ++w)
    workers_.emplace_back([this, w] { work(static_cast<std::uint32_t>(w)); });
}

TaskPool::~TaskPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_)
    t.join();
}

void* TaskPool::enqueue(TaskFunction* fn, int count, int min_range, void* context) {
  if (count <= 0) return nullptr;  // nothing to run, nothing to finish
  // A few chunks per thread balance uneven items; never smaller than Box2D asks.
  const int most = std::max(1, count / std::max(1, min_range));
  const int chunks = std::min(most, 4 * threads_);
  Task* task = nullptr;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) {
      owned_.push_back(std::make_unique<Task>());
      free_.push_back(owned_.back().get());
    }
    task = free_.back();
    free_.pop_back();
    task->fn = fn;
    task->context = context;
    task->count = count;
    task->chunks = chunks;
    task->next = 0;
    task->done.store(0, std::memory_order_relaxed);
    open_.push_back(task);
  }
  if (chunks > 1) {
    wake_.notify_all();
  } else {
    wake_.notify_one();
  }
  return task;
}

std::pair<TaskPool::Task*, int> TaskPool::claim(Task* only) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Task* task = only;
  if (!task) {
    if (open_.empty()) return {nullptr, 0};
    task = open_.front();
  }
  if (task->next >= task->chunks) return {nullptr, 0};
  const int chunk = task->next++;
  if (task->next == task->chunks) open_.erase(std::find(open_.begin(), open_.end(), task));
  return {task, chunk};
}

void TaskPool::run(Task& task, int chunk, std::uint32_t worker) {
  const auto n = static_cast<long long>(task.count);
  const auto begin = static_cast<int>(n * chunk / task.chunks);
  const auto end = static_cast<int>(n * (chunk + 1) / task.chunks);
  task.fn(begin, end, worker, task.context);
  task.done.fetch_add(1, std::memory_order_release);  // the last touch: finish() may reuse it
}

void TaskPool::finish(void* handle) {
  Task* task = static_cast<Task*>(handle);
  for (;;) {
    if (auto [t, chunk] = claim(task); t) {
      run(*t, chunk, 0);
      continue;
    }
    if (task->done.load(std::memory_order_acquire) == task->chunks) break;
    // Its last chunks run elsewhere: help with any other task meanwhile. (Box2D's solver workers
    // wait for its worker 0, which is always enqueued, and so claimed, before them.)
    if (auto [t, chunk] = claim(nullptr); t) {
      run(*t, chunk, 0);
    } else {
      std::this_thread::yield();
    }
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  free_.push_back(task);
}

void TaskPool::work(std::uint32_t worker) {
  for (;;) {
    Task* task = nullptr;
    int chunk = 0;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !open_.empty(); });
      if (stop_) return;
      task = open_.front();
      chunk = task->next++;
      if (task->next == task->chunks) open_.erase(open_.begin());
    }
    run(*task, chunk, worker);
  }
}

void* TaskPool::enqueue_callback(TaskFunction* fn, int count, int min_range, void* context,
                                 void* pool) {
  return static_cast<TaskPool*>(pool)->enqueue(fn, count, min_range, context);
}

void TaskPool::finish_callback(void* task, void* pool) {
  static_cast<TaskPool*>(pool)->finish(task);
}

}  // namespace chainbench
