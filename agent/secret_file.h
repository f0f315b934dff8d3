// Reads the farm secret from its key file (hex, as protocol/farm_secret.h reads it). Errors name
// the file and never quote its contents.
#pragma once

#include <string>

#include "base/result.h"
#include "protocol/farm_secret.h"

namespace radfarm::agent {

Result<protocol::FarmSecret> ReadSecretFile(const std::string& path);

}  // namespace radfarm::agent
