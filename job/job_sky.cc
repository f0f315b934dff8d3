#include "job/job_sky.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace radfarm {
namespace {

// "YYYY-MM-DD" into *when, false if it is not a date of the Gregorian calendar.
bool ParseDate(const std::string& text, SolarTime* when) {
  int y = 0, m = 0, d = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3) return false;
  if (m < 1 || m > 12 || d < 1) return false;
  static constexpr int kDays[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  if (d > kDays[m - 1] || (m == 2 && d == 29 && !leap)) return false;
  when->year = y, when->month = m, when->day = d;
  return true;
}

// "HH:MM" or "HH:MM:SS", 24-hour, into when->hour.
bool ParseTime(const std::string& text, SolarTime* when) {
  int h = 0, m = 0, s = 0;
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%2d:%2d:%2d%c", &h, &m, &s, &tail);
  if (n != 2 && n != 3) return false;
  if (h < 0 || h > 23 || m < 0 || m > 59 || s < 0 || s > 59) return false;
  when->hour = h + m / 60.0 + s / 3600.0;
  return true;
}

Status ReadKind(TomlTableReader* r, JobSky* sky) {
  std::string type;
  bool has_type = false;
  RADFARM_RETURN_IF_ERROR(r->String("type", &type, &has_type));
  if (!has_type) return r->ErrorFor("type", "is missing");
  if (type == "uniform") {
    sky->kind = SkyKind::kUniform;
  } else if (type == "cie-overcast") {
    sky->kind = SkyKind::kCieOvercast;
  } else if (type == "cie-clear") {
    sky->kind = SkyKind::kCieClear;
  } else {
    return r->ErrorFor(
        "type", "must be \"uniform\", \"cie-overcast\" or \"cie-clear\", got \"" + type + "\"");
  }
  return Ok{};
}

// The clear sky's sun: `sun`, or `date`, `time` and the place. Other kinds take none of these.
Status ReadSun(TomlTableReader* r, JobSky* sky) {
  bool has_sun = false, has_date = false, has_time = false, has_lat = false, has_lon = false;
  Vec3 sun;
  std::string date, time;
  SolarTime when;
  Vec3 north{0, 0, -1};
  bool has_north = false, has_zone = false;
  RADFARM_RETURN_IF_ERROR(r->Vector("sun", &sun, &has_sun));
  RADFARM_RETURN_IF_ERROR(r->String("date", &date, &has_date));
  RADFARM_RETURN_IF_ERROR(r->String("time", &time, &has_time));
  RADFARM_RETURN_IF_ERROR(r->Real("latitude", Interval::Closed(-90, 90), &when.latitude, &has_lat));
  RADFARM_RETURN_IF_ERROR(
      r->Real("longitude", Interval::Closed(-180, 180), &when.longitude, &has_lon));
  RADFARM_RETURN_IF_ERROR(
      r->Real("timezone", Interval::Closed(-14, 14), &when.timezone, &has_zone));
  RADFARM_RETURN_IF_ERROR(r->Vector("north", &north, &has_north));
  const bool place = has_date || has_time || has_lat || has_lon || has_zone || has_north;
  if (sky->kind != SkyKind::kCieClear) {
    for (const auto& [key, given] : {std::pair{"sun", has_sun},
                                     {"date", has_date},
                                     {"time", has_time},
                                     {"latitude", has_lat},
                                     {"longitude", has_lon},
                                     {"timezone", has_zone},
                                     {"north", has_north}}) {
      if (given) return r->ErrorFor(key, "is for a \"cie-clear\" sky only");
    }
    return Ok{};
  }
  if (has_sun && place) {
    return r->ErrorFor("sun", "and date, time and place go apart: give one or the other");
  }
  if (has_sun) {
    const double length = Length(sun);
    if (!IsFinite(sun) || !(length > 0)) return r->ErrorFor("sun", "must be finite and nonzero");
    sky->sun = sun / length;
    if (!(sky->sun.y > 0)) return r->ErrorFor("sun", "must point above the horizon (+Y is up)");
    return Ok{};
  }
  for (const auto& [key, given] : {std::pair{"date", has_date},
                                   {"time", has_time},
                                   {"latitude", has_lat},
                                   {"longitude", has_lon}}) {
    if (!given) {
      return r->ErrorFor(key,
                         "is missing (a \"cie-clear\" sky takes `sun`, or date, time, "
                         "latitude and longitude)");
    }
  }
  if (!ParseDate(date, &when)) return r->ErrorFor("date", "must be a date \"YYYY-MM-DD\"");
  if (!ParseTime(time, &when)) return r->ErrorFor("time", "must be a time \"HH:MM\" (24-hour)");
  if (!IsFinite(north) || !(std::fabs(north.y) < 1e-9) || !(Length(north) > 0)) {
    return r->ErrorFor("north", "must be finite, nonzero and horizontal (y = 0)");
  }
  sky->sun = SunDirectionInScene(when, Normalize(north));
  if (!(sky->sun.y > 0)) {
    return r->ErrorFor("time", "puts the sun below the horizon at that date and place");
  }
  return Ok{};
}

}  // namespace

double SunNormalIlluminance(const Vec3& sun) {
  if (!(sun.y > 0)) return 0;
  return 127500 * std::exp(-0.21 / sun.y);
}

Status ReadSky(TomlTableReader* r, JobSky* sky) {
  RADFARM_RETURN_IF_ERROR(ReadKind(r, sky));
  bool has_zenith = false, has_horizontal = false, has_sun_lux = false;
  double horizontal = 0;
  RADFARM_RETURN_IF_ERROR(
      r->Real("zenith_luminance", Interval::Above(0), &sky->zenith, &has_zenith));
  RADFARM_RETURN_IF_ERROR(
      r->Real("horizontal_illuminance", Interval::Above(0), &horizontal, &has_horizontal));
  RADFARM_RETURN_IF_ERROR(
      r->Real("sun_illuminance", Interval::AtLeast(0), &sky->sun_illuminance, &has_sun_lux));
  if (has_zenith == has_horizontal) {
    return r->ErrorFor(has_zenith ? "horizontal_illuminance" : "zenith_luminance",
                       has_zenith ? "and zenith_luminance go apart: give one"
                                  : "or horizontal_illuminance is required");
  }
  if (has_sun_lux && sky->kind != SkyKind::kCieClear) {
    return r->ErrorFor("sun_illuminance", "is for a \"cie-clear\" sky only");
  }
  RADFARM_RETURN_IF_ERROR(ReadSun(r, sky));
  if (has_horizontal) {
    // The dome's shape at a zenith luminance of 1, scaled to the illuminance asked for.
    const Sky unit{sky->kind, 1.0, sky->sun};
    sky->zenith = horizontal / SkyHorizontalIlluminance(unit);
  }
  if (sky->kind == SkyKind::kCieClear && !has_sun_lux) {
    sky->sun_illuminance = SunNormalIlluminance(sky->sun);
  }
  return Ok{};
}

Sky SkyOf(const JobSky& sky) { return Sky{sky.kind, sky.zenith, sky.sun}; }

std::optional<PunctualLight> SunOf(const JobSky& sky) {
  if (sky.kind != SkyKind::kCieClear) return std::nullopt;
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = -sky.sun;
  sun.intensity = {sky.sun_illuminance, sky.sun_illuminance, sky.sun_illuminance};
  return sun;
}

}  // namespace radfarm
