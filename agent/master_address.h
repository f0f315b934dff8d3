// Where to connect: the master's HOST:PORT as an address. An IP literal is used as it is; a host
// name is looked up (getaddrinfo, which BLOCKS: call it on a worker thread), and successive
// attempts go through the addresses it gives in turn.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "loop/host_port.h"
#include "loop/socket_address.h"

namespace radfarm::agent {

// The address for connection attempt `attempt` (0-based): address attempt % count of the lookup.
Result<loop::SocketAddress> ResolveMaster(const loop::HostPort& master, uint32_t attempt);

}  // namespace radfarm::agent
