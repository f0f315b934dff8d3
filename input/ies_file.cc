#include "input/ies_file.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/text_file.h"

namespace radfarm {
namespace {

// Far more angles than any goniophotometer measures, few enough to bound the table's memory.
constexpr long long kMaxAngles = 10000;
constexpr long long kMaxLamps = 1000;
constexpr double kMetresPerFoot = 0.3048;

struct Word {
  std::string_view text;
  uint32_t line;
};

std::string_view Trim(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// The numbers after the TILT line, read in order across lines as LM-63 allows.
class WordStream {
 public:
  WordStream(const std::string& path, std::vector<Word> words, uint32_t last_line)
      : path_(path), words_(std::move(words)), last_line_(last_line) {}

  Result<double> Number(const std::string& what) {
    if (next_ == words_.size()) {
      return Error{Where(last_line_) + "the file ends before " + what};
    }
    const Word& w = words_[next_++];
    double value = 0;
    if (!ParseDouble(w.text, &value) || !std::isfinite(value)) {
      return Error{Where(w.line) + what + " '" + std::string(w.text) + "' is not a number"};
    }
    return value;
  }

  Result<long long> Count(const std::string& what, long long min, long long max) {
    Result<double> v = Number(what);
    RADFARM_RETURN_IF_ERROR(v);
    if (*v != std::floor(*v) || *v < static_cast<double>(min) || *v > static_cast<double>(max)) {
      return Error{Where(line()) + what + " " + Format(*v) + " is not a whole number from " +
                   std::to_string(min) + " to " + std::to_string(max)};
    }
    return static_cast<long long>(*v);
  }

  Status Rest() const {
    if (next_ == words_.size()) return Ok{};
    return Error{Where(words_[next_].line) + "unexpected '" + std::string(words_[next_].text) +
                 "' after the candela table"};
  }

  // The line of the word read last.
  uint32_t line() const { return next_ == 0 ? last_line_ : words_[next_ - 1].line; }
  std::string Where(uint32_t line) const { return path_ + ":" + std::to_string(line) + ": "; }
  size_t left() const { return words_.size() - next_; }

  static std::string Format(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }

 private:
  const std::string& path_;
  std::vector<Word> words_;
  uint32_t last_line_;
  size_t next_ = 0;
};

Result<std::string> FormatOf(std::string_view first, const std::string& path) {
  if (first == "IESNA:LM-63-2002") return std::string("LM-63-2002");
  if (first == "IESNA:LM-63-1995") return std::string("LM-63-1995");
  if (first == "IESNA91") return std::string("LM-63-1991");
  return Error{path + ":1: '" + std::string(first) +
               "' is not an LM-63 header: expected IESNA:LM-63-2002, IESNA:LM-63-1995 or IESNA91"};
}

// The header's keyword lines up to the TILT line; its index in `lines`.
Result<size_t> ReadKeywords(const std::vector<std::string_view>& lines, const std::string& path,
                            IesPhotometry* out) {
  for (size_t i = 1; i < lines.size(); ++i) {
    const std::string_view line = Trim(lines[i]);
    const std::string where = path + ":" + std::to_string(i + 1) + ": ";
    if (line.starts_with("TILT=") || line.starts_with("TILT ")) {
      const std::string_view tilt = Trim(line.substr(line.find_first_of("= ") + 1));
      if (tilt == "NONE") return i;
      if (tilt == "INCLUDE") {
        return Error{where +
                     "TILT=INCLUDE is not supported: the luminaire's output must not depend on "
                     "its tilt (TILT=NONE)"};
      }
      return Error{where + "TILT=" + std::string(tilt) +
                   " names a tilt file, which is not supported: only TILT=NONE"};
    }
    if (line.starts_with("[")) {
      const size_t close = line.find(']');
      if (close == std::string_view::npos) {
        return Error{where + "the keyword line has no closing ']'"};
      }
      out->keywords.emplace_back(std::string(line.substr(1, close - 1)),
                                 std::string(Trim(line.substr(close + 1))));
    } else if (out->format == "LM-63-2002" && !line.empty()) {
      return Error{where + "'" + std::string(line) +
                   "' is neither a [KEYWORD] line nor the TILT line, as LM-63-2002 requires"};
    } else if (!line.empty()) {
      out->keywords.emplace_back("", std::string(line));
    }
  }
  return Error{path + ":" + std::to_string(lines.size()) + ": the file has no TILT line"};
}

// The numbers after the TILT line, each with its line.
std::vector<Word> WordsAfter(const std::vector<std::string_view>& lines, size_t tilt) {
  std::vector<Word> words;
  for (size_t i = tilt + 1; i < lines.size(); ++i) {
    for (std::string_view w : SplitWords(lines[i])) {
      // Some files separate numbers with commas as well as spaces.
      while (!w.empty()) {
        const size_t comma = w.find(',');
        const std::string_view part = w.substr(0, comma);
        if (!part.empty()) words.push_back({part, static_cast<uint32_t>(i + 1)});
        if (comma == std::string_view::npos) break;
        w.remove_prefix(comma + 1);
      }
    }
  }
  return words;
}

Status ReadGeometry(WordStream& in, IesPhotometry* out, long long* n_vertical,
                    long long* n_horizontal) {
  Result<long long> lamps = in.Count("the lamp count", 1, kMaxLamps);
  RADFARM_RETURN_IF_ERROR(lamps);
  out->lamps = static_cast<int>(*lamps);
  Result<double> lumens = in.Number("the lumens per lamp");
  RADFARM_RETURN_IF_ERROR(lumens);
  if (!(*lumens > 0 || *lumens == -1)) {
    return Error{in.Where(in.line()) + "the lumens per lamp " + WordStream::Format(*lumens) +
                 " is neither positive nor -1 (absolute photometry)"};
  }
  out->lumens_per_lamp = *lumens;
  Result<double> multiplier = in.Number("the candela multiplier");
  RADFARM_RETURN_IF_ERROR(multiplier);
  if (!(*multiplier > 0)) {
    return Error{in.Where(in.line()) + "the candela multiplier " + WordStream::Format(*multiplier) +
                 " is not positive"};
  }
  out->multiplier = *multiplier;
  Result<long long> nv = in.Count("the number of vertical angles", 1, kMaxAngles);
  RADFARM_RETURN_IF_ERROR(nv);
  Result<long long> nh = in.Count("the number of horizontal angles", 1, kMaxAngles);
  RADFARM_RETURN_IF_ERROR(nh);
  *n_vertical = *nv;
  *n_horizontal = *nh;
  Result<long long> type = in.Count("the photometric type", 1, 3);
  RADFARM_RETURN_IF_ERROR(type);
  if (*type != 1) {
    return Error{in.Where(in.line()) + "photometric type " + std::to_string(*type) +
                 (*type == 2 ? " (type B)" : " (type A)") + " is not supported: only type C (1)"};
  }
  Result<long long> units = in.Count("the units type (1 feet, 2 metres)", 1, 2);
  RADFARM_RETURN_IF_ERROR(units);
  const double scale = *units == 1 ? kMetresPerFoot : 1.0;
  for (double* d : {&out->width, &out->length, &out->height}) {
    Result<double> v = in.Number("the luminous opening's size");
    RADFARM_RETURN_IF_ERROR(v);
    *d = *v * scale;
  }
  Result<double> ballast = in.Number("the ballast factor");
  RADFARM_RETURN_IF_ERROR(ballast);
  // LM-63-1995's ballast-lamp photometric factor; "future use" (1) in 2002.
  Result<double> ballast_lamp = in.Number("the ballast-lamp photometric factor");
  RADFARM_RETURN_IF_ERROR(ballast_lamp);
  const double factor = *ballast * (out->format == "LM-63-2002" ? 1.0 : *ballast_lamp);
  if (!(factor > 0)) {
    return Error{in.Where(in.line()) + "the ballast factor " + WordStream::Format(factor) +
                 " is not positive"};
  }
  out->ballast_factor = factor;
  Result<double> watts = in.Number("the input watts");
  RADFARM_RETURN_IF_ERROR(watts);
  if (*watts < 0) {
    return Error{in.Where(in.line()) + "the input watts " + WordStream::Format(*watts) +
                 " is negative"};
  }
  out->input_watts = *watts;
  return Ok{};
}

// n numbers into `out`; with `non_negative`, a negative one is an error at its line.
Status ReadList(WordStream& in, long long n, const std::string& what, bool non_negative,
                std::vector<double>* out) {
  out->reserve(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i) {
    if (in.left() == 0) {
      return Error{in.Where(in.line()) + "the file ends inside the " + what + " (" +
                   std::to_string(i) + " of " + std::to_string(n) + " values)"};
    }
    Result<double> v = in.Number("a value of the " + what);
    RADFARM_RETURN_IF_ERROR(v);
    if (non_negative && *v < 0) {
      return Error{in.Where(in.line()) + "the " + what + " holds a negative value " +
                   WordStream::Format(*v)};
    }
    out->push_back(*v);
  }
  return Ok{};
}

}  // namespace

Result<IesPhotometry> ParseIes(std::string_view text, const std::string& path) {
  const std::vector<std::string_view> lines = SplitLines(text);
  if (lines.empty()) return Error{path + ":1: the file is empty"};
  IesPhotometry out;
  Result<std::string> format = FormatOf(Trim(lines[0]), path);
  RADFARM_RETURN_IF_ERROR(format);
  out.format = *format;
  Result<size_t> tilt = ReadKeywords(lines, path, &out);
  RADFARM_RETURN_IF_ERROR(tilt);
  WordStream in(path, WordsAfter(lines, *tilt), static_cast<uint32_t>(lines.size()));
  long long nv = 0;
  long long nh = 0;
  RADFARM_RETURN_IF_ERROR(ReadGeometry(in, &out, &nv, &nh));
  RADFARM_RETURN_IF_ERROR(ReadList(in, nv, "vertical angles", false, &out.table.vertical));
  const uint32_t vertical_line = in.line();
  RADFARM_RETURN_IF_ERROR(ReadList(in, nh, "horizontal angles", false, &out.table.horizontal));
  const uint32_t horizontal_line = in.line();
  RADFARM_RETURN_IF_ERROR(ReadList(in, nv * nh, "candela table", true, &out.table.candela));
  RADFARM_RETURN_IF_ERROR(in.Rest());
  for (double& c : out.table.candela) c *= out.multiplier * out.ballast_factor;
  // The counts match by construction, and candela were checked as read: what is left is about
  // the angles, located at the list it names.
  const std::string problem = CandelaTableProblem(out.table);
  if (!problem.empty()) {
    const bool horizontal = problem.starts_with("the horizontal");
    return Error{in.Where(horizontal ? horizontal_line : vertical_line) + problem};
  }
  return out;
}

}  // namespace radfarm
