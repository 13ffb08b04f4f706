#include "app/process/console.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gf::app {
namespace {

// True when standard output is a pipe or socket whose reader has closed it (poll reports an
// error on the write end then).
bool readerGone() {
  struct stat s {};
  if (fstat(STDOUT_FILENO, &s) != 0 || !(S_ISFIFO(s.st_mode) || S_ISSOCK(s.st_mode))) return false;
  pollfd p{STDOUT_FILENO, 0, 0};
  return poll(&p, 1, 0) == 1 && (p.revents & (POLLERR | POLLHUP)) != 0;
}

// errno values a write that failed on a file or device leaves (EPIPE is told by readerGone: an
// EPIPE left by another pipe, ffmpeg's, must not end the command quietly).
bool writeError(int e) { return e == ENOSPC || e == EIO || e == EFBIG || e == EDQUOT; }

}  // namespace

void flushOutput() {
  const int earlier = errno;  // what a write that failed since the last flush left, if nothing since
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int error = !flushed ? errno : writeError(earlier) ? earlier : 0;
  if (flushed && !std::ferror(stdout)) return;
  if (error == EPIPE || readerGone()) throw OutputClosed();
  std::clearerr(stdout);
  throw std::runtime_error(std::string("standard output: cannot write: ") +
                           (error != 0 ? std::strerror(error) : "a write failed"));
}

}  // namespace gf::app
