#!/usr/bin/python3
"""The benchmark on a real one-node Slurm cluster started in a temporary folder.

Starts munged (its own key and socket), slurmctld and slurmd (their own slurm.conf for this host,
free ports, state, spool and logs in the folder), lets `visgrab slurm --submit` submit the
benchmark of the given grasps as a 4-task array plus the merge job, polls squeue with a timeout
and checks that the merged trials.csv and run.csv equal a one-machine `visgrab run` byte for
byte. The daemons are always stopped by PID at the end (also on failure or timeout) and no
process started here is left behind.

Exit codes: 0 passed, 1 failed, 77 skipped (not root, no Slurm or munge, daemons that do not
start), with the reason on stdout.

Usage: slurm_cluster_test.py VISGRAB DATABASE GRASPS HAND WORKDIR
"""

import os
import pwd
import signal
import socket
import subprocess
import sys
import time

SKIP = 77
SHARDS = 4
# Seconds: the daemons to come up, the jobs to finish.
START_TIMEOUT = 30
JOBS_TIMEOUT = 240


class Skip(Exception):
    """The cluster cannot start here: the test reports itself skipped."""


class Failure(Exception):
    """The test failed."""


def find(program):
    for folder in (os.environ.get("PATH", "").split(os.pathsep) + ["/usr/sbin", "/usr/bin",
                                                                   "/sbin", "/bin"]):
        path = os.path.join(folder, program)
        if folder and os.access(path, os.X_OK):
            return path
    return None


def file_tail(path, lines=15):
    """The last lines of a daemon's log, for the reason of a skip or failure."""
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return "(no log at " + path + ")"


def free_ports(n):
    """n distinct TCP ports free on this host now (bound to port 0, then released)."""
    sockets = []
    try:
        for _ in range(n):
            s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            s.bind(("127.0.0.1", 0))
            sockets.append(s)
        return [s.getsockname()[1] for s in sockets]
    finally:
        for s in sockets:
            s.close()


class Cluster:
    """munged, slurmctld and slurmd in `root`; stop() ends them (and any job) by PID."""

    def __init__(self, root, scope):
        self.root = root
        self.scope = scope  # any process with this path in its command line is the test's
        self.daemons = []  # (name, Popen), in start order
        self.env = dict(os.environ)
        self.programs = {}

    def path(self, *parts):
        return os.path.join(self.root, *parts)

    def log_tail(self, name):
        return file_tail(self.path("log", name))

    def start(self):
        for program in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo", "scancel"):
            self.programs[program] = find(program)
            if not self.programs[program]:
                raise Skip(program + " not found (Debian: apt-get install slurm-wlm munge)")
        try:
            munge_user = pwd.getpwnam("munge")
        except KeyError:
            raise Skip("no munge user (Debian: apt-get install munge)")
        os.chmod(self.root, 0o755)  # munged (the munge user) must reach its folder
        for d in ("log", "state", "spool", "run"):
            os.makedirs(self.path(d), mode=0o755)
        self.start_munge(munge_user)
        self.start_slurm()

    def start_munge(self, user):
        folder = self.path("munge")
        os.makedirs(folder)
        os.chmod(folder, 0o755)  # the socket's folder must be searchable by all
        key = os.path.join(folder, "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        for p in (folder, key):
            os.chown(p, user.pw_uid, user.pw_gid)
        self.socket = os.path.join(folder, "munge.socket")
        command = [self.programs["munged"], "--foreground", "--socket=" + self.socket,
                   "--key-file=" + key, "--pid-file=" + os.path.join(folder, "munged.pid"),
                   "--log-file=" + os.path.join(folder, "munged.log"),
                   "--seed-file=" + os.path.join(folder, "munged.seed")]
        self.spawn("munged", command, user=user.pw_uid, group=user.pw_gid)
        self.wait_for(lambda: os.path.exists(self.socket), "munged's socket",
                      lambda: file_tail(os.path.join(folder, "munged.log")))

    def start_slurm(self):
        host = socket.gethostname().split(".")[0]
        ctld_port, node_port = free_ports(2)
        conf = self.path("slurm.conf")
        with open(conf, "w") as f:
            f.write(f"""ClusterName=visgrabtest
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={node_port}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.socket}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc={self.path('log', 'jobcomp.txt')}
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerParameters=batch_sched_delay=0,sched_interval=2,bf_interval=1
StateSaveLocation={self.path('state')}
SlurmdSpoolDir={self.path('spool')}
SlurmctldPidFile={self.path('run', 'slurmctld.pid')}
SlurmdPidFile={self.path('run', 'slurmd.pid')}
SlurmctldLogFile={self.path('log', 'slurmctld.log')}
SlurmdLogFile={self.path('log', 'slurmd.log')}
ReturnToService=2
MailProg=/bin/true
MinJobAge=300
NodeName={host} NodeAddr=127.0.0.1 CPUs={os.cpu_count() or 1} State=UNKNOWN
PartitionName=test Nodes={host} Default=YES MaxTime=INFINITE State=UP
""")
        self.env["SLURM_CONF"] = conf
        self.spawn("slurmctld", [self.programs["slurmctld"], "-D", "-f", conf])
        self.spawn("slurmd", [self.programs["slurmd"], "-D", "-f", conf, "-N", host])
        self.wait_for(self.node_idle, "the node to be idle",
                      lambda: self.log_tail("slurmctld.log") + self.log_tail("slurmd.log"))

    def spawn(self, name, command, **kwargs):
        with open(self.path("log", name + ".out"), "wb") as out:
            process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=out,
                                       stderr=subprocess.STDOUT, env=self.env,
                                       start_new_session=True, **kwargs)
        self.daemons.append((name, process))

    def wait_for(self, ready, what, logs):
        deadline = time.monotonic() + START_TIMEOUT
        while time.monotonic() < deadline:
            for name, process in self.daemons:
                if process.poll() is not None:
                    raise Skip(f"{name} exited with code {process.returncode} while waiting for "
                               f"{what}:\n{self.log_tail(name + '.out')}{logs()}")
            if ready():
                return
            time.sleep(0.2)
        raise Skip(f"no {what} after {START_TIMEOUT} s:\n{logs()}")

    def run(self, command, timeout=30):
        return subprocess.run(command, env=self.env, capture_output=True, text=True,
                              timeout=timeout)

    def node_idle(self):
        r = self.run([self.programs["sinfo"], "-h", "-o", "%T"])
        return r.returncode == 0 and r.stdout.strip() == "idle"

    def jobs_left(self, ids):
        r = self.run([self.programs["squeue"], "-h", "-o", "%i %T", "-j", ",".join(ids)])
        if r.returncode != 0:
            # squeue forgets finished jobs only after MinJobAge; an error here is a failure.
            raise Failure("squeue failed: " + r.stderr)
        return [line for line in r.stdout.splitlines() if line.strip()]

    def stop(self):
        """Cancels every job, then stops the daemons (last started first) by PID."""
        if self.programs.get("scancel") and any(n == "slurmctld" for n, _ in self.daemons):
            try:
                self.run([self.programs["scancel"], "--full", "--user=root"], timeout=10)
                deadline = time.monotonic() + 10
                while time.monotonic() < deadline:
                    r = self.run([self.programs["squeue"], "-h"], timeout=10)
                    if r.returncode != 0 or not r.stdout.strip():
                        break
                    time.sleep(0.5)
            except (OSError, subprocess.SubprocessError):
                pass
        for name, process in reversed(self.daemons):
            stop_process(process)
        self.kill_leftovers()

    def kill_leftovers(self):
        """Ends any process still running from this folder (a job step of a killed slurmd)."""
        for pid in os.listdir("/proc"):
            if not pid.isdigit() or int(pid) in (os.getpid(), os.getppid()):
                continue
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    cmdline = f.read().decode(errors="replace")
            except OSError:
                continue
            if self.scope in cmdline:
                try:
                    os.kill(int(pid), signal.SIGKILL)
                except OSError:
                    pass


def stop_process(process):
    if process.poll() is not None:
        return
    try:
        os.killpg(process.pid, signal.SIGTERM)  # its own session: the daemon and its children
    except OSError:
        process.terminate()
    try:
        process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except OSError:
            process.kill()
        process.wait()


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def check(visgrab, database, grasps, hand, work, cluster):
    out = os.path.join(work, "sweep")
    submit = cluster.run([visgrab, "slurm", "--db", database, "--grasps", grasps, "--hand", hand,
                          "--shards", str(SHARDS), "--cpus-per-task", "1", "--out", out,
                          "--time", "10", "--no-pictures", "--submit"], timeout=60)
    if submit.returncode != 0:
        raise Failure("visgrab slurm --submit failed:\n" + submit.stdout + submit.stderr)
    print(submit.stdout, end="")
    words = submit.stdout.split()
    ids = [words[i + 2].rstrip(",") for i, w in enumerate(words[:-2])
           if w in ("trials", "merge") and words[i + 1] == "job"]
    if len(ids) != 2 or not all(i.isdigit() for i in ids):
        raise Failure("no job ids in visgrab slurm's output:\n" + submit.stdout)

    # The one-machine run while the cluster works (the same work, two threads).
    whole = os.path.join(work, "whole")
    one = subprocess.run([visgrab, "run", "--db", database, "--grasps", grasps, "--hand", hand,
                          "--threads", "2", "--quiet", "--out", whole], capture_output=True,
                         text=True, timeout=JOBS_TIMEOUT)
    if one.returncode != 0:
        raise Failure("visgrab run failed:\n" + one.stdout + one.stderr)

    deadline = time.monotonic() + JOBS_TIMEOUT
    while cluster.jobs_left(ids):
        if time.monotonic() > deadline:
            raise Failure(f"the jobs did not finish within {JOBS_TIMEOUT} s:\n" +
                          "\n".join(cluster.jobs_left(ids)) + "\n" +
                          cluster.log_tail("slurmctld.log"))
        time.sleep(1)

    logs = os.path.join(out, "slurm", "logs")
    jobcomp = cluster.path("log", "jobcomp.txt")
    # The job record is written as each job ends; give the last line a moment.
    for _ in range(20):
        records = open(jobcomp).read() if os.path.exists(jobcomp) else ""
        states = [w.split("=", 1)[1] for line in records.splitlines() for w in line.split()
                  if w.startswith("JobState=")]
        if len(states) >= SHARDS + 1:
            break
        time.sleep(0.5)
    if len(states) != SHARDS + 1 or any(s != "COMPLETED" for s in states):
        raise Failure(f"expected {SHARDS + 1} completed jobs, the job record says {states}:\n"
                      + records)
    task_logs = sorted(f for f in os.listdir(logs) if f.startswith("trials-"))
    if len(task_logs) != SHARDS:
        raise Failure(f"expected {SHARDS} task logs in {logs}, found {task_logs}")

    name = os.path.splitext(os.path.basename(grasps))[0]
    merged = os.path.join(out, "results", name)
    for f in ("trials.csv", "run.csv"):
        if read_bytes(os.path.join(merged, f)) != read_bytes(os.path.join(whole, f)):
            raise Failure(f"the merged {f} differs from the one-machine run's "
                          f"({merged} vs {whole})")
    report = os.path.join(out, "report", "report.md")
    if not os.path.exists(report):
        raise Failure("the merge job wrote no report (" + report + ")")
    trials = read_bytes(os.path.join(merged, "trials.csv")).count(b"\n")
    shard_trials = [read_bytes(os.path.join(out, "shards", name, f"shard-{k}", "trials.csv"))
                    .count(b"\n") for k in range(1, SHARDS + 1)]
    print(f"merged trials.csv ({trials} lines) equals the one-machine run's; lines per shard "
          f"{shard_trials}")


def main():
    if len(sys.argv) != 6:
        print(__doc__)
        return 2
    visgrab, database, grasps, hand, work = sys.argv[1:]
    if os.geteuid() != 0:
        print("SKIPPED: not root: munged, slurmctld and slurmd of a test cluster need root")
        return SKIP
    # A SIGTERM (ctest stopping the test, say) ends the test through the finally below.
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(1))
    cluster = Cluster(os.path.join(work, "cluster"), work)
    os.makedirs(cluster.root)
    try:
        started = time.monotonic()
        cluster.start()
        print(f"cluster up in {time.monotonic() - started:.1f} s")
        check(visgrab, database, grasps, hand, work, cluster)
        return 0
    except Skip as e:
        print("SKIPPED: the cluster cannot start: " + str(e))
        return SKIP
    except (Failure, subprocess.TimeoutExpired, OSError) as e:
        print("FAILED: " + str(e))
        return 1
    finally:
        cluster.stop()


if __name__ == "__main__":
    sys.exit(main())
