// The run folder: what `godfinger run` writes into its --out folder, by name, and the rules that
// keep it one run's: a lock held for the whole run, room checked and the folder proven writable
// before an earlier run's files are removed, and only a run's own kinds of file removed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace gf::app {

/// The files and folders of a run folder.
inline constexpr char kTraceFile[] = "trace.csv";        ///< one row per haptic step
inline constexpr char kSummaryFile[] = "summary.json";   ///< settings, counters, timings, expectations
inline constexpr char kForcesFile[] = "forces.csv";      ///< forces on the bodies of record.forces
inline constexpr char kForceChartFile[] = "forces.png";  ///< record.force_chart
inline constexpr char kRunLogFile[] = "run.log";         ///< a child run's output (check, study, compare)
inline constexpr char kContactsFolder[] = "contacts";    ///< contacts/t0.500.json and close-ups
inline constexpr char kFramesFolder[] = "frames";        ///< frames/000000.png ...
inline constexpr char kLockFile[] = ".godfinger.lock";   ///< the owner's lock, holding its pid

/// Where every command writes when it is given no --out: `out/` of the current folder.
inline constexpr char kDefaultOutRoot[] = "out";

/// The folder a command writes into without --out: "out/NAME" (run-SCENE, compare-SCENE,
/// study-NAME, check, live-SCENE, bench-realtime, screenshots), relative to the current folder,
/// never the source tree's or the data's.
std::string defaultOutFolder(const std::string& name);

/// The name stem of the contact snapshot at `t` seconds ("t0.500"): contacts/t0.500.json.
std::string contactStem(double t);

/// A folder one command owns while it writes into it: an advisory lock (flock) on its lock file,
/// taken before anything in it is touched and held until destruction. A second owner is refused
/// at once. The lock file stays (empty of meaning once unlocked). Owner thread only.
class RunFolder {
 public:
  /// Creates `dir` (and its parents) and takes the lock. Throws std::runtime_error naming the
  /// folder and, when another process holds it, that process's pid. On a file system that
  /// cannot lock files (ENOSYS, ENOLCK, EOPNOTSUPP: some network and FUSE file systems) it says
  /// so on stderr and goes on without the lock.
  explicit RunFolder(const std::filesystem::path& dir);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;
 private:
  int fd_ = -1;
};

/// Creates `folder` (and its parents) and proves a file can be written there by writing one
/// block (4 KiB) and removing it. Throws std::runtime_error naming the folder and `what` it is for.
void requireWritableFolder(const std::filesystem::path& folder, const std::string& what);

/// Throws std::runtime_error naming `folder`, `what` and both sizes when its file system has
/// fewer than `bytes` free for this user (statvfs; not checked where the file system gives no
/// figures).
void requireRoom(const std::filesystem::path& folder, std::uintmax_t bytes, const std::string& what);

/// Removes what an earlier run left in `dir` of the kinds of output a run writes (trace.csv,
/// forces.csv, forces.png, summary.json, the frame sequence, contact snapshots and close-ups,
/// and their temporary names), nothing else; says on stderr how many temporary ones (a run that
/// died writing them) it removed. Throws std::runtime_error naming a file it cannot remove.
void clearRunOutputs(const std::filesystem::path& dir);

/// Removes a frame sequence an earlier run left in `folder` (000000.png ... and their temporary
/// names), nothing else. Throws std::runtime_error naming a file it cannot remove.
void clearFrames(const std::filesystem::path& folder);

/// The bytes of what clearRunOutputs(dir) would remove: room a rerun gets back.
std::uintmax_t runOutputBytes(const std::filesystem::path& dir);

/// The name of frame `k` of a frame sequence: "000042.png".
std::string frameFileName(long k);

/// Removes from `folder` the videos a run left unfinished when it died (`kill -9`): temporary
/// names NAME.mp4.PID.part (.mkv, .mov; as render::VideoWriter writes them) whose PID is no
/// running process, each said on stderr. A name of a live process (another run writing its video
/// there) stays. Returns how many were removed.
int removeStaleVideoParts(const std::filesystem::path& folder);

/// Checks a video path before any work: not a folder, ends in .mp4, .mkv or .mov, its folder
/// created and writable; then removes the stale temporary videos there (removeStaleVideoParts).
/// Throws std::runtime_error naming the path.
void requireVideoPath(const std::string& path);

}  // namespace gf::app
