// FrameBudget: the bytes that frames still arriving may hold, shared by many connections (the
// master's agents). Each connection's FrameSplitter joins it as one holder, charges its partial
// frame's buffer as the buffer grows and gives it all back when the frame completes or the
// connection goes. So peers that trickle big frames, however many, hold at most the budget
// between them, not their count times the frame limit.
//
// A growth the budget cannot cover closes the holder holding the most: the holders above the
// one asking are evicted, largest first, until the growth fits; if the one asking would then hold
// the most, it is refused instead. So one peer with a huge unfinished frame cannot starve peers
// sending small ones: it is the one that goes.
//
// Loop thread only (every connection sharing it reads there). Held by shared_ptr: a connection's
// splitter may outlive its owner until libuv's close callback frees it (handle_block.h).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>

namespace radfarm::loop {

class FrameBudget {
 public:
  // Called once when the holder is evicted, its share already given back; the reason names the
  // limit. It must not call back into the budget.
  using OnEvicted = std::function<void(const std::string& reason)>;

  // `name` says where the limit is set, for the error a refused frame gets ("--max-frame-...").
  FrameBudget(uint64_t limit, std::string name) : limit_(limit), name_(std::move(name)) {}
  FrameBudget(const FrameBudget&) = delete;
  FrameBudget& operator=(const FrameBudget&) = delete;

  // A new holder, holding nothing; Leave gives back what it still holds.
  uint64_t Join(OnEvicted on_evicted);
  void Leave(uint64_t holder);

  // Charges `bytes` more to `holder` if they fit, evicting larger holders as the header says;
  // else charges nothing, counts a refusal and returns false.
  bool Take(uint64_t holder, uint64_t bytes);
  void Give(uint64_t holder, uint64_t bytes);

  uint64_t limit() const { return limit_; }
  uint64_t held() const { return held_; }
  uint64_t held_by(uint64_t holder) const;
  uint64_t peak() const { return peak_; }        // the most held at once
  uint64_t refused() const { return refused_; }  // frames refused or evicted
  uint64_t evicted() const { return evicted_; }  // of those, holders closed for another's frame
  const std::string& name() const { return name_; }

 private:
  struct Holder {
    uint64_t held = 0;
    OnEvicted on_evicted;
  };
  // The holder other than `asking` holding the most, or end().
  std::map<uint64_t, Holder>::iterator Largest(uint64_t asking);
  void Evict(std::map<uint64_t, Holder>::iterator victim, uint64_t wanted);

  const uint64_t limit_;
  const std::string name_;
  std::map<uint64_t, Holder> holders_;
  uint64_t next_holder_ = 1;
  uint64_t held_ = 0;
  uint64_t peak_ = 0;
  uint64_t refused_ = 0;
  uint64_t evicted_ = 0;
};

}  // namespace radfarm::loop
