// What the commands print on standard output, checked: a line that cannot be written is an error,
// not something lost in silence; a reader that went away (`godfinger check ... | head`) ends the
// command quietly with the status a shell gives SIGPIPE, as other Unix tools do.
#pragma once

#include <stdexcept>

namespace gf::app {

/// Thrown by flushOutput when the reader of standard output has gone (a closed pipe).
class OutputClosed : public std::runtime_error {
 public:
  OutputClosed() : std::runtime_error("standard output: the reader has gone") {}
};

/// The exit status of a command whose standard output's reader went away: 128 + SIGPIPE.
inline constexpr int kOutputClosedStatus = 141;

/// Flushes standard output and checks every write to it since the last call. Throws
/// OutputClosed when its reader has gone (EPIPE), std::runtime_error naming the reason for any
/// other failure (a full disk, /dev/full). Any thread that prints; cheap when nothing is pending.
void flushOutput();

}  // namespace gf::app
