// Where to connect: the master's HOST:PORT as an address. An IP literal is used as it is; a host
// name is looked up (getaddrinfo, which BLOCKS: call it on a worker thread), and successive
// attempts go through the addresses it gives in turn.
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"
#include "loop/host_port.h"
#include "loop/socket_address.h"

namespace radfarm::agent {

// The master's HOST:PORT read from `path`, the master's listen.addr (radfarmd writes it once it
// listens, and writes a new one when it restarts on another port). One line, surrounding
// whitespace ignored. Errors name the file. BLOCKS (a file read): call it on a worker thread.
Result<loop::HostPort> ReadMasterFile(const std::string& path);

// The address for connection attempt `attempt` (0-based): address attempt % count of the lookup.
Result<loop::SocketAddress> ResolveMaster(const loop::HostPort& master, uint32_t attempt);

}  // namespace radfarm::agent
