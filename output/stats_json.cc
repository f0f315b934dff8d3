#include "output/stats_json.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>

#include "base/atomic_file.h"
#include "output/number_format.h"

namespace radfarm {
namespace {

// Length of the well-formed UTF-8 sequence starting at s[i] (a lead byte >= 0x80), or 0 when it is
// malformed: truncated, overlong, a surrogate or beyond U+10FFFF.
size_t Utf8SequenceLength(std::string_view s, size_t i) {
  const unsigned char lead = static_cast<unsigned char>(s[i]);
  size_t length;
  uint32_t code_point;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    code_point = lead & 0x1F;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    code_point = lead & 0x0F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    code_point = lead & 0x07;
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    const unsigned char next = static_cast<unsigned char>(s[i + k]);
    if ((next & 0xC0) != 0x80) return 0;
    code_point = (code_point << 6) | (next & 0x3F);
  }
  if (length == 3 && (code_point < 0x800 || (code_point >= 0xD800 && code_point <= 0xDFFF))) {
    return 0;
  }
  if (length == 4 && (code_point < 0x10000 || code_point > 0x10FFFF)) return 0;
  return length;
}

std::string JsonNumber(double value) { return std::isfinite(value) ? FormatDouble(value) : "null"; }

class ObjectWriter {
 public:
  ObjectWriter() : text_("{") {}

  // False when `key` was already written.
  bool Add(const std::string& key, const std::string& json_value) {
    if (!keys_.insert(key).second) return false;
    text_ += keys_.size() == 1 ? "\n  " : ",\n  ";
    text_ += JsonString(key);
    text_ += ": ";
    text_ += json_value;
    return true;
  }
  std::string Finish() { return text_ + "\n}\n"; }

 private:
  std::string text_;
  std::set<std::string> keys_;
};

}  // namespace

std::string JsonString(std::string_view text) {
  std::string out = "\"";
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      const size_t length = Utf8SequenceLength(text, i);
      if (length == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(text.substr(i, length));
        i += length;
      }
      continue;
    }
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20 || c == 0x7F) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
          out += escaped;
        } else {
          out += static_cast<char>(c);
        }
    }
    ++i;
  }
  return out + "\"";
}

Result<std::string> FormatStatsJson(const SolveStats& stats, const JsonNumbers& extra_numbers,
                                    const JsonStrings& extra_strings, const JobTimeline& timeline) {
  ObjectWriter object;
  // The field list mirrors core/solve_stats.h in declaration order.
  object.Add("rays", FormatUnsigned(stats.rays));
  if (stats.start_rays > 0) object.Add("start_rays", FormatUnsigned(stats.start_rays));
  if (stats.start_seconds > 0) object.Add("start_seconds", JsonNumber(stats.start_seconds));
  object.Add("rounds", FormatUnsigned(stats.rounds));
  object.Add("seconds", JsonNumber(stats.seconds));
  object.Add("rays_per_second", JsonNumber(stats.rays_per_second));
  object.Add("patches", FormatUnsigned(stats.patches));
  object.Add("unshot_fraction", JsonNumber(stats.unshot_fraction));
  object.Add("escaped_rays", FormatUnsigned(stats.escaped_rays));
  object.Add("backface_hits", FormatUnsigned(stats.backface_hits));
  object.Add("threads", FormatUnsigned(stats.threads));
  object.Add("seed", FormatUnsigned(stats.seed));
  object.Add("sampler", JsonString(stats.sampler));
  object.Add("stop_reason", JsonString(stats.stop_reason));
  object.Add("emitted_power", JsonNumber(stats.emitted_power));
  object.Add("absorbed_power", JsonNumber(stats.absorbed_power));
  object.Add("escaped_power", JsonNumber(stats.escaped_power));
  for (const auto& [key, value] : extra_numbers) {
    if (!object.Add(key, JsonNumber(value))) {
      return Error{"stats: duplicate key " + JsonString(key)};
    }
  }
  for (const auto& [key, value] : extra_strings) {
    if (!object.Add(key, JsonString(value))) {
      return Error{"stats: duplicate key " + JsonString(key)};
    }
  }
  if (!timeline.empty()) {
    std::string entries;
    for (const TimelineEntry& e : timeline) {
      entries += std::string(entries.empty() ? "" : ",") +
                 "\n    {\"phase\": " + JsonString(JobPhaseName(e.phase)) +
                 ", \"where\": " + JsonString(e.where) +
                 ", \"wall_seconds\": " + JsonNumber(e.wall_seconds) +
                 ", \"cpu_seconds\": " + JsonNumber(e.cpu_seconds) + "}";
    }
    if (!object.Add("timeline", "[" + entries + "\n  ]")) {
      return Error{"stats: duplicate key \"timeline\""};
    }
  }
  return object.Finish();
}

Status WriteStatsJson(const std::string& path, const SolveStats& stats,
                      const JsonNumbers& extra_numbers, const JsonStrings& extra_strings,
                      const JobTimeline& timeline) {
  Result<std::string> text = FormatStatsJson(stats, extra_numbers, extra_strings, timeline);
  if (!text.ok()) return Error{path + ": cannot write " + text.error()};
  return WriteFileAtomically(path, *text);
}

}  // namespace radfarm
