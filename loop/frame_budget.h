// FrameBudget: the bytes that frames still arriving may hold, shared by many connections (the
// master's agents). FrameSplitter charges a partial frame's buffer to it as the buffer grows and
// gives it all back when the frame completes or the connection goes; a growth the budget cannot
// cover fails that one stream. So peers that trickle big frames, however many, hold at most the
// budget between them, not their count times the frame limit.
//
// Loop thread only (every connection sharing it reads there). Held by shared_ptr: a connection's
// splitter may outlive its owner until libuv's close callback frees it (handle_block.h).
#pragma once

#include <cstdint>
#include <string>
#include <utility>

namespace radfarm::loop {

class FrameBudget {
 public:
  // `name` says where the limit is set, for the error a refused frame gets ("--max-frame-...").
  FrameBudget(uint64_t limit, std::string name) : limit_(limit), name_(std::move(name)) {}
  FrameBudget(const FrameBudget&) = delete;
  FrameBudget& operator=(const FrameBudget&) = delete;

  // Charges `bytes` if they fit, else charges nothing and counts a refusal.
  bool Take(uint64_t bytes);
  void Give(uint64_t bytes);

  uint64_t limit() const { return limit_; }
  uint64_t held() const { return held_; }
  uint64_t peak() const { return peak_; }        // the most held at once
  uint64_t refused() const { return refused_; }  // Takes that did not fit
  const std::string& name() const { return name_; }

 private:
  const uint64_t limit_;
  const std::string name_;
  uint64_t held_ = 0;
  uint64_t peak_ = 0;
  uint64_t refused_ = 0;
};

}  // namespace radfarm::loop
