// `radfarm secret new FILE|-`: a fresh farm secret (the handshake's HMAC key, protocol/
// farm_secret.h) as hex. To a file: mode 0600, written to a temporary name first, and an existing
// file is never replaced without --force. `-` prints it on stdout.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct SecretOptions {
  std::string file;  // "-": stdout
  bool force = false;
};

// Adds `secret` and its subcommand `new`; returns `new`.
CLI::App* AddSecretCommand(CLI::App& app, SecretOptions* options);
int RunSecretNew(const SecretOptions& options);

// Writes `text` (a key's hex) to `file` as `secret new` does (mode 0600, atomically, missing
// folders 0700, never over an existing file without `force`); errors are printed. Returns the
// exit code. Also writes `agents enroll`'s key files.
int WriteSecretFile(const std::string& file, const std::string& text, bool force);

}  // namespace radfarm
