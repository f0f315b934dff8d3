#include "core/thread_pool.h"

#include <algorithm>

namespace radfarm {

ThreadPool::ThreadPool(unsigned threads) : size_(threads != 0 ? threads : MachineThreads()) {
  try {
    for (unsigned w = 1; w < size_; ++w) threads_.emplace_back([this, w] { WorkerLoop(w); });
  } catch (...) {
    // The system refused a thread: the ones started must be joined before the exception leaves,
    // or their std::thread destructors terminate the process.
    Stop();
    throw;
  }
}

unsigned MachineThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

ThreadPool::~ThreadPool() { Stop(); }

void ThreadPool::Stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void ThreadPool::RunShare(unsigned worker) {
  std::unique_lock lock(mutex_);
  while (next_ < count_) {
    const size_t index = next_++;
    lock.unlock();
    try {
      (*body_)(worker, index);
    } catch (...) {
      lock.lock();
      if (!error_) error_ = std::current_exception();
      next_ = count_;  // stop handing out work
      continue;
    }
    lock.lock();
  }
}

void ThreadPool::WorkerLoop(unsigned worker) {
  uint64_t seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
    if (stopping_) return;
    seen = generation_;
    ++busy_;
    lock.unlock();
    RunShare(worker);
    lock.lock();
    if (--busy_ == 0) done_.notify_all();
  }
}

void ParallelForOrInline(ThreadPool* pool, size_t count,
                         const std::function<void(unsigned worker, size_t index)>& body) {
  if (pool != nullptr) {
    pool->ParallelFor(count, body);
    return;
  }
  for (size_t i = 0; i < count; ++i) body(0, i);
}

unsigned WorkersOf(const ThreadPool* pool) { return pool != nullptr ? pool->size() : 1; }

void ThreadPool::ParallelFor(size_t count,
                             const std::function<void(unsigned worker, size_t index)>& body) {
  {
    std::lock_guard lock(mutex_);
    body_ = &body;
    count_ = count;
    next_ = 0;
    error_ = nullptr;
    ++generation_;
  }
  wake_.notify_all();
  RunShare(0);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  body_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

}  // namespace radfarm
