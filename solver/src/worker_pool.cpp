// SPDX-License-Identifier: MIT
#include "worker_pool.h"

namespace chain::detail {

WorkerPool::WorkerPool(int threads) {
  start(threads);
}

WorkerPool& WorkerPool::operator=(const WorkerPool& other) {
  if (this != &other) reset(other.threads());
  return *this;
}

void WorkerPool::reset(int threads) {
  if (shared_ && threads == this->threads()) return;
  join();
  start(threads);
}

WorkerPool::~WorkerPool() {
  join();
}

void WorkerPool::start(int threads) {
  shared_ = std::make_unique<Shared>();
  workers_.reserve(threads > 1 ? static_cast<std::size_t>(threads - 1) : 0u);
  for (int t = 1; t < threads; ++t)
    workers_.emplace_back(&WorkerPool::work, shared_.get());
}

void WorkerPool::join() {
  if (!shared_) return;
  {
    const std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->stop = true;
  }
  shared_->start.notify_all();
  for (std::thread& t : workers_)
    t.join();
  workers_.clear();
  shared_.reset();
}

void WorkerPool::drain(Shared& s, std::unique_lock<std::mutex>& lock) {
  // Tasks are claimed under the lock but run outside it; a step has a few runs of a few dozen
  // tasks each, so the lock is never what a thread waits for long.
  while (s.next < s.tasks) {
    const std::uint32_t k = s.next++;
    const Call call = s.call;
    void* const arg = s.arg;
    lock.unlock();
    call(arg, k);
    lock.lock();
    if (++s.finished == s.tasks) s.done.notify_all();
  }
}

void WorkerPool::run_tasks(std::uint32_t tasks, Call call, void* arg) {
  Shared& s = *shared_;
  std::unique_lock<std::mutex> lock(s.mutex);
  s.call = call;
  s.arg = arg;
  s.tasks = tasks;
  s.next = s.finished = 0;
  ++s.generation;
  s.start.notify_all();
  drain(s, lock);
  s.done.wait(lock, [&] { return s.finished == s.tasks; });
}

void WorkerPool::work(Shared* shared) {
  Shared& s = *shared;
  std::uint64_t seen = 0;
  std::unique_lock<std::mutex> lock(s.mutex);
  for (;;) {
    s.start.wait(lock, [&] { return s.stop || s.generation != seen; });
    if (s.stop) return;
    seen = s.generation;
    drain(s, lock);
  }
}

}  // namespace chain::detail
