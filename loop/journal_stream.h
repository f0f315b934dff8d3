// Whether a file descriptor writes into systemd-journald. systemd sets $JOURNAL_STREAM to
// "DEVICE:INODE" of the stream it connects a service's stdout/stderr to (systemd.exec(5)); the
// variable alone proves nothing, since children inherit it after redirecting stderr to a file, so
// the descriptor's own device and inode must match. journald reads a leading "<N>" on each line
// of such a stream as the line's syslog priority (sd-daemon(3)), which `journalctl -p` filters on.
#pragma once

namespace radfarm::loop {

// True when `journal_stream` (the value of $JOURNAL_STREAM, or null when unset) names the device
// and inode of `fd`. False for a malformed value or a descriptor fstat cannot read.
bool FdIsJournalStream(int fd, const char* journal_stream);

}  // namespace radfarm::loop
