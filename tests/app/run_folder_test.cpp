// A run folder has one owner, and faults a user meets do not cost earlier outputs: a second run
// into a busy folder, a disk too full for the run, a disk that fills while the MP4 is written,
// and standard output that cannot be written (a full disk, a closed pipe).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <csignal>
#include <fstream>
#include <functional>
#include <map>
#include <string>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/runs/run_folder.hpp"
#include "tests/app/run_helpers.hpp"

extern char** environ;

namespace gf::app {
namespace {

using namespace test;

// A tmpfs of `size` mounted on `dir` while alive: a disk of known room. Mounting needs root (or
// CAP_SYS_ADMIN); `mounted` says whether it worked.
struct Tmpfs {
  fs::path dir;
  bool mounted = false;
  Tmpfs(const fs::path& where, const std::string& size) : dir(where) {
    fs::create_directories(dir);
    mounted = exitStatus("mount -t tmpfs -o size=" + size + " tmpfs '" + dir.string() + "' 2> /dev/null") == 0;
  }
  ~Tmpfs() {
    if (mounted) exitStatus("umount '" + dir.string() + "'");
  }
  Tmpfs(const Tmpfs&) = delete;
  Tmpfs& operator=(const Tmpfs&) = delete;
};

// freshFolder(name) for a test that mounts a Tmpfs on its "disk": a mount left by a run of the
// test that was killed (or aborted) is taken away first, or the folder could not be removed.
fs::path freshDiskFolder(const std::string& name) {
  const fs::path stale = fs::path(GF_BINARY_DIR) / "test-outputs" / name / "disk";
  if (fs::exists(stale)) exitStatus("umount '" + stale.string() + "' 2> /dev/null");
  return freshFolder(name);
}

// Every output file under `dir` (the lock file aside) with a hash of its bytes, for "nothing was
// touched".
std::map<std::string, std::size_t> contentsOf(const fs::path& dir) {
  std::map<std::string, std::size_t> out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().filename() != kLockFile) {
      out[fs::relative(e.path(), dir).string()] = std::hash<std::string>{}(readFile(e.path()));
    }
  }
  return out;
}

// In one process: the folder's second owner is refused, naming the folder and the holder's pid;
// once the first is gone, the folder can be owned again.
TEST(RunFolder, ASecondOwnerIsRefusedNamingTheFolderAndThePid) {
  const fs::path dir = freshFolder("gf_folder_owner") / "out";
  {
    const RunFolder first(dir);
    try {
      const RunFolder second(dir);
      ADD_FAILURE() << "a second owner was let in";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(dir.string()), std::string::npos) << what;
      EXPECT_NE(what.find("pid " + std::to_string(getpid())), std::string::npos) << what;
    }
  }
  EXPECT_NO_THROW(RunFolder again(dir));
}

// Two runs into one --out at once: the second exits 1 at once, naming the folder and the first
// run's pid, and removes nothing (a contact snapshot placed after the first began, which a run
// starting there would clear, stays); the first finishes its outputs (here stopped by Ctrl-C) as
// if alone. The first is a realtime run, so it is still running when the second starts.
TEST(RunFolder, ASecondRunIntoABusyFolderExits1AndRemovesNothing) {
  const fs::path dir = freshFolder("gf_folder_busy");
  const fs::path out = dir / "out", log = dir / "second.txt";
  Child first = start(kBin + " run " + kFig8 + " --realtime --no-fifo --duration 10 --out " + out.string(), "/dev/null");
  ASSERT_NE(first.lines, nullptr);
  ASSERT_GT(first.pid, 0);
  KillGroupOnExit guard{first.pid};
  ASSERT_TRUE(waitForLine(first.lines, "[godfinger]"));  // its loop runs: the folder is held
  std::ofstream(out / kContactsFolder / "t9.000.json") << "marker\n";
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + out.string() + " > /dev/null 2> " +
                       log.string()),
            1);
  const std::string said = readFile(log);
  EXPECT_NE(said.find(out.string()), std::string::npos) << said;
  EXPECT_NE(said.find("pid " + std::to_string(first.pid)), std::string::npos) << said;
  ASSERT_EQ(kill(-first.pid, SIGINT), 0);
  EXPECT_EQ(finish(first), 130);
  guard.done = true;
  const nlohmann::json summary = summaryOf(out);
  EXPECT_TRUE(summary["interrupted"].get<bool>());
  EXPECT_EQ(summary["clock"], "realtime");  // the first run's, not the second's
  EXPECT_DOUBLE_EQ(lastTraceTime(out), summary["time_reached_s"].get<double>());
  EXPECT_EQ(readFile(out / kContactsFolder / "t9.000.json"), "marker\n");
}

// A disk without room for the run's outputs: the run exits 1 before removing anything, saying
// how much it needs and how much is free; the earlier run's outputs are as they were. A rerun of
// the earlier run fits: the room its earlier outputs give back counts.
TEST(RunFolder, ADiskTooFullForTheRunKeepsTheEarlierOutputs) {
  const fs::path dir = freshDiskFolder("gf_folder_full_disk");
  const Tmpfs disk(dir / "disk", "1m");
  if (!disk.mounted) GTEST_SKIP() << "mounting a 1 MB tmpfs needs root (or CAP_SYS_ADMIN): not checked here";
  const fs::path out = disk.dir / "out", log = dir / "stderr.txt";
  ASSERT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + out.string() + " > /dev/null 2>&1"), 0);
  const auto earlier = contentsOf(out);
  ASSERT_TRUE(earlier.count("trace.csv") && earlier.count("summary.json"));
  {
    std::ofstream filler(disk.dir / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    while (filler.write(block.data(), block.size()) && fs::space(disk.dir).available > 200 * 1024) {
    }
  }
  // 2 s of trace.csv alone is about 1.2 MB: more than the disk holds.
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 2 --out " + out.string() + " > /dev/null 2> " +
                       log.string()),
            1);
  const std::string said = readFile(log);
  EXPECT_NE(said.find("too little room"), std::string::npos) << said;
  EXPECT_NE(said.find(out.string()), std::string::npos) << said;
  EXPECT_EQ(contentsOf(out), earlier);
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + out.string() + " > /dev/null 2> " +
                       log.string()),
            0)
      << readFile(log);
  EXPECT_EQ(contentsOf(out).at("trace.csv"), earlier.at("trace.csv")) << "the same run again: the same trace";
  EXPECT_DOUBLE_EQ(summaryOf(out)["time_reached_s"].get<double>(), 0.2);
}

// A disk that fills while the MP4 is written (60 kB for the video): ffmpeg reports "No space left
// on device" (and still exits 0): the run exits 1 naming the video, summary.json holds the error,
// no broken MP4 is left under the video's name or a temporary one, and the file that was there
// before stays. The other outputs hold the whole run.
TEST(RunFolder, AVideoDiskThatFillsLeavesNoBrokenVideo) {
  const fs::path dir = freshDiskFolder("gf_folder_video_disk");
  const Tmpfs disk(dir / "disk", "60k");
  if (!disk.mounted) GTEST_SKIP() << "mounting a 60 kB tmpfs needs root (or CAP_SYS_ADMIN): not checked here";
  const fs::path video = disk.dir / "x.mp4", out = dir / "out", log = dir / "stderr.txt";
  std::ofstream(video) << "earlier\n";
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 2 --out " + out.string() + " --video " +
                       video.string() + " > /dev/null 2> " + log.string()),
            1);
  const std::string said = readFile(log);
  EXPECT_NE(said.find(video.string() + ": ffmpeg failed"), std::string::npos) << said;
  EXPECT_NE(said.find("No space left on device"), std::string::npos) << said;
  EXPECT_EQ(readFile(video), "earlier\n");
  EXPECT_EQ(countFiles(disk.dir), 1) << "no temporary video left";
  const nlohmann::json summary = summaryOf(out);
  EXPECT_NE(summary["error"].get<std::string>().find("no video written"), std::string::npos) << summary["error"];
  EXPECT_DOUBLE_EQ(lastTraceTime(out), 2.0);
}

// Commands that print: standard output that cannot be written (a full device) is an error on
// stderr and exit 1, not an empty file and exit 0.
TEST(CommandOutput, StandardOutputThatCannotBeWrittenIsAnError) {
  const fs::path log = freshFolder("gf_output_full") / "stderr.txt";
  const std::string mesh = std::string(GF_SOURCE_DIR) + "/assets/meshes/bunny.obj";
  for (const std::string& command : {std::string("schema"), std::string("list"), "mesh-info " + mesh}) {
    EXPECT_EQ(exitStatus(kBin + " " + command + " > /dev/full 2> " + log.string()), 1) << command;
    const std::string said = readFile(log);
    EXPECT_NE(said.find("standard output: cannot write: No space left on device"), std::string::npos) << command << ": "
                                                                                                        << said;
  }
}

// A reader that has gone (a pipe whose read end is closed, as after `| head` ends): the command
// ends quietly with 141, the status a shell gives SIGPIPE, as other Unix tools do.
TEST(CommandOutput, AClosedPipeEndsTheCommandQuietlyWith141) {
  const fs::path log = freshFolder("gf_output_pipe") / "stderr.txt";
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  close(fds[0]);  // the reader is gone before the command writes
  const int err = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(err, 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err, STDERR_FILENO);
  const char* argv[] = {kBin.c_str(), "schema", nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, kBin.c_str(), &actions, nullptr, const_cast<char* const*>(argv), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  close(err);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 141);
  EXPECT_EQ(readFile(log), "");
}

// The pid of a process that has ended (and been waited for).
pid_t deadPid() {
  const char* argv[] = {"/bin/true", nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, "/bin/true", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0) return -1;
  waitpid(pid, nullptr, 0);
  return pid;
}

// A `kill -9` leaves the video's temporary file (NAME.mp4.PID.part) beside it: the next run with a
// video into that folder removes it, saying so, but not a live process's (another run writing its
// video there) nor a file that is not a video's temporary one. A temporary file a dead run left in
// the run folder is removed with a message too.
TEST(RunFolder, AStaleVideoPartOfADeadRunIsRemovedByTheNextRun) {
  const fs::path dir = freshFolder("gf_folder_stale_part");
  const pid_t dead = deadPid();
  ASSERT_GT(dead, 0);
  const std::string stale = "v.mp4." + std::to_string(dead) + ".part", ours = "v.mp4." + std::to_string(getpid()) + ".part";
  for (const std::string& name : {stale, ours, std::string("w.mkv.1.part"), "notes." + std::to_string(dead) + ".part"}) {
    std::ofstream(dir / name) << "partial\n";
  }
  EXPECT_EQ(removeStaleVideoParts(dir), 1);
  EXPECT_FALSE(fs::exists(dir / stale));
  EXPECT_EQ(countFiles(dir), 3) << "the live processes' and the other file stay";
  // Through a run: the stale video part and an unfinished trace.csv.tmp go, each said.
  std::ofstream(dir / stale) << "partial\n";
  const fs::path out = dir / "out", log = dir / "stderr.txt";
  fs::create_directories(out);
  std::ofstream(out / "trace.csv.tmp") << "t\n0.001,";
  ASSERT_EQ(exitStatus(kBin + " run press-box --quiet --duration 0.05 --out " + out.string() + " --video " +
                       (dir / "v.mp4").string() + " > /dev/null 2> " + log.string()),
            0)
      << readFile(log);
  const std::string said = readFile(log);
  EXPECT_NE(said.find((dir / stale).string() + ": removed the unfinished video of a run that is gone (pid " +
                      std::to_string(dead) + ")"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find(out.string() + ": removed 1 unfinished file (.part, .tmp)"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(dir / stale));
  EXPECT_TRUE(fs::exists(dir / "v.mp4"));
  EXPECT_TRUE(fs::exists(dir / ours));
}

}  // namespace
}  // namespace gf::app
