// Schedule: the times of the week an agent may work, e.g. outside office hours:
//
//   "Mon-Fri 18:00-08:00, Sat-Sun 00:00-24:00"
//
// Entries are separated by commas; each is an optional day or day range (Mon Tue Wed Thu Fri Sat
// Sun, case-insensitive; a range may wrap, "Fri-Mon") and a time range HH:MM-HH:MM on the local
// clock, the start included and the end excluded; 24:00 is the end of the day. A range whose end
// is not after its start crosses midnight and belongs to the day it starts on: "Fri 18:00-08:00"
// runs from Friday evening to Saturday morning. Without days an entry holds every day. The empty
// schedule holds always.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "idle/local_time.h"

namespace radfarm::idle {

class Schedule {
 public:
  Schedule() = default;  // always
  // Errors name the entry: "entry 2 'Mon-Fry 18:00-08:00': unknown day 'Fry' (Mon..Sun)".
  static Result<Schedule> Parse(std::string_view text);

  bool Contains(LocalTime time) const;
  bool always() const { return entries_.empty(); }
  const std::string& text() const { return text_; }

 private:
  struct Entry {
    bool days[7];
    int start;  // minutes since midnight
    int end;    // 1 ... 1440; <= start: crosses midnight
  };

  std::string text_;
  std::vector<Entry> entries_;
};

}  // namespace radfarm::idle
