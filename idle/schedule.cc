#include "idle/schedule.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>

namespace radfarm::idle {
namespace {

constexpr std::array<std::string_view, 7> kDays = {"mon", "tue", "wed", "thu", "fri", "sat", "sun"};

std::string_view Trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
    text.remove_prefix(1);
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
    text.remove_suffix(1);
  }
  return text;
}

std::optional<int> DayIndex(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (size_t i = 0; i < kDays.size(); ++i) {
    if (lower == kDays[i]) return static_cast<int>(i);
  }
  return std::nullopt;
}

// "HH:MM" with HH 00..24 and MM 00..59; 24:00 only when `allow_end_of_day`.
std::optional<int> ParseClock(std::string_view text, bool allow_end_of_day) {
  if (text.size() != 5 || text[2] != ':') return std::nullopt;
  for (size_t i : {0, 1, 3, 4}) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) return std::nullopt;
  }
  const int hours = (text[0] - '0') * 10 + (text[1] - '0');
  const int minutes = (text[3] - '0') * 10 + (text[4] - '0');
  if (minutes > 59) return std::nullopt;
  if (hours == 24 && minutes == 0 && allow_end_of_day) return 24 * 60;
  if (hours > 23) return std::nullopt;
  return hours * 60 + minutes;
}

}  // namespace

Result<Schedule> Schedule::Parse(std::string_view text) {
  Schedule schedule;
  schedule.text_ = std::string(Trim(text));
  if (schedule.text_.empty()) return schedule;

  std::string_view rest = schedule.text_;
  for (int number = 1;; ++number) {
    const size_t comma = rest.find(',');
    const std::string_view entry_text = Trim(rest.substr(0, comma));
    const auto fail = [&](const std::string& what) {
      return Error{"entry " + std::to_string(number) + " '" + std::string(entry_text) +
                   "': " + what};
    };

    Entry entry{};
    std::string_view times = entry_text;
    const size_t space = entry_text.find(' ');
    if (space == std::string_view::npos) {
      std::fill(std::begin(entry.days), std::end(entry.days), true);
    } else {
      const std::string_view days = entry_text.substr(0, space);
      times = Trim(entry_text.substr(space + 1));
      const size_t dash = days.find('-');
      const std::string_view first_name = days.substr(0, dash);
      const std::string_view last_name =
          dash == std::string_view::npos ? first_name : days.substr(dash + 1);
      const std::optional<int> first = DayIndex(first_name);
      const std::optional<int> last = DayIndex(last_name);
      if (!first || !last) {
        return fail("unknown day '" + std::string(first ? last_name : first_name) + "' (Mon..Sun)");
      }
      for (int day = *first;; day = (day + 1) % 7) {
        entry.days[day] = true;
        if (day == *last) break;
      }
    }

    const size_t dash = times.find('-');
    const std::optional<int> start =
        dash == std::string_view::npos ? std::nullopt : ParseClock(times.substr(0, dash), false);
    const std::optional<int> end =
        dash == std::string_view::npos ? std::nullopt : ParseClock(times.substr(dash + 1), true);
    if (!start || !end) return fail("expected [DAYS ]HH:MM-HH:MM, e.g. 'Mon-Fri 18:00-08:00'");
    if (*start == *end) return fail("the range is empty (for a whole day write 00:00-24:00)");
    entry.start = *start;
    entry.end = *end;
    schedule.entries_.push_back(entry);

    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return schedule;
}

bool Schedule::Contains(LocalTime time) const {
  if (entries_.empty()) return true;
  const int yesterday = (time.weekday + 6) % 7;
  for (const Entry& entry : entries_) {
    if (entry.start < entry.end) {
      if (entry.days[time.weekday] && time.minute >= entry.start && time.minute < entry.end) {
        return true;
      }
    } else {  // crosses midnight: the evening part today, the morning part from yesterday
      if (entry.days[time.weekday] && time.minute >= entry.start) return true;
      if (entry.days[yesterday] && time.minute < entry.end) return true;
    }
  }
  return false;
}

}  // namespace radfarm::idle
