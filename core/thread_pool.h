// ThreadPool: a fixed set of worker threads that run index-parallel loops. The caller's thread
// takes part too, so ParallelFor on a pool of one thread runs inline.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace radfarm {

class ThreadPool;

// body(worker, index) for every index in [0, count): on `pool`'s threads, or in order on the
// calling thread as worker 0 when `pool` is null (for callers whose pool is optional).
void ParallelForOrInline(ThreadPool* pool, size_t count,
                         const std::function<void(unsigned worker, size_t index)>& body);
// The workers ParallelForOrInline may name: pool->size(), or 1 without a pool.
unsigned WorkersOf(const ThreadPool* pool);

// One per core (at least 1): what `threads == 0` means.
unsigned MachineThreads();

class ThreadPool {
 public:
  // threads == 0 means one per core. Throws std::system_error when the system refuses a thread
  // (a process or memory limit), after joining the ones it started.
  explicit ThreadPool(unsigned threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return size_; }

  // Calls body(worker, index) for every index in [0, count), spread over the threads; `worker` is
  // in [0, size()) and unique to the calling thread during the loop. Returns when all calls are
  // done. Exceptions from body are rethrown here (the first one).
  void ParallelFor(size_t count, const std::function<void(unsigned worker, size_t index)>& body);

 private:
  void Stop();  // ends and joins the workers
  void WorkerLoop(unsigned worker);
  void RunShare(unsigned worker);

  unsigned size_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(unsigned, size_t)>* body_ = nullptr;
  size_t count_ = 0;
  size_t next_ = 0;
  unsigned busy_ = 0;
  uint64_t generation_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace radfarm
