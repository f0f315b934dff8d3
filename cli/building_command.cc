#include "cli/building_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/messages.h"
#include "cli/option_checks.h"
#include "scenegen/building.h"
#include "scenegen/obj_writer.h"
#include "scenegen/room_layout.h"

namespace radfarm {

CLI::App* AddBuildingCommand(CLI::App& app, BuildingOptions* options) {
  CLI::App* command = app.add_subcommand(
      "building",
      "Write a procedural office building (storeys of rooms with doors, furniture, ceiling "
      "lights; closed) as OUT/NAME.obj, .mtl and a .toml job to render or submit");
  command->add_option("--out", options->out, "Directory to write the scene to")->required();
  command->add_option("--name", options->name, "File name stem (default: building)")
      ->check([](const std::string& s) {
        return s.empty() || s.find('/') != std::string::npos || s[0] == '.'
                   ? std::string("'" + s + "' is not a plain file name")
                   : std::string();
      });
  command->add_option("--floors", options->floors, "Storeys (default: 1)")
      ->check(PositiveInteger());
  command->add_option("--rooms", options->rooms,
                      "Rooms per storey along x and z, as AxB (default: 2x2)");
  command->add_option("--room-size", options->room_size,
                      "Inside size of a room in metres, as WxD or one number (default: 4x4)");
  command->add_option("--height", options->height, "Room height in metres (default: 3)")
      ->check(PositiveReal());
  command->add_option("--seed", options->seed, "Seed of the furniture and door jitter (default: 1)")
      ->check(UnsignedInteger());
  command->add_option("--lights", options->lights,
                      "Ceiling panels per room along x and z, as AxB (default: 2x1)");
  command->add_flag("--windows", options->windows, "A daylight panel on every outer wall");
  command->add_flag("--no-furniture", options->no_furniture,
                    "Only walls, floors, ceilings, lights");
  command
      ->add_option("--patch-size", options->patch_size,
                   "Patch size the job file asks for, in metres; 0: automatic (default: 0.25)")
      ->check(RealInRange(0, 1e6));
  command
      ->add_option("--refine-tolerance", options->refine_tolerance,
                   "Adaptive refinement tolerance the job file asks for (the relative error "
                   "that splits an element); 0: a uniform mesh, no refinement (default: 0.05)")
      ->check(RealInRange(0, 1e6));
  return command;
}

int RunBuilding(const BuildingOptions& options) {
  scenegen::BuildingParams params;
  params.floors = options.floors;
  params.room_height = options.height;
  params.seed = options.seed;
  params.windows = options.windows;
  const Result<std::pair<int, int>> rooms = scenegen::ParseRoomCounts(options.rooms);
  if (!rooms.ok()) {
    PrintError("building: " + rooms.error());
    return kExitBadInput;
  }
  params.rooms_x = rooms->first;
  params.rooms_z = rooms->second;
  const Result<std::pair<int, int>> lights = scenegen::ParseLightCounts(options.lights);
  if (!lights.ok()) {
    PrintError("building: " + lights.error());
    return kExitBadInput;
  }
  params.lights_x = lights->first;
  params.lights_z = lights->second;
  const Result<std::pair<double, double>> size = scenegen::ParseRoomSize(options.room_size);
  if (!size.ok()) {
    PrintError("building: " + size.error());
    return kExitBadInput;
  }
  params.room_width = size->first;
  params.room_depth = size->second;

  Result<scenegen::SceneModel> model = scenegen::GenerateBuilding(params, !options.no_furniture);
  if (!model.ok()) {
    PrintError("building: " + model.error());
    return kExitBadInput;
  }
  const scenegen::RoomView view = scenegen::FirstRoomView(params);
  scenegen::JobFileSettings job;
  job.patch_size = options.patch_size;
  job.refine_tolerance = options.refine_tolerance;
  job.eye = view.eye;
  job.target = view.target;
  const Result<std::string> written = scenegen::WriteScene(*model, options.out, options.name, job);
  if (!written.ok()) {
    PrintError(written.error());
    return kExitFailure;
  }
  const scenegen::BuildingCounts counts = scenegen::CountBuilding(params);
  std::printf("wrote %s (rooms %lld, doors %lld, lights %lld, faces %zu)\n", written->c_str(),
              static_cast<long long>(counts.rooms), static_cast<long long>(counts.doors),
              static_cast<long long>(counts.lights), model->faces().size());
  return kExitOk;
}

}  // namespace radfarm
