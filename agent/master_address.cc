#include "agent/master_address.h"

#include <vector>

#include "agent/agent_settings.h"
#include "base/result.h"
#include "base/text_file.h"

namespace radfarm::agent {

Result<loop::HostPort> ReadMasterFile(const std::string& path) {
  Result<std::string> text = ReadTextFile(path);
  RADFARM_RETURN_IF_ERROR(text);
  const size_t first = text->find_first_not_of(" \t\r\n");
  const size_t last = text->find_last_not_of(" \t\r\n");
  const std::string line = first == std::string::npos ? "" : text->substr(first, last - first + 1);
  if (line.empty()) return Error{path + ": empty (the master has not written its address yet)"};
  return ParseMasterAddress(line, path);
}

Result<loop::SocketAddress> ResolveMaster(const loop::HostPort& master, uint32_t attempt) {
  Result<std::vector<loop::SocketAddress>> addresses = loop::Resolve(master, /*passive=*/false);
  RADFARM_RETURN_IF_ERROR(addresses);
  return (*addresses)[attempt % addresses->size()];
}

}  // namespace radfarm::agent
