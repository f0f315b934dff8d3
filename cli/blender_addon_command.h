// `radfarm blender-addon install [--addons-dir DIR] [--print-path]`: copies the Blender add-on
// radfarm Bake (blender/radfarm_bake, docs/USAGE.md "From Blender") into Blender's add-ons folder,
// with a file naming this radfarm program so the add-on runs the radfarm that installed it.
//
// The packaged add-on is found beside the program: PREFIX/bin/radfarm reads
// PREFIX/share/radfarm/blender/radfarm_bake (cmake --install, the .deb), and the build tree's
// build/cli/radfarm reads build/share/radfarm/blender/radfarm_bake (blender/CMakeLists.txt puts a
// copy there).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "base/result.h"

namespace CLI {
class App;
}

namespace radfarm {

struct BlenderAddonOptions {
  std::string addons_dir;  // empty: DefaultAddonsDir
  bool print_path = false;
};

inline constexpr char kAddonName[] = "radfarm_bake";
// The file in the installed add-on naming the radfarm program to run (blender/radfarm_bake/
// settings.py reads it).
inline constexpr char kAddonProgramFile[] = "radfarm_program";

// Adds `blender-addon` and its subcommand `install`; returns `install`.
CLI::App* AddBlenderAddonCommand(CLI::App& app, BlenderAddonOptions* options);
int RunBlenderAddonInstall(const BlenderAddonOptions& options);

// The packaged add-on's folder for the program at `executable`, or an error naming where it was
// looked for.
Result<std::filesystem::path> PackagedAddon(const std::filesystem::path& executable);

// Blender 3.4's user add-ons folder: $BLENDER_USER_SCRIPTS/addons when set (Blender reads its
// user scripts there), else $XDG_CONFIG_HOME (or $HOME/.config)/blender/3.4/scripts/addons.
// `getenv` looks variables up (nullopt: unset).
using EnvLookup = std::function<std::optional<std::string>(const std::string&)>;
Result<std::filesystem::path> DefaultAddonsDir(const EnvLookup& getenv);

// Copies the add-on folder `source` (its regular files) into `addons_dir`/radfarm_bake, with
// kAddonProgramFile holding `program`. The new copy is written beside the old under a temporary
// name and then takes its place, so Blender never sees half an add-on.
Status InstallAddon(const std::filesystem::path& source, const std::filesystem::path& addons_dir,
                    const std::string& program);

}  // namespace radfarm
