#include "agent/master_address.h"

#include <vector>

#include "base/result.h"

namespace radfarm::agent {

Result<loop::SocketAddress> ResolveMaster(const loop::HostPort& master, uint32_t attempt) {
  Result<std::vector<loop::SocketAddress>> addresses = loop::Resolve(master, /*passive=*/false);
  RADFARM_RETURN_IF_ERROR(addresses);
  return (*addresses)[attempt % addresses->size()];
}

}  // namespace radfarm::agent
