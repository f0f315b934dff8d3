#include "output/illuminance_report.h"

#include <algorithm>

#include "output/number_format.h"
#include "output/stats_json.h"

namespace radfarm {
namespace {

std::string SummaryFields(const LuxSummary& s) {
  return "\"points\": " + FormatUnsigned(s.points) + ", \"min\": " + FormatDouble(s.min) +
         ", \"mean\": " + FormatDouble(s.mean) + ", \"max\": " + FormatDouble(s.max) +
         ", \"uniformity_min_mean\": " + FormatDouble(s.uniformity) +
         ", \"uniformity_min_max\": " + FormatDouble(s.diversity);
}

}  // namespace

LuxSummary SummariseLux(const std::vector<double>& lux) {
  LuxSummary s;
  s.points = lux.size();
  if (lux.empty()) return s;
  s.min = *std::min_element(lux.begin(), lux.end());
  s.max = *std::max_element(lux.begin(), lux.end());
  double sum = 0;
  for (double v : lux) sum += v;
  s.mean = sum / double(lux.size());
  s.uniformity = s.mean > 0 ? s.min / s.mean : 0;
  s.diversity = s.max > 0 ? s.min / s.max : 0;
  return s;
}

std::string IlluminanceCsv(const PlaneIlluminance& plane) {
  std::string out = std::string(kIlluminanceCsvHeader) + "\n";
  for (size_t i = 0; i < plane.grid.points.size(); ++i) {
    const Vec3& p = plane.grid.points[i].position;
    out += FormatDouble(p.x) + "," + FormatDouble(p.y) + "," + FormatDouble(p.z) + "," +
           FormatDouble(plane.lux[i]) + "\n";
  }
  return out;
}

std::string IlluminanceJson(const std::vector<PlaneIlluminance>& planes) {
  std::string out = "{\n  \"unit\": \"lux\",\n  \"planes\": [";
  for (size_t k = 0; k < planes.size(); ++k) {
    const PlaneIlluminance& p = planes[k];
    out += std::string(k == 0 ? "" : ",") + "\n    {\"name\": " + JsonString(p.plane.name) +
           ", \"height\": " + FormatDouble(p.plane.height) +
           ", \"spacing\": " + FormatDouble(p.plane.spacing) + ", " +
           SummaryFields(SummariseLux(p.lux)) + ",\n     \"levels\": [";
    for (size_t level = 0; level < p.grid.levels.size(); ++level) {
      std::vector<double> lux;
      for (size_t i = 0; i < p.grid.cells.size(); ++i) {
        if (p.grid.cells[i].level == level) lux.push_back(p.lux[i]);
      }
      out += std::string(level == 0 ? "" : ",") +
             "\n       {\"surface_height\": " + FormatDouble(p.grid.levels[level]) + ", " +
             SummaryFields(SummariseLux(lux)) + "}";
    }
    out += p.grid.levels.empty() ? "]}" : "\n     ]}";
  }
  out += planes.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

}  // namespace radfarm
