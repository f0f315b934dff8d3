// What the batch-system tests (slurm_agents_test.cc, htcondor_agents_test.cc) share: the agent
// config that the shipped examples document in their comments, made to point at a test farm, and
// the comparison of a farm job's files with `radfarm render`'s.
#pragma once

#include <string>

namespace radfarm::packaging::testing {

// The example config in `example_text`'s comments (the "#   " block that begins with
// `master = `), with its master and secret_file values replaced; "" if there is no such block.
std::string ExampleAgentConfig(const std::string& example_text, const std::string& master,
                               const std::string& secret_file);

// Writes `text` to `path`, readable by its owner only; false on failure.
bool WritePrivateFile(const std::string& path, const std::string& text);

// The output files of `radfarm fetch` in `fetched` that differ from those of `radfarm render` in
// `rendered` (patches.csv, radiosity.ply, image.png, image.exr), comma-separated; "" when all
// are byte-identical.
std::string DifferingOutputs(const std::string& fetched, const std::string& rendered);

}  // namespace radfarm::packaging::testing
