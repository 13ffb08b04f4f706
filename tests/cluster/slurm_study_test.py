#!/usr/bin/env python3
"""A study on a real one-node Slurm cluster gives the results of a local `--jobs 1` run.

Usage: slurm_study_test.py GODFINGER SLURM_STUDY OUT

Brings up munged, slurmctld and slurmd (Debian's munge and slurm-wlm, GF_PACKAGES) on this
host with a generated munge key and slurm.conf in a temporary folder under /tmp (no file of
/etc/slurm or /etc/munge is read, no system daemon is used: the clients find the configuration
through SLURM_CONF and the munge socket through slurm.conf's AuthInfo). Then, as the manual's
study-files.md says a user does: `godfinger study torsion --quick --emit-jobs`, `sbatch --array`
of `scripts/slurm-study`, `godfinger study torsion --collect`. Every array task must complete
with exit code 0, every run's trace.csv must equal the local run's byte for byte, and
results.csv must equal the local one in every column but the three step and patch times, which
are wall-clock measurements (the two runs of a configuration never take exactly as long).

The daemons run in the foreground as children of this process and die with it
(PR_SET_PDEATHSIG); they are stopped, and the temporary folder removed, whatever happens. Every
wait has a deadline, so the test fails instead of hanging. Their logs are copied to OUT/logs.
"""
import csv
import ctypes
import glob
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

STUDY = "torsion"
FOLDER_PREFIX = "godfinger-slurm-"
# The exit code ctest counts as skipped (the test's SKIP_RETURN_CODE).
SKIP_CODE = 77
# Whole-test budget in seconds; ctest's TIMEOUT (300 s) is above it so that the cleanup runs.
DEADLINE_S = 240.0
# The columns that are wall-clock measurements: equal between two runs only by chance.
TIMED_COLUMNS = {"step_us_median", "step_us_p99", "patch_us_mean"}
DAEMONS = ("munged", "slurmctld", "slurmd")
CLIENTS = ("mungekey", "munge", "sbatch", "squeue", "scontrol", "scancel", "sinfo")
TERMINAL_STATES = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY",
                   "PREEMPTED", "BOOT_FAIL", "DEADLINE"}


class Failure(Exception):
    """What went wrong, for the test's one-line verdict."""


def say(start, what):
    """One line of progress on stderr, with the seconds since the test started."""
    print(f"[{time.monotonic() - start:6.1f} s] {what}", file=sys.stderr, flush=True)


def deadline_left(start):
    """Seconds left of the test's budget (at least 1, so a last command can still run)."""
    return max(1.0, DEADLINE_S - (time.monotonic() - start))


def wait_until(what, check, timeout_s, poll_s=0.2):
    """Polls check() until it returns a true value, which is returned; Failure after timeout_s."""
    end = time.monotonic() + timeout_s
    while True:
        result = check()
        if result:
            return result
        if time.monotonic() > end:
            raise Failure(f"{what}: not after {timeout_s:.0f} s")
        time.sleep(poll_s)


def die_with_parent():
    """Run in a daemon's child before exec: it gets SIGTERM when this process ends."""
    libc = ctypes.CDLL(None, use_errno=True)
    pr_set_pdeathsig = 1
    libc.prctl(pr_set_pdeathsig, signal.SIGTERM, 0, 0, 0)


def free_ports(count):
    """Ports nobody listens on now (the kernel's choice), held together so they differ."""
    sockets = [socket.socket() for _ in range(count)]
    try:
        for s in sockets:
            s.bind(("", 0))
        return [s.getsockname()[1] for s in sockets]
    finally:
        for s in sockets:
            s.close()


def run(args, timeout_s, **kwargs):
    """Runs a command to completion; its stdout. Failure naming it when it fails or times out."""
    try:
        done = subprocess.run(args, capture_output=True, text=True, timeout=timeout_s,
                              stdin=subprocess.DEVNULL, **kwargs)
    except subprocess.TimeoutExpired:
        raise Failure(f"{args[0]}: still running after {timeout_s:.0f} s") from None
    if done.returncode != 0:
        raise Failure(f"{' '.join(map(str, args))}: exit {done.returncode}: {done.stderr.strip()}")
    return done.stdout


class Cluster:
    """munged, slurmctld and slurmd on this host, configured in a folder of their own."""

    def __init__(self, root, logs):
        self.root = root
        self.logs = logs
        self.host = socket.gethostname().split(".")[0]
        self.conf = os.path.join(root, "slurm.conf")
        self.socket = os.path.join(root, "munge.socket")
        self.env = dict(os.environ, SLURM_CONF=self.conf)
        self.processes = []

    def path(self, name):
        return os.path.join(self.root, name)

    def start(self, timeout_s):
        """Generates the key and configuration, starts the daemons, waits for an idle node."""
        self._start_munge(timeout_s)
        self._write_conf()
        self._spawn("slurmctld", ["slurmctld", "-D", "-f", self.conf])
        wait_until("slurmctld answering scontrol ping", self._controller_up, timeout_s)
        self._spawn("slurmd", ["slurmd", "-D", "-f", self.conf, "-N", self.host])
        wait_until(f"node {self.host} idle in sinfo", self._node_idle, timeout_s)

    def _start_munge(self, timeout_s):
        # munged wants its socket's folder searchable by all, and its key readable by it alone.
        os.chmod(self.root, 0o755)
        run(["mungekey", "--create", "--keyfile", self.path("munge.key")], 30)
        self._spawn("munged", ["munged", "--foreground", "--key-file", self.path("munge.key"),
                               "--socket", self.socket, "--pid-file", self.path("munged.pid"),
                               "--log-file", self.path("munged.log"), "--seed-file",
                               self.path("munged.seed")])
        wait_until("munged's socket", self._munge_up, timeout_s)

    def _munge_up(self):
        self.check_alive()
        return self._answers(["munge", "-n", "-S", self.socket])

    def _write_conf(self):
        ctld_port, slurmd_port = free_ports(2)
        for folder in ("state", "spool"):
            os.mkdir(self.path(folder))
        lines = [
            "ClusterName=godfinger",
            f"SlurmctldHost={self.host}(127.0.0.1)",
            f"SlurmctldPort={ctld_port}",
            f"SlurmdPort={slurmd_port}",
            "SlurmUser=root",
            "SlurmdUser=root",
            "AuthType=auth/munge",
            "CredType=cred/munge",
            f"AuthInfo=socket={self.socket}",
            f"StateSaveLocation={self.path('state')}",
            f"SlurmdSpoolDir={self.path('spool')}",
            f"SlurmctldPidFile={self.path('slurmctld.pid')}",
            f"SlurmdPidFile={self.path('slurmd.pid')}",
            f"SlurmctldLogFile={self.path('slurmctld.log')}",
            f"SlurmdLogFile={self.path('slurmd.log')}",
            "MailProg=/bin/true",
            # No cgroups: processes tracked by their parents, tasks not bound.
            "ProctrackType=proctrack/linuxproc",
            "TaskPlugin=task/none",
            "JobAcctGatherType=jobacct_gather/none",
            "AccountingStorageType=accounting_storage/none",
            "JobCompType=jobcomp/none",
            "MpiDefault=none",
            "SwitchType=switch/none",
            # One CPU per task, two tasks at a time; finished tasks stay visible for 10 minutes.
            "SelectType=select/cons_tres",
            "SelectTypeParameters=CR_CPU",
            "MinJobAge=600",
            "ReturnToService=2",
            # The node is what this file says, whatever the hardware: no drain on a 1-CPU host.
            "SlurmdParameters=config_overrides",
            f"NodeName={self.host} NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN",
            f"PartitionName=studies Nodes={self.host} Default=YES MaxTime=10 State=UP",
        ]
        with open(self.conf, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")

    def _spawn(self, name, args):
        log = open(self.path(name + ".out"), "w", encoding="utf-8")
        process = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                   env=self.env, preexec_fn=die_with_parent)
        self.processes.append((name, process))

    def _answers(self, args):
        """Whether a client command succeeds (a daemon not yet up answers no, or not in 30 s)."""
        try:
            return subprocess.run(args, env=self.env, capture_output=True, stdin=subprocess.DEVNULL,
                                  timeout=30).returncode == 0
        except subprocess.TimeoutExpired:
            return False

    def _controller_up(self):
        self.check_alive()
        return self._answers(["scontrol", "ping"])

    def _node_idle(self):
        self.check_alive()
        state = run(["sinfo", "-h", "-N", "-n", self.host, "-o", "%t"], 30, env=self.env).strip()
        return state == "idle"

    def check_alive(self):
        """Failure naming a daemon that has exited, and its log."""
        for name, process in self.processes:
            if process.poll() is not None:
                raise Failure(f"{name} exited with {process.returncode} (see {self.logs})")

    def stop(self):
        """Cancels what is left, stops the daemons (slurmd first), keeps their logs."""
        if self.processes:
            self._answers(["scancel", "--full", "--user", str(os.getuid())])
        for name, process in reversed(self.processes):
            process.terminate()
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait(timeout=30)
        self.processes = []
        os.makedirs(self.logs, exist_ok=True)
        for name in os.listdir(self.root):
            if name.endswith((".log", ".out")):
                shutil.copy(self.path(name), self.logs)

    def leftovers(self):
        """Processes still running whose command line or environment names the cluster's folder
        (the daemons and what they started: slurmscriptd, slurmstepd, the tasks); killed."""
        found = []
        for pid in filter(str.isdigit, os.listdir("/proc")):
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    cmdline = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
                with open(f"/proc/{pid}/environ", "rb") as f:
                    environ = f.read().decode(errors="replace")
            except OSError:
                continue
            if int(pid) != os.getpid() and (self.root in cmdline or self.root in environ):
                found.append(f"{pid} {cmdline}")
                os.kill(int(pid), signal.SIGKILL)
        return found


def tasks_of(cluster, job_id):
    """The array's records as dicts of scontrol's fields (a pending range is one record)."""
    text = run(["scontrol", "show", "job", "-o", job_id], 30, env=cluster.env)
    records = []
    for line in text.splitlines():
        fields = dict(word.split("=", 1) for word in line.split() if "=" in word)
        records.append(fields)
    return records


def run_array(cluster, godfinger, slurm_study, out, timeout_s):
    """Emits the study's jobs, runs them as one Slurm array, checks every task, collects."""
    jobs = os.path.join(out, "jobs.txt")
    folder = os.path.join(out, "slurm")
    run([godfinger, "study", STUDY, "--quick", "--out", folder, "--emit-jobs", jobs], 60)
    with open(jobs, encoding="utf-8") as f:
        count = sum(1 for line in f if line.strip())
    job_id = run(["sbatch", "--parsable", f"--array=1-{count}", "--time=5", "--job-name=gf-" + STUDY,
                  f"--output={out}/task-%A_%a.out", slurm_study, jobs], 30, env=cluster.env, cwd=out)
    job_id = job_id.strip().split(";")[0]

    def finished():
        cluster.check_alive()
        records = tasks_of(cluster, job_id)
        return records if all(r.get("JobState") in TERMINAL_STATES for r in records) else None

    records = wait_until(f"array job {job_id} finished", finished, timeout_s)
    bad = [r for r in records if r.get("JobState") != "COMPLETED" or r.get("ExitCode") != "0:0"]
    if len(records) != count or bad:
        raise Failure(f"array job {job_id}: {len(records)} of {count} tasks, not completed with 0:0: "
                      + ", ".join(f"task {r.get('ArrayTaskId')} {r.get('JobState')} {r.get('ExitCode')}"
                                  for r in bad))
    print(f"slurm: array job {job_id}: {count} tasks completed with exit code 0", file=sys.stderr)
    run([godfinger, "study", STUDY, "--collect", folder], 120)
    return folder


def read_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def compare(local, slurm):
    """Failure naming the first difference between the two study folders' measured outputs."""
    a, b = read_rows(os.path.join(local, "results.csv")), read_rows(os.path.join(slurm, "results.csv"))
    if not a or a[0] != b[0] or len(a) != len(b):
        raise Failure(f"results.csv: header or row count differs ({len(a)} vs {len(b)} lines)")
    header = a[0]
    for row_a, row_b in zip(a[1:], b[1:]):
        for name, value_a, value_b in zip(header, row_a, row_b):
            if name not in TIMED_COLUMNS and value_a != value_b:
                raise Failure(f"results.csv: run {row_a[-1]}: {name}: local {value_a}, slurm {value_b}")
        if row_b[header.index("status")] != "ok":
            raise Failure(f"results.csv: run {row_b[-1]}: status {row_b[header.index('status')]}")
    for row in a[1:]:
        trace_a = os.path.join(local, "runs", row[-1], "trace.csv")
        trace_b = os.path.join(slurm, "runs", row[-1], "trace.csv")
        with open(trace_a, "rb") as fa, open(trace_b, "rb") as fb:
            if fa.read() != fb.read():
                raise Failure(f"{trace_b}: differs from {trace_a}")
    return len(a) - 1


def cluster_folder():
    """A new folder for the cluster under /tmp (a unix socket's path must stay under 108 bytes),
    naming this process in it; folders of earlier tests whose process has gone (killed before
    it could clean up) are removed first."""
    for stale in glob.glob(os.path.join("/tmp", FOLDER_PREFIX + "*")):
        try:
            with open(os.path.join(stale, "test.pid"), encoding="utf-8") as f:
                os.kill(int(f.read()), 0)
        except (OSError, ValueError):
            shutil.rmtree(stale, ignore_errors=True)
    root = tempfile.mkdtemp(prefix=FOLDER_PREFIX, dir="/tmp")
    with open(os.path.join(root, "test.pid"), "w", encoding="utf-8") as f:
        f.write(str(os.getpid()))
    return root


def check_tools():
    missing = [tool for tool in DAEMONS + CLIENTS if shutil.which(tool) is None
               and not os.path.exists(os.path.join("/usr/sbin", tool))]
    if missing:
        raise Failure(f"not installed: {', '.join(missing)} (Debian's slurm-wlm and munge; "
                      "scripts/test installs GF_PACKAGES)")
    # Debian puts the daemons in /usr/sbin, outside a non-root PATH.
    os.environ["PATH"] = os.environ.get("PATH", "/usr/bin:/bin") + ":/usr/sbin:/sbin"


def check_root():
    """Exits with ctest's skip code when not root: slurmd starts each job as its owner, so it runs
    as root, as scripts/test and CI do (they install packages)."""
    if os.getuid() != 0:
        print("SKIP: a Slurm node runs as root (slurmd starts jobs as their owner); "
              "run as root, as scripts/test and .ci/run do", file=sys.stderr)
        sys.exit(SKIP_CODE)


def interrupted(signum, _frame):
    raise Failure(f"stopped by signal {signum}")


def main(start):
    godfinger, slurm_study, out = (os.path.abspath(p) for p in sys.argv[1:4])
    for signum in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(signum, interrupted)
    check_tools()
    check_root()
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    local = os.path.join(out, "local")
    run([godfinger, "study", STUDY, "--quick", "--jobs", "1", "--out", local], deadline_left(start))
    say(start, f"local: {STUDY} --quick --jobs 1 done")
    cluster = Cluster(cluster_folder(), os.path.join(out, "logs"))
    try:
        cluster.start(min(60.0, deadline_left(start)))
        say(start, f"slurm: node {cluster.host} idle")
        slurm = run_array(cluster, godfinger, slurm_study, out, deadline_left(start))
        say(start, "slurm: collected")
    finally:
        for signum in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(signum, signal.SIG_IGN)
        cluster.stop()
        shutil.rmtree(cluster.root, ignore_errors=True)
        say(start, "slurm: daemons stopped, their folder removed")
    left = cluster.leftovers()
    if left:
        raise Failure("still running after the cluster stopped: " + "; ".join(left))
    rows = compare(local, slurm)
    say(start, f"slurm: {rows} rows of results.csv equal to --jobs 1's but for "
               f"{', '.join(sorted(TIMED_COLUMNS))}, every trace.csv equal")


if __name__ == "__main__":
    try:
        main(time.monotonic())
    except Failure as failure:
        print(f"FAIL: {failure}", file=sys.stderr)
        sys.exit(1)
