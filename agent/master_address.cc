#include "agent/master_address.h"

#include <vector>

namespace radfarm::agent {

Result<loop::SocketAddress> ResolveMaster(const loop::HostPort& master, uint32_t attempt) {
  Result<std::vector<loop::SocketAddress>> addresses = loop::Resolve(master, /*passive=*/false);
  if (!addresses) return Error{addresses.error()};
  return (*addresses)[attempt % addresses->size()];
}

}  // namespace radfarm::agent
