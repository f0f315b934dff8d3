// One size of scaling_bench: the procedural building written by `radfarm building`, solved by
// `radfarm render` and by a loopback farm (radfarmd and agents of one thread each) to the same ray
// budget, timed end to end and measured for peak memory.
#pragma once

#include <cstdint>
#include <string>

namespace radfarm::bench {

struct BuildingJob {
  std::string rooms;  // AxB, as `radfarm building --rooms`
  std::string toml;   // the job file written
  uint64_t rays = 0;  // the budget both runs get (--rays)
};

// Writes the building with the automatic patch size into `dir` and returns its job.
BuildingJob WriteBuildingJob(const std::string& rooms, uint64_t rays_per_room,
                             const std::string& dir);

struct RenderFigures {
  uint64_t patches = 0;
  uint64_t rays = 0;
  double wall_seconds = 0;     // the process, start to exit
  double mesh_seconds = 0;     // reading and meshing ("read and meshed in" of its output)
  double solve_seconds = 0;    // stats.json: the direct light and the rounds
  double display_seconds = 0;  // stats.json: the display mesh's light
  double rays_per_second = 0;  // stats.json
  uint64_t peak_rss_bytes = 0;
  std::string patches_csv;  // path of its patches.csv
};

RenderFigures MeasureRender(const BuildingJob& job, const std::string& dir);

struct FarmFigures {
  double job_seconds = 0;      // from the submission to the job done, as the master reports it
  double solve_seconds = 0;    // stats.json: the rounds
  double rays_per_second = 0;  // stats.json
  uint64_t master_peak_rss_bytes = 0;
  uint64_t agent_peak_rss_bytes = 0;  // the largest of the agents'
  bool same_as_render = false;        // patches.csv byte for byte
  // The slowest agent's start on the job, from its first lease frame (agent debug log): its
  // scene ready, and its first LeaseResult sent; -1 when its log lacks the lines.
  double agent_scene_ready_seconds = -1;
  double agent_first_result_seconds = -1;
};

// An agent's start on its first job, from its log at debug level: seconds from the first lease
// frame received to the first "ready" scene and to the first results sent (-1 when absent).
struct AgentStart {
  double scene_ready_seconds = -1;
  double first_result_seconds = -1;
};
AgentStart ReadAgentStart(const std::string& log_text);

FarmFigures MeasureFarm(const BuildingJob& job, unsigned agents, const RenderFigures& render,
                        const std::string& dir);

}  // namespace radfarm::bench
