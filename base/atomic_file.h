// Atomic file replacement shared by every writer: the bytes go to a temporary file in the target's
// directory, are flushed to disk, and the temporary is renamed over the target. A reader (or a farm
// agent polling for results) therefore sees either the old file or the complete new one.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"
#include "base/unique_fd.h"

namespace radfarm {

// Writes `contents` to `path` atomically. Errors name `path` and the failing step; on error no
// temporary file is left behind and an existing file at `path` is untouched.
Status WriteFileAtomically(const std::string& path, std::string_view contents);

// WriteFileAtomically for files too large to build in memory first: Open, Append as often as
// needed (buffered), Commit. Destroyed without a successful Commit (an error, an early return), it
// removes its temporary and leaves `path` untouched. Move-only.
class AtomicFileWriter {
 public:
  // `mode`, less the umask, is the file's permissions (0600: its owner's alone, whatever the
  // umask).
  static Result<AtomicFileWriter> Open(const std::string& path, unsigned mode = 0666);
  AtomicFileWriter(AtomicFileWriter&& other) noexcept;
  AtomicFileWriter& operator=(AtomicFileWriter&&) = delete;
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  ~AtomicFileWriter();

  // Queues `bytes`, writing them out whenever the buffer is full. After an error every later call
  // fails with it.
  Status Append(std::string_view bytes);
  // What Append buffered, written to the temporary file (readable there, not yet on disk for
  // sure): a reader may then use the bytes before Commit makes them durable.
  Status Flush();
  // The rest written, flushed to disk and renamed over the target.
  Status Commit();

  const std::string& path() const { return path_; }
  // The temporary file the bytes go to until Commit; empty once committed.
  const std::string& temporary_path() const { return temporary_; }

 private:
  AtomicFileWriter(std::string path, std::string temporary, UniqueFd fd);

  std::string path_;
  std::string temporary_;  // empty once committed or moved from
  UniqueFd fd_;
  std::string buffer_;
  std::string error_;
};

// Whether a file name (without its directory) is one of WriteFileAtomically's temporaries
// ("NAME.tmp.PID.N"), e.g. left behind by a writer that crashed, for cleanups at start-up.
bool IsAtomicFileTemporary(std::string_view name);

}  // namespace radfarm
