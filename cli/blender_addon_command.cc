#include "cli/blender_addon_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include "cli/exit_codes.h"
#include "cli/messages.h"

namespace radfarm {
namespace {

namespace fs = std::filesystem;

// Blender's version folder: the add-on is written for Debian 12's Blender 3.4.
constexpr char kBlenderVersion[] = "3.4";

Error FsError(const std::string& what, const std::error_code& error) {
  return Error{what + ": " + error.message()};
}

// A name beside `target` no other install uses at the same time.
fs::path Beside(const fs::path& target, const std::string& what) {
  return target.parent_path() /
         ("." + target.filename().string() + "." + what + "-" + std::to_string(::getpid()));
}

Status CopyFiles(const fs::path& source, const fs::path& target, const std::string& program) {
  std::error_code error;
  fs::create_directory(target, error);
  if (error) return FsError(target.string() + ": cannot create the folder", error);
  for (const fs::directory_entry& entry : fs::directory_iterator(source, error)) {
    // The add-on's modules only: not Python's caches, not a program file from elsewhere.
    if (!entry.is_regular_file() || entry.path().extension() != ".py") continue;
    fs::copy_file(entry.path(), target / entry.path().filename(), error);
    if (error) return FsError(entry.path().string() + ": cannot copy", error);
  }
  if (error) return FsError(source.string() + ": cannot read the folder", error);
  std::ofstream file(target / kAddonProgramFile);
  file << program << "\n";
  file.close();
  if (!file) return Error{(target / kAddonProgramFile).string() + ": cannot write"};
  return Ok{};
}

std::optional<std::string> GetEnv(const std::string& name) {
  const char* value = std::getenv(name.c_str());
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::string(value);
}

}  // namespace

Result<fs::path> PackagedAddon(const fs::path& executable) {
  const fs::path folder =
      executable.parent_path().parent_path() / "share" / "radfarm" / "blender" / kAddonName;
  std::error_code error;
  if (!fs::is_regular_file(folder / "__init__.py", error)) {
    return Error{"the Blender add-on is not installed beside " + executable.string() + ": no " +
                 (folder / "__init__.py").lexically_normal().string()};
  }
  return folder.lexically_normal();
}

Result<fs::path> DefaultAddonsDir(const EnvLookup& getenv) {
  if (std::optional<std::string> scripts = getenv("BLENDER_USER_SCRIPTS")) {
    return fs::path(*scripts) / "addons";
  }
  fs::path config;
  if (std::optional<std::string> xdg = getenv("XDG_CONFIG_HOME")) {
    config = *xdg;
  } else if (std::optional<std::string> home = getenv("HOME")) {
    config = fs::path(*home) / ".config";
  } else {
    return Error{
        "neither HOME nor XDG_CONFIG_HOME is set: give the add-ons folder with "
        "--addons-dir"};
  }
  return config / "blender" / kBlenderVersion / "scripts" / "addons";
}

Status InstallAddon(const fs::path& source, const fs::path& addons_dir,
                    const std::string& program) {
  std::error_code error;
  fs::create_directories(addons_dir, error);
  if (error) return FsError(addons_dir.string() + ": cannot create the folder", error);
  const fs::path target = addons_dir / kAddonName;
  const fs::path fresh = Beside(target, "new");
  const fs::path old = Beside(target, "old");
  fs::remove_all(fresh, error);
  if (Status copied = CopyFiles(source, fresh, program); !copied) {
    fs::remove_all(fresh, error);
    return copied;
  }
  // An earlier install steps aside, the new one takes its name, then the old one goes.
  const bool had_one = fs::exists(target, error);
  if (had_one) {
    fs::rename(target, old, error);
    if (error) {
      fs::remove_all(fresh, error);
      return FsError(target.string() + ": cannot replace the add-on there", error);
    }
  }
  fs::rename(fresh, target, error);
  if (error) {
    const Error failed = FsError(target.string() + ": cannot install", error);
    if (had_one) fs::rename(old, target, error);
    fs::remove_all(fresh, error);
    return failed;
  }
  if (had_one) fs::remove_all(old, error);
  return Ok{};
}

CLI::App* AddBlenderAddonCommand(CLI::App& app, BlenderAddonOptions* options) {
  CLI::App* addon = app.add_subcommand("blender-addon", "The Blender add-on radfarm Bake");
  addon->require_subcommand(1);
  CLI::App* install = addon->add_subcommand(
      "install",
      "Copy the Blender add-on radfarm Bake into Blender 3.4's add-ons folder (then enable it in "
      "Blender: Edit > Preferences > Add-ons, radfarm Bake); it runs this radfarm");
  install->add_option("--addons-dir", options->addons_dir,
                      "Blender's add-ons folder (default: $BLENDER_USER_SCRIPTS/addons if set, "
                      "else ~/.config/blender/3.4/scripts/addons)");
  install->add_flag("--print-path", options->print_path,
                    "Print the packaged add-on's folder and install nothing (to copy it by hand)");
  return install;
}

int RunBlenderAddonInstall(const BlenderAddonOptions& options) {
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (error) {
    PrintError("cannot find this program's own path: " + error.message());
    return kExitFailure;
  }
  Result<fs::path> source = PackagedAddon(executable);
  if (!source.ok()) {
    PrintError(source.error());
    return kExitFailure;
  }
  if (options.print_path) {
    std::printf("%s\n", source->c_str());
    return kExitOk;
  }
  Result<fs::path> addons =
      options.addons_dir.empty() ? DefaultAddonsDir(GetEnv) : fs::path(options.addons_dir);
  if (!addons.ok()) {
    PrintError(addons.error());
    return kExitBadInput;
  }
  if (Status installed = InstallAddon(*source, *addons, executable.string()); !installed) {
    PrintError(installed.error());
    return kExitFailure;
  }
  std::printf(
      "installed radfarm Bake in %s\nenable it in Blender: Edit > Preferences > Add-ons, search "
      "\"radfarm\"; its panel is the radfarm tab of the 3D view's sidebar (N)\n",
      (*addons / kAddonName).c_str());
  return kExitOk;
}

}  // namespace radfarm
