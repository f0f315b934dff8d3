// LoadJob. A job file is TOML; every key is optional except `scene`, and any other key is an error:
//
//   scene = "cornell-box.obj"     # the OBJ, .gltf or .glb; relative to this file's directory
//   two_sided = false             # every surface receives and emits on both sides
//   from = "out"                  # re-bake from the render written to this directory (relative
//                                 # to this file), shooting only what changed: `render` only
//   [mesh]
//   patch_size = 30.0             # largest patch edge in scene units, > 0 (absent: automatic);
//                                 # a triangle's longest edge may be sqrt(2) times it
//   refine = false                # adaptive refinement of receivers during the solve
//   refine_tolerance = 0.1        # relative image error that splits an element, > 0
//   min_element_size = 3.0        # smallest element edge, > 0 (absent: patch size / 4)
//   max_elements = 20000          # element budget, integer >= 1 (absent: 8 x initial patches)
//   [solver]
//   sampler = "sobol"             # grid | random | sobol
//   seed = 1                      # integer >= 0
//   tolerance = 0.001             # stop when unshot power < tolerance * emitted, in (0, 1)
//   rays = 0                      # ray budget, integer >= 0, 0 = none
//   seconds = 0                   # time budget, >= 0, 0 = none
//   shot_rays = 4194304           # rays per emitted power, integer > 0
//   min_shooter_rays = 1          # integer >= 1
//   shooters_per_round = 0        # integer >= 0, 0 = every patch with unshot power
//   overrelaxation = 1.0          # Southwell over-relaxation factor, in [1, 2), 1 = none
//   gather_rays = 2048            # final gather rays per patch, integer in [0, 2^20], 0 = off
//   grid_step_degrees = 1.0       # grid sampler's angular step, in (0, 90]
//   threads = 0                   # integer in [0, 65536], 0 = all cores
//   [camera]
//   eye = [278, 273, -800]        # eye and target go together; setting them turns off the
//   target = [278, 273, 0]        # automatic camera
//   up = [0, 1, 0]                # not parallel to target - eye
//   fov = 39.3077                 # vertical field of view in degrees, in (0, 180)
//   width = 512                   # pixels, in [1, 16384]
//   height = 512                  # pixels, in [1, 16384]
//   exposure = 0.0                # stops; setting it turns off automatic exposure
//   samples_per_pixel = 4         # in [1, 1024]
//   name = "Camera"               # a camera of the scene file (glTF) by node or camera name
//   [output]
//   lightmap_size = 1024          # every lightmap this many texels square, 0 or in [16, 8192]
//                                 # (absent or 0: automatic, 32 to 2048 by the object's area)
//   lightmap_texel = 0.01         # automatic size from texels of about this edge, scene units,
//                                 # > 0 (absent: patch size / 4, or / 16 where the display
//                                 # refined itself); not with lightmap_size
//   [[illuminance]]               # a calculation plane of the illuminance report; repeatable
//   name = "desks"                # the files' stem, unique: letters, digits, '-', '_', '.'
//   height = 0.8                  # above the surfaces, scene units, >= 0
//   spacing = 0.25                # between grid points, scene units, > 0
//   surfaces = ["Desk*"]          # objects or materials (shell patterns) carrying the plane
//                                 # (absent: every floor)
//   [[lamps]]                     # an IES lamp hung in the scene; repeatable
//   file = "downlight.ies"        # LM-63 photometric file, relative to this file's directory
//   position = [2, 2.7, 3]        # scene units (metres)
//   aim = [0, -1, 0]              # the lamp's nadir axis, nonzero (absent: straight down)
//   rotate = 0                    # degrees around the aim (turns horizontal angle 0 toward 90)
//   multiplier = 1                # times the file's candela, > 0
//   [sky]                         # light from beyond the scene (core/sky.h); +Y is up
//   type = "cie-overcast"         # uniform | cie-overcast | cie-clear
//   zenith_luminance = 3000       # cd/m^2 at the zenith (a uniform sky's everywhere), > 0; or
//   horizontal_illuminance = 10000  # lux the dome gives an open horizontal plane, > 0 (one of
//   them) sun = [0.3, 0.8, -0.5]        # cie-clear: toward the sun, above the horizon; or: date =
//   "2025-06-21"           # cie-clear: the sun from date, local clock time and place time =
//   "14:30"                #   "HH:MM" (24-hour) timezone = 1                  #   hours east of
//   UTC of the clock, in [-14, 14] (absent: 0) latitude = 51.5               #   degrees north, in
//   [-90, 90] longitude = -0.12             #   degrees east, in [-180, 180] north = [0, 0, -1] #
//   the scene's north, horizontal (absent: -Z; east is +X) sun_illuminance = 80000       #
//   cie-clear: the sun's lux on a plane facing it, >= 0 (absent:
//                                 # from its altitude, 127500 exp(-0.21 / sin altitude))
//   [materials.NAME]              # per material of the scene, by name
//   two_sided = true              # this material receives and emits on both sides (an
//                                 # emitter then lights both ways; false: its front only)
//
// Errors are one line naming the file, the line and the dotted key:
// "job.toml:7: unknown key 'solver.sampel'".
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "base/diagnostic.h"
#include "base/file_extension.h"
#include "base/result.h"
#include "base/toml_file.h"
#include "base/toml_table_reader.h"
#include "job/job.h"
#include "job/job_sky.h"

namespace radfarm {
namespace {

constexpr int64_t kMaxInt64 = std::numeric_limits<int64_t>::max();
constexpr int64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();
constexpr int64_t kMaxSamplesPerPixel = 1024;

// Applies a section's reads to the sub-table `name` of `root`, then rejects its unknown keys.
template <typename ReadKeys>
Status ReadSection(const std::string& path, TomlTableReader* root, std::string_view name,
                   ReadKeys read) {
  Result<const toml::table*> table = root->Table(name);
  RADFARM_RETURN_IF_ERROR(table);
  if (*table == nullptr) return Ok{};
  TomlTableReader reader(path, **table, std::string(name) + ".");
  RADFARM_RETURN_IF_ERROR(read(&reader));
  return reader.CheckNoUnknownKeys();
}

Status ReadMesh(TomlTableReader* r, MeshSettings* mesh, RefineSettings* refine) {
  RADFARM_RETURN_IF_ERROR(r->Real("patch_size", Interval::Above(0), &mesh->patch_size));
  RADFARM_RETURN_IF_ERROR(r->Bool("refine", &refine->enabled));
  RADFARM_RETURN_IF_ERROR(r->Real("refine_tolerance", Interval::Above(0), &refine->tolerance));
  RADFARM_RETURN_IF_ERROR(
      r->Real("min_element_size", Interval::Above(0), &refine->min_element_size));
  return r->Integer("max_elements", 1, kMaxInt64, &refine->max_elements);
}

Status ReadSolver(TomlTableReader* r, SolverSettings* solver) {
  std::string sampler;
  bool has_sampler = false;
  RADFARM_RETURN_IF_ERROR(r->String("sampler", &sampler, &has_sampler));
  if (has_sampler && !ParseSamplerName(sampler, &solver->sampler)) {
    return r->ErrorFor("sampler",
                       "must be \"grid\", \"random\" or \"sobol\", got \"" + sampler + "\"");
  }
  RADFARM_RETURN_IF_ERROR(r->Integer("seed", 0, kMaxInt64, &solver->seed));
  RADFARM_RETURN_IF_ERROR(r->Real("tolerance", ToleranceRange(), &solver->tolerance));
  RADFARM_RETURN_IF_ERROR(r->Integer("rays", 0, kMaxInt64, &solver->max_rays));
  RADFARM_RETURN_IF_ERROR(r->Real("seconds", Interval::AtLeast(0), &solver->max_seconds));
  RADFARM_RETURN_IF_ERROR(r->Integer("shot_rays", 1, kMaxInt64, &solver->shot_rays));
  RADFARM_RETURN_IF_ERROR(r->Integer("min_shooter_rays", 1, kMaxUint32, &solver->min_shooter_rays));
  RADFARM_RETURN_IF_ERROR(
      r->Integer("shooters_per_round", 0, kMaxUint32, &solver->shooters_per_round));
  RADFARM_RETURN_IF_ERROR(r->Real("overrelaxation",
                                  Interval::ClosedOpen(kMinOverrelaxation, kMaxOverrelaxation),
                                  &solver->overrelaxation));
  RADFARM_RETURN_IF_ERROR(
      r->Real("grid_step_degrees", Interval::OpenClosed(0, 90), &solver->grid_step_degrees));
  RADFARM_RETURN_IF_ERROR(r->Integer("gather_rays", 0, kMaxGatherRays, &solver->gather_rays));
  return r->Integer("threads", 0, int64_t{kMaxSolverThreads}, &solver->threads);
}

// An explicit camera needs both ends of its view direction and an up vector off that direction.
Status CheckExplicitCamera(TomlTableReader* r, bool has_eye, bool has_target,
                           const Camera& camera) {
  if (has_eye != has_target) {
    return r->ErrorFor(has_eye ? "eye" : "target",
                       has_eye ? "is set without 'camera.target'; set both or neither"
                               : "is set without 'camera.eye'; set both or neither");
  }
  const Vec3 view = camera.target - camera.eye;
  if (Length(view) == 0) return r->ErrorFor("eye", "must differ from camera.target");
  if (Length(Cross(view, camera.up)) <= 1e-9 * Length(view) * Length(camera.up)) {
    return r->ErrorFor("up", "must be nonzero and not parallel to camera.target - camera.eye");
  }
  return Ok{};
}

Status ReadCamera(TomlTableReader* r, Job* job) {
  Camera* camera = &job->camera;
  bool has_eye = false, has_target = false, has_exposure = false, has_width = false,
       has_height = false;
  RADFARM_RETURN_IF_ERROR(r->Vector("eye", &camera->eye, &has_eye));
  RADFARM_RETURN_IF_ERROR(r->Vector("target", &camera->target, &has_target));
  RADFARM_RETURN_IF_ERROR(r->Vector("up", &camera->up));
  RADFARM_RETURN_IF_ERROR(r->Real("fov", Interval::Open(0, 180), &camera->fov_degrees));
  RADFARM_RETURN_IF_ERROR(r->Integer("width", 1, kMaxImageSide, &camera->width, &has_width));
  RADFARM_RETURN_IF_ERROR(r->Integer("height", 1, kMaxImageSide, &camera->height, &has_height));
  job->width_given = has_width;
  job->height_given = has_height;
  RADFARM_RETURN_IF_ERROR(r->Real("exposure", Interval::Any(), &camera->exposure, &has_exposure));
  RADFARM_RETURN_IF_ERROR(
      r->Integer("samples_per_pixel", 1, kMaxSamplesPerPixel, &camera->samples_per_pixel));
  if (has_exposure) camera->auto_exposure = false;
  if (has_eye || has_target) {
    RADFARM_RETURN_IF_ERROR(CheckExplicitCamera(r, has_eye, has_target, *camera));
    camera->automatic = false;
  }
  return Ok{};
}

// The lightmaps' resolution: a fixed size or a texel size, not both.
Status ReadOutput(TomlTableReader* r, Job* job) {
  int64_t size = 0;
  bool has_size = false, has_texel = false;
  RADFARM_RETURN_IF_ERROR(r->Integer("lightmap_size", std::numeric_limits<int64_t>::min(),
                                     kMaxInt64, &size, &has_size));
  if (has_size && !IsValidLightmapSize(size)) {
    return r->ErrorFor("lightmap_size",
                       "must be " + LightmapSizeRange() + ", got " + std::to_string(size));
  }
  RADFARM_RETURN_IF_ERROR(
      r->Real("lightmap_texel", Interval::Above(0), &job->lightmap_texel, &has_texel));
  if (has_texel && has_size && size > 0) {
    return r->ErrorFor("lightmap_texel",
                       "is set with 'output.lightmap_size'; set one or the other");
  }
  job->lightmap_size = static_cast<uint32_t>(size);
  return Ok{};
}

// One [[illuminance]] table: name, height and spacing are required.
Status ReadIlluminancePlane(TomlTableReader* r, const std::vector<IlluminancePlane>& earlier,
                            IlluminancePlane* plane) {
  bool has_name = false, has_height = false, has_spacing = false;
  RADFARM_RETURN_IF_ERROR(r->String("name", &plane->name, &has_name));
  RADFARM_RETURN_IF_ERROR(r->Real("height", Interval::AtLeast(0), &plane->height, &has_height));
  RADFARM_RETURN_IF_ERROR(r->Real("spacing", Interval::Above(0), &plane->spacing, &has_spacing));
  RADFARM_RETURN_IF_ERROR(r->Strings("surfaces", &plane->surfaces));
  for (const auto& [key, given] :
       {std::pair{"name", has_name}, {"height", has_height}, {"spacing", has_spacing}}) {
    if (!given) return r->ErrorFor(key, "is missing (name, height and spacing are required)");
  }
  // The problem's first word is the key it is about ("name must be ...").
  const std::string problem = IlluminancePlaneProblem(*plane);
  if (!problem.empty()) {
    const size_t space = problem.find(' ');
    return r->ErrorFor(problem.substr(0, space), problem.substr(space + 1));
  }
  for (const IlluminancePlane& other : earlier) {
    if (other.name == plane->name) return r->ErrorFor("name", "repeats an earlier plane's name");
  }
  return r->CheckNoUnknownKeys();
}

Status ReadIlluminance(const std::string& path, TomlTableReader* root, Job* job) {
  Result<std::vector<const toml::table*>> tables = root->Tables("illuminance");
  RADFARM_RETURN_IF_ERROR(tables);
  for (size_t i = 0; i < tables->size(); ++i) {
    TomlTableReader reader(path, *(*tables)[i], "illuminance[" + std::to_string(i) + "].");
    IlluminancePlane plane;
    RADFARM_RETURN_IF_ERROR(ReadIlluminancePlane(&reader, job->illuminance, &plane));
    job->illuminance.push_back(std::move(plane));
  }
  return Ok{};
}

// One [[lamps]] table: file and position are required.
Status ReadLamp(const std::string& path, const toml::table& table, TomlTableReader* r,
                JobLamp* lamp) {
  bool has_file = false, has_position = false;
  RADFARM_RETURN_IF_ERROR(r->String("file", &lamp->file, &has_file));
  RADFARM_RETURN_IF_ERROR(r->Vector("position", &lamp->position, &has_position));
  RADFARM_RETURN_IF_ERROR(r->Vector("aim", &lamp->aim));
  RADFARM_RETURN_IF_ERROR(r->Real("rotate", Interval::Any(), &lamp->rotate));
  RADFARM_RETURN_IF_ERROR(r->Real("multiplier", Interval::Above(0), &lamp->multiplier));
  for (const auto& [key, given] : {std::pair{"file", has_file}, {"position", has_position}}) {
    if (!given) return r->ErrorFor(key, "is missing (file and position are required)");
  }
  if (lamp->file.empty()) return r->ErrorFor("file", "must not be empty");
  if (!IsFinite(lamp->position)) return r->ErrorFor("position", "must be finite");
  const double length = Length(lamp->aim);
  if (!IsFinite(lamp->aim) || !(length > 0))
    return r->ErrorFor("aim", "must be finite and nonzero");
  lamp->aim = lamp->aim / length;
  lamp->location = path + ":" + std::to_string(table.at("file").source().begin.line) + ": '" +
                   r->DottedKey("file") + "'";
  return r->CheckNoUnknownKeys();
}

Status ReadLamps(const std::string& path, TomlTableReader* root, Job* job) {
  Result<std::vector<const toml::table*>> tables = root->Tables("lamps");
  RADFARM_RETURN_IF_ERROR(tables);
  for (size_t i = 0; i < tables->size(); ++i) {
    TomlTableReader reader(path, *(*tables)[i], "lamps[" + std::to_string(i) + "].");
    JobLamp lamp;
    RADFARM_RETURN_IF_ERROR(ReadLamp(path, *(*tables)[i], &reader, &lamp));
    job->lamps.push_back(std::move(lamp));
  }
  return Ok{};
}

// [materials.NAME] tables, one per material named, each with its optional two_sided.
Status ReadMaterials(const std::string& path, TomlTableReader* materials, const toml::table& table,
                     Job* job) {
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    Result<const toml::table*> one = materials->Table(name);
    RADFARM_RETURN_IF_ERROR(one);
    TomlTableReader reader(path, **one, "materials." + name + ".");
    bool two_sided = false;
    RADFARM_RETURN_IF_ERROR(reader.Bool("two_sided", &two_sided));
    if ((*one)->contains("two_sided")) job->material_two_sided[name] = two_sided;
    RADFARM_RETURN_IF_ERROR(reader.CheckNoUnknownKeys());
  }
  return Ok{};
}

Status ReadJob(const std::string& path, const toml::table& table, Job* job) {
  TomlTableReader root(path, table, "");
  std::string scene;
  bool has_scene = false;
  RADFARM_RETURN_IF_ERROR(root.String("scene", &scene, &has_scene));
  if (!has_scene) return ErrorAt(path, 0, "missing key 'scene'");
  if (scene.empty()) return root.ErrorFor("scene", "must not be empty");
  job->scene_path = (std::filesystem::path(path).parent_path() / scene).string();
  RADFARM_RETURN_IF_ERROR(ReadSection(path, &root, "mesh", [&](TomlTableReader* r) {
    return ReadMesh(r, &job->mesh, &job->refine);
  }));
  RADFARM_RETURN_IF_ERROR(ReadSection(
      path, &root, "solver", [&](TomlTableReader* r) { return ReadSolver(r, &job->solver); }));
  RADFARM_RETURN_IF_ERROR(root.Bool("two_sided", &job->two_sided));
  std::string from;
  bool has_from = false;
  RADFARM_RETURN_IF_ERROR(root.String("from", &from, &has_from));
  if (has_from && from.empty()) return root.ErrorFor("from", "must not be empty");
  if (has_from) job->from = (std::filesystem::path(path).parent_path() / from).string();
  RADFARM_RETURN_IF_ERROR(ReadSection(path, &root, "camera", [&](TomlTableReader* r) -> Status {
    RADFARM_RETURN_IF_ERROR(r->String("name", &job->camera_name));
    return ReadCamera(r, job);
  }));
  RADFARM_RETURN_IF_ERROR(
      ReadSection(path, &root, "output", [&](TomlTableReader* r) { return ReadOutput(r, job); }));
  RADFARM_RETURN_IF_ERROR(ReadIlluminance(path, &root, job));
  RADFARM_RETURN_IF_ERROR(ReadLamps(path, &root, job));
  RADFARM_RETURN_IF_ERROR(
      ReadSection(path, &root, "sky", [&](TomlTableReader* r) { return ReadSky(r, &job->sky); }));
  Result<const toml::table*> materials = root.Table("materials");
  RADFARM_RETURN_IF_ERROR(materials);
  if (*materials != nullptr) {
    TomlTableReader reader(path, **materials, "materials.");
    RADFARM_RETURN_IF_ERROR(ReadMaterials(path, &reader, **materials, job));
  }
  return root.CheckNoUnknownKeys();
}

Result<Job> LoadTomlJob(const std::string& path) {
  Result<toml::table> table = ReadTomlFile(path);
  RADFARM_RETURN_IF_ERROR(table);
  Job job;
  RADFARM_RETURN_IF_ERROR(ReadJob(path, *table, &job));
  return job;
}

}  // namespace

Result<Job> LoadJob(const std::string& path) {
  const std::string ext = LowercaseExtension(path);
  if (ext == ".toml") return LoadTomlJob(path);
  if (ext == ".obj" || ext == ".gltf" || ext == ".glb") {
    Job job;
    job.scene_path = path;
    return job;
  }
  return ErrorAt(path, 0, "not a scene: expected a .obj, .gltf, .glb or a .toml job file");
}

}  // namespace radfarm
