// What the render thread asks of the process: its own nice value and the heap's settings.
#include "render/render_thread.hpp"

#include <cerrno>

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include "render/frames/frame_sinks.hpp"

namespace gf::render {

// Lowers the calling thread (only it: Linux keeps a nice value per thread) to nice
// kBackgroundNice, which any user may choose: the scheduler then gives a haptic loop at nice 0 about
// ten times its share and wakes it ahead of the renderer, yet the renderer still gets what the
// loop leaves (SCHED_IDLE got only that and starved frames). Threads and processes it starts
// afterwards inherit it. Raising it back needs privileges. Returns whether the thread now runs at
// kBackgroundNice or nicer.
bool lowerToNice() {
  const id_t self = static_cast<id_t>(gettid());
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, self);
  if (errno == 0 && now >= kBackgroundNice) return true;  // started nicer still (`nice -n 15`): kept
  return setpriority(PRIO_PROCESS, self, kBackgroundNice) == 0;
}

namespace {
// Mesa's draw module allocates and frees vertex buffers at every draw call. With glibc's
// defaults the render thread's heap was given back to the system (madvise) after the frees and
// faulted in again at the next frame: 4-5 ms of CPU per 1280x720 Fig. 8 frame (perf: page
// faults, sysmalloc and madvise on the render thread). Keeping up to kKeptFreeBytes of freed
// memory per heap, and taking blocks under kHeapBlockBytes (frames included) from the heap
// rather than from mmap, ends most of that. The rest came from the threads' own arenas: glibc
// unmaps a thread arena's whole heap when it empties, whatever the trim threshold, and the render
// thread's and llvmpipe's heaps emptied and filled at every frame (about 6 600 page faults a
// second in a 1280x720 realtime run). One arena for the process keeps them (see the header).
constexpr int kKeptFreeBytes = 256 << 20, kHeapBlockBytes = 32 << 20;
}  // namespace

void keepFreedMemory() {
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_TRIM_THRESHOLD, kKeptFreeBytes);
  mallopt(M_MMAP_THRESHOLD, kHeapBlockBytes);
}

}  // namespace gf::render
