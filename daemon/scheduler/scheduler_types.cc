#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::scheduler {

std::string_view DropReasonName(DropReason reason) {
  switch (reason) {
    case DropReason::kNone:
      return "none";
    case DropReason::kStaleRound:
      return "stale round";
    case DropReason::kUnknownAttempt:
      return "unknown attempt";
    case DropReason::kDuplicate:
      return "duplicate";
    case DropReason::kLate:
      return "late";
    case DropReason::kWrongBatch:
      return "wrong batch";
    case DropReason::kNotHolder:
      return "not the holder";
    case DropReason::kBlocklisted:
      return "blocklisted";
    case DropReason::kInvalid:
      return "invalid";
  }
  return "?";
}

}  // namespace radfarm::scheduler
