#include "cli/secret_command.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "base/unique_fd.h"
#include "cli/exit_codes.h"
#include "cli/messages.h"
#include "protocol/farm_secret.h"

namespace radfarm {
namespace {

// A temporary file beside the target, removed when destroyed unless Forget() is called.
class TempFile {
 public:
  explicit TempFile(const std::string& target) {
    const std::filesystem::path p(target);
    path_ = (p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path()) /
            ("." + p.filename().string() + ".XXXXXX");
    fd_ = UniqueFd(mkstemp(path_.data()));  // mode 0600 whatever the umask
    if (!fd_.valid()) path_.clear();
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  int fd() const { return fd_.get(); }
  const std::string& path() const { return path_; }
  void CloseFd() { fd_.Reset(); }
  // The file now has another name (renamed): nothing to remove.
  void Forget() { path_.clear(); }

 private:
  std::string path_;
  UniqueFd fd_;
};

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

// Creates the missing folders above `file`, each with mode 0700 (only its owner may look inside
// a folder that holds a secret); folders that exist are left as they are.
Status CreateMissingParents(const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::filesystem::path path;
  for (const std::filesystem::path& part : parent) {
    path /= part;
    if (::mkdir(path.c_str(), 0700) != 0 && errno != EEXIST) {
      return Error{Errno(path.string() + ": cannot create the folder")};
    }
  }
  return Ok{};
}

}  // namespace

int WriteSecretFile(const std::string& file, const std::string& text, bool force) {
  if (Status s = CreateMissingParents(file); !s) {
    PrintError(s.error());
    return kExitFailure;
  }
  TempFile temp(file);
  if (temp.fd() < 0) {
    PrintError(Errno(file + ": cannot create a temporary file beside it"));
    return kExitFailure;
  }
  const bool written = ::fchmod(temp.fd(), 0600) == 0 &&
                       ::write(temp.fd(), text.data(), text.size()) == ssize_t(text.size()) &&
                       ::fsync(temp.fd()) == 0;
  if (!written) {
    PrintError(Errno(temp.path() + ": cannot write"));
    return kExitFailure;
  }
  temp.CloseFd();
  // rename replaces the file; link refuses an existing one, atomically.
  if (force && ::rename(temp.path().c_str(), file.c_str()) == 0) {
    temp.Forget();
    return kExitOk;
  }
  if (!force && ::link(temp.path().c_str(), file.c_str()) == 0) return kExitOk;
  if (!force && errno == EEXIST) {
    PrintError(file + ": already exists; pass --force to replace it");
    return kExitBadInput;
  }
  PrintError(Errno(file));
  return kExitFailure;
}

CLI::App* AddSecretCommand(CLI::App& app, SecretOptions* options) {
  CLI::App* secret = app.add_subcommand("secret", "Manage the farm secret (the handshake's key)");
  secret->require_subcommand(1);
  CLI::App* create = secret->add_subcommand(
      "new",
      "Write a fresh farm secret as hex to FILE (mode 0600; missing folders above it are made "
      "with mode 0700), or to stdout with -");
  create->add_option("FILE", options->file, "Key file to create, or - for stdout")->required();
  create->add_flag("--force,-f", options->force, "Replace FILE if it exists");
  return create;
}

int RunSecretNew(const SecretOptions& options) {
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::Generate();
  if (!secret.ok()) {
    PrintError(secret.error());
    return kExitFailure;
  }
  std::string text = secret->ToHex() + "\n";
  int code;
  if (options.file == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    code = std::fflush(stdout) == 0 ? kExitOk : kExitFailure;
  } else {
    code = WriteSecretFile(options.file, text, options.force);
    if (code == kExitOk) std::printf("wrote a new farm secret to %s\n", options.file.c_str());
  }
  explicit_bzero(text.data(), text.size());  // FarmSecret wipes its key; wipe the hex copy too
  return code;
}

}  // namespace radfarm
