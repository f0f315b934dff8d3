#include "idle/logind_user_idle.h"

#include <systemd/sd-bus.h>

#include <cstring>
#include <ctime>

namespace radfarm::idle {
namespace {

constexpr const char* kService = "org.freedesktop.login1";
constexpr const char* kPath = "/org/freedesktop/login1";
constexpr const char* kInterface = "org.freedesktop.login1.Manager";
constexpr uint64_t kCallTimeoutUsec = 250'000;

// Frees an sd_bus_error's strings at scope exit.
class BusError {
 public:
  BusError() = default;
  ~BusError() { sd_bus_error_free(&error_); }
  BusError(const BusError&) = delete;
  BusError& operator=(const BusError&) = delete;

  sd_bus_error* get() { return &error_; }
  std::string Describe(int result) const {
    if (sd_bus_error_is_set(&error_)) return std::string(error_.name) + ": " + error_.message;
    return std::strerror(-result);
  }

 private:
  sd_bus_error error_ = SD_BUS_ERROR_NULL;
};

uint64_t MonotonicUsec() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<uint64_t>(now.tv_sec) * 1'000'000 + static_cast<uint64_t>(now.tv_nsec) / 1000;
}

UserIdle Unknown(std::string detail) {
  return UserIdle{UserIdle::State::kUnknown, std::chrono::seconds(0), std::move(detail)};
}

}  // namespace

void BusCloser::operator()(sd_bus* bus) const { sd_bus_flush_close_unref(bus); }

Result<BusPtr> ConnectSystemBus() {
  sd_bus* raw = nullptr;
  const int opened = sd_bus_open_system(&raw);
  if (opened < 0) {
    return Error{std::string("cannot connect to the system D-Bus: ") + std::strerror(-opened)};
  }
  return BusPtr(raw);
}

LogindUserIdle::LogindUserIdle(BusConnector connect) : connect_(std::move(connect)) {}

LogindUserIdle::~LogindUserIdle() = default;

UserIdle LogindUserIdle::Read() {
  if (bus_ && sd_bus_is_open(bus_.get()) <= 0) bus_.reset();
  if (!bus_) {
    Result<BusPtr> bus = connect_();
    if (!bus) return Unknown(bus.error());
    bus_ = std::move(bus).value();
    sd_bus_set_method_call_timeout(bus_.get(), kCallTimeoutUsec);
  }

  BusError hint_error;
  int hint = 0;
  int got = sd_bus_get_property_trivial(bus_.get(), kService, kPath, kInterface, "IdleHint",
                                        hint_error.get(), 'b', &hint);
  if (got < 0) {
    bus_.reset();  // reconnect next time: logind may be starting, or the bus restarted
    return Unknown("logind IdleHint: " + hint_error.Describe(got));
  }
  BusError since_error;
  uint64_t since_usec = 0;
  got = sd_bus_get_property_trivial(bus_.get(), kService, kPath, kInterface,
                                    "IdleSinceHintMonotonic", since_error.get(), 't', &since_usec);
  if (got < 0) {
    bus_.reset();
    return Unknown("logind IdleSinceHintMonotonic: " + since_error.Describe(got));
  }

  if (!hint) return UserIdle{UserIdle::State::kActive, std::chrono::seconds(0), "logind"};
  const uint64_t now = MonotonicUsec();
  const uint64_t idle_usec = now > since_usec ? now - since_usec : 0;
  return UserIdle{UserIdle::State::kIdle,
                  std::chrono::seconds(static_cast<int64_t>(idle_usec / 1'000'000)), "logind"};
}

}  // namespace radfarm::idle
