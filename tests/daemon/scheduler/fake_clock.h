// The scheduler tests' fake clock: times are kT0 plus a duration the test picks.
#pragma once

#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::scheduler {

inline constexpr TimePoint kT0{};

}  // namespace radfarm::scheduler
