// UnixListener: a listening Unix stream socket, for the daemon's control socket. Accepted
// connections arrive as FramedConnections, as with TcpListener. Loop thread only.
//
// Permissions: the socket file is made owner-only (0600) after bind() and before listen(). The
// file briefly exists with the umask's mode, but until listen() every connect() is refused, and
// Linux checks the file's mode at connect(), so no peer ever gets in through the wider mode. The
// umask is not touched: it is process-wide, and worker threads may be creating files meanwhile.
// Put the socket in a directory only the daemon's user can write (the STATE directory), so nobody
// can swap the file between bind and chmod; Listen checks the result (a socket, ours, 0600).
//
// A socket file left by a crashed daemon is removed if nothing answers on it; if something does,
// Listen fails ("another process is listening"). Close() unlinks the file if it is still ours.
#pragma once

#include <sys/types.h>

#include <functional>
#include <memory>
#include <string>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/handle_block.h"

namespace radfarm::loop {

namespace internal {
struct ListenBlock;
}

class UnixListener {
 public:
  using OnConnection = std::function<void(std::unique_ptr<FramedConnection>)>;

  static Result<std::unique_ptr<UnixListener>> Listen(EventLoop& loop, const std::string& path,
                                                      OnConnection on_connection);
  UnixListener(const UnixListener&) = delete;
  UnixListener& operator=(const UnixListener&) = delete;

  const std::string& path() const { return path_; }

  void Close();  // also unlinks the socket file
  HandleState state() const;

 private:
  UnixListener() = default;
  internal::BlockRef<internal::ListenBlock> block_;
  std::string path_;
};

}  // namespace radfarm::loop
