#include "fake_logind.h"

#include <sys/socket.h>
#include <systemd/sd-bus.h>
#include <unistd.h>

#include <cstring>
#include <ctime>
#include <string>

namespace radfarm::idle::testing {
namespace {

int GetIdleHint(sd_bus*, const char*, const char*, const char*, sd_bus_message* reply,
                void* userdata, sd_bus_error*) {
  const auto* fake = static_cast<FakeLogind*>(userdata);
  return sd_bus_message_append(reply, "b", static_cast<int>(fake->idle_hint.load()));
}

int GetIdleSince(sd_bus*, const char*, const char*, const char*, sd_bus_message* reply,
                 void* userdata, sd_bus_error*) {
  const auto* fake = static_cast<FakeLogind*>(userdata);
  return sd_bus_message_append(reply, "t", fake->idle_since_usec.load());
}

const sd_bus_vtable kManagerVtable[] = {
    SD_BUS_VTABLE_START(0),
    SD_BUS_PROPERTY("IdleHint", "b", GetIdleHint, 0, 0),
    SD_BUS_PROPERTY("IdleSinceHintMonotonic", "t", GetIdleSince, 0, 0),
    SD_BUS_VTABLE_END,
};

}  // namespace

uint64_t MonotonicNowUsec() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<uint64_t>(now.tv_sec) * 1'000'000 + static_cast<uint64_t>(now.tv_nsec) / 1000;
}

FakeLogind::~FakeLogind() {
  stop_ = true;
  std::lock_guard lock(mutex_);
  for (std::thread& thread : threads_) thread.join();
}

void FakeLogind::Set(bool hint, uint64_t since_usec) {
  idle_hint = hint;
  idle_since_usec = since_usec;
}

BusConnector FakeLogind::Connector() {
  return [this]() -> Result<BusPtr> {
    int fds[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
      return Error{std::string("socketpair: ") + std::strerror(errno)};
    }
    {
      std::lock_guard lock(mutex_);
      threads_.emplace_back([this, fd = fds[0]] { Serve(fd); });
    }
    sd_bus* raw = nullptr;
    int r = sd_bus_new(&raw);
    if (r < 0) {
      close(fds[1]);
      return Error{std::string("sd_bus_new: ") + std::strerror(-r)};
    }
    BusPtr client(raw);
    r = sd_bus_set_fd(client.get(), fds[1], fds[1]);
    if (r < 0) {
      close(fds[1]);
      return Error{std::string("sd_bus_set_fd: ") + std::strerror(-r)};
    }
    r = sd_bus_start(client.get());
    if (r < 0) return Error{std::string("sd_bus_start: ") + std::strerror(-r)};
    ++connections_;
    return client;
  };
}

void FakeLogind::Serve(int fd) {
  sd_bus* raw = nullptr;
  if (sd_bus_new(&raw) < 0) {
    close(fd);
    return;
  }
  BusPtr server(raw);
  sd_id128_t id;
  sd_id128_randomize(&id);
  if (sd_bus_set_fd(server.get(), fd, fd) < 0 || sd_bus_set_server(server.get(), 1, id) < 0) {
    return;
  }
  if (serve_manager &&
      sd_bus_add_object_vtable(server.get(), nullptr, "/org/freedesktop/login1",
                               "org.freedesktop.login1.Manager", kManagerVtable, this) < 0) {
    return;
  }
  if (sd_bus_start(server.get()) < 0) return;
  while (!stop_) {
    const int processed = sd_bus_process(server.get(), nullptr);
    if (processed < 0) return;  // the client hung up
    if (processed > 0) continue;
    // Wakes for the next message, or after 50 ms to see `stop_`.
    if (sd_bus_wait(server.get(), 50'000) < 0) return;
  }
}

}  // namespace radfarm::idle::testing
