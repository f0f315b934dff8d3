// The job file's sky (`[sky]`): what it says, read with located errors, and what it makes of the
// scene's light: the dome (core/sky.h) and, for a clear sky, its sun as a punctual sun
// (core/punctual_light.h). cli/ puts both in the scene (InputScene::sky and lights).
#pragma once

#include <optional>

#include "base/result.h"
#include "base/toml_table_reader.h"
#include "core/punctual_light.h"
#include "core/sky.h"
#include "core/solar_position.h"
#include "core/vec3.h"

namespace radfarm {

struct JobSky {
  SkyKind kind = SkyKind::kNone;
  double zenith = 0;  // the dome's zenith luminance, cd/m^2 (from horizontal_illuminance if given)
  Vec3 sun{0, 1, 0};  // unit, toward the sun, above the horizon (cie-clear)
  // The sun's illuminance on a plane facing it, lux; 0 on a clear sky: from its altitude
  // (SunNormalIlluminance).
  double sun_illuminance = 0;
};

// The sun's illuminance at normal incidence under a clear sky at this altitude (unit `sun`,
// +Y up): 127,500 lx exp(-0.21 m), air mass m = 1 / sin(altitude), the IES Lighting Handbook's
// extinction model for clear skies.
double SunNormalIlluminance(const Vec3& sun);

// Reads the keys of a `[sky]` table (job/job_file.cc lists them); errors name the file, line and
// key.
Status ReadSky(TomlTableReader* r, JobSky* sky);

// The dome the scene is lit by (kind none for a job without a sky).
Sky SkyOf(const JobSky& sky);
// A clear sky's sun as a punctual sun; nullopt for the other kinds.
std::optional<PunctualLight> SunOf(const JobSky& sky);

}  // namespace radfarm
