// LogindUserIdle: the users' idle time from systemd-logind over D-Bus: the Manager's IdleHint and
// IdleSinceHintMonotonic properties (org.freedesktop.login1), which logind computes over every
// session: the machine is idle when every session is (a desktop session reports idle after its
// own idle delay, e.g. GNOME's screen blank; a text or SSH session after its terminal's last
// input). With no session at all, logind reports idle since boot.
//
// Each Read() asks logind with a 250 ms timeout. Without a system bus or logind (containers, some
// batch nodes) it returns kUnknown with the reason and tries to connect again on the next Read().
#pragma once

#include <functional>
#include <memory>

#include "base/result.h"
#include "idle/user_idle.h"

typedef struct sd_bus sd_bus;

namespace radfarm::idle {

// Owns one sd_bus connection (flushed, closed and unreferenced on destruction).
struct BusCloser {
  void operator()(sd_bus* bus) const;
};
using BusPtr = std::unique_ptr<sd_bus, BusCloser>;

// Opens the bus to ask. The default is the system bus (sd_bus_open_system).
using BusConnector = std::function<Result<BusPtr>()>;
Result<BusPtr> ConnectSystemBus();

class LogindUserIdle : public UserIdleSource {
 public:
  explicit LogindUserIdle(BusConnector connect = ConnectSystemBus);
  ~LogindUserIdle() override;

  UserIdle Read() override;

 private:
  BusConnector connect_;
  BusPtr bus_;
};

}  // namespace radfarm::idle
