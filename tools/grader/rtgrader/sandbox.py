"""Running a submission's code with limits.

Every process that runs student code (the compiler on their file, each test
case, the chapter program) goes through run_limited():

- its own session and process group, killed as a whole at the wall-clock limit
  and again when it ends (a forked child cannot outlive its test);
- resource limits: CPU seconds, address space, size of any file written
  (which also caps the captured output), number of processes;
- stdout and stderr go to a file the grader opened, read back capped;
- when the grader runs as root, the process runs as an unprivileged user
  ("rt-grader-N", one per parallel worker) that cannot read the hidden tests,
  the solutions or the build tree; every process of that user is killed after
  each run, which also catches children that escaped the process group.
"""

import fcntl
import os
import pwd
import resource
import secrets
import signal
import stat
import subprocess
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

MiB = 1024 * 1024
_users_lock = threading.Lock()


@dataclass
class Limits:
    wall_seconds: float = 10.0
    cpu_seconds: int = 11
    memory_bytes: int = 2048 * MiB
    file_bytes: int = 8 * MiB      # also the most output a process may print
    processes: int = 64


@dataclass
class Outcome:
    returncode: int                # negative: killed by that signal
    timed_out: bool
    output: str                    # stdout and stderr, capped
    output_truncated: bool
    seconds: float
    extra: dict = field(default_factory=dict)


def is_root():
    return os.geteuid() == 0


def sandbox_user(slot, lane=0):
    """The unprivileged user of worker `slot` (root only); created when missing.
    Lanes are extra users for work a worker runs in parallel (its compiles):
    after each run every process of the run's user is killed, so two runs
    at the same time need two users."""
    name = f"rt-grader-{slot}" if lane == 0 else f"rt-grader-{slot}-{lane}"
    with _users_lock:
        try:
            entry = pwd.getpwnam(name)
        except KeyError:
            subprocess.run(["useradd", "--system", "--no-create-home", "--shell", "/usr/sbin/nologin", name],
                           check=True, capture_output=True)
            entry = pwd.getpwnam(name)
    return entry.pw_uid, entry.pw_gid


def slots_folder(tree_folder):
    """Where slot locks live: machine-wide as root (the sandbox users are
    machine-wide), next to the grading tree otherwise."""
    if is_root():
        folder = "/tmp/rt-grader-slots"
        os.makedirs(folder, mode=0o700, exist_ok=True)
        info = os.lstat(folder)
        if info.st_uid != 0 or not stat.S_ISDIR(info.st_mode):
            raise SystemExit(f"grader: {folder} is not root's own folder; remove it")
        os.chmod(folder, 0o700)
        return folder
    return os.path.join(tree_folder, "slots")


@contextmanager
def worker_slot(folder):
    """Holds the lowest free slot number (a lock file in folder) while grading."""
    os.makedirs(folder, exist_ok=True)
    slot = 0
    while True:
        f = open(os.path.join(folder, f"{slot}.lock"), "w")
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            f.close()
            slot += 1
            continue
        try:
            yield slot
        finally:
            fcntl.flock(f, fcntl.LOCK_UN)
            f.close()
        return


def _processes_of_uid(uid):
    pids = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/status") as f:
                for line in f:
                    if line.startswith("Uid:"):
                        if int(line.split()[1]) == uid:
                            pids.append(int(name))
                        break
        except OSError:
            pass
    return pids


def _processes_with_token(token):
    """Processes whose environment holds our token (children that left the group)."""
    marker = f"RT_GRADER_TOKEN={token}".encode()
    pids = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/environ", "rb") as f:
                if marker in f.read().split(b"\0"):
                    pids.append(int(name))
        except OSError:
            pass
    return pids


def _kill_everything(pgid, uid, token):
    """Kills the process group, and every process of the sandbox user (root)
    or carrying the run's token (not root), until none is left."""
    for _ in range(100):
        try:
            os.killpg(pgid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        pids = _processes_of_uid(uid) if uid is not None else _processes_with_token(token)
        pids = [p for p in pids if p != os.getpid()]
        if not pids:
            return
        for p in pids:
            try:
                os.kill(p, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        time.sleep(0.02)


def _count_own_threads():
    """RLIMIT_NPROC counts threads, not processes, of the real user."""
    uid = os.getuid()
    total = 0
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/status") as f:
                fields = dict(line.split(":", 1) for line in f if ":" in line)
            if int(fields["Uid"].split()[0]) == uid:
                total += int(fields["Threads"])
        except (OSError, KeyError, ValueError):
            pass
    return total


def read_capped(path, cap):
    with open(path, "rb") as f:
        data = f.read(cap + 1)
    truncated = len(data) > cap
    return data[:cap].decode("utf-8", errors="replace"), truncated


def run_limited(cmd, cwd, limits, log_path, user=None, env_extra=None, pass_fds=(), output_cap=64 * 1024):
    """Runs cmd under the limits; user is (uid, gid) or None. Returns an Outcome."""
    token = secrets.token_hex(8)
    env = {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": cwd,
        "TMPDIR": cwd,
        "LANG": "C.UTF-8",
        "MALLOC_ARENA_MAX": "2",        # threads' malloc arenas would eat the address-space limit
        "RT_GRADER_TOKEN": token,
    }
    env.update(env_extra or {})
    nproc = limits.processes if user is not None else _count_own_threads() + limits.processes

    def set_limits():  # runs in the child after setuid, just before exec
        resource.setrlimit(resource.RLIMIT_CPU, (limits.cpu_seconds, limits.cpu_seconds + 1))
        resource.setrlimit(resource.RLIMIT_AS, (limits.memory_bytes, limits.memory_bytes))
        resource.setrlimit(resource.RLIMIT_FSIZE, (limits.file_bytes, limits.file_bytes))
        resource.setrlimit(resource.RLIMIT_NPROC, (nproc, nproc))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

    kwargs = {}
    if user is not None:
        kwargs.update(user=user[0], group=user[1], extra_groups=[])
    start = time.monotonic()
    with open(log_path, "wb") as log:
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                start_new_session=True, preexec_fn=set_limits, pass_fds=pass_fds,
                                close_fds=True, **kwargs)
    timed_out = False
    try:
        proc.wait(timeout=limits.wall_seconds)
    except subprocess.TimeoutExpired:
        timed_out = True
    _kill_everything(proc.pid, user[0] if user is not None else None, token)
    proc.wait()
    seconds = time.monotonic() - start
    output, truncated = read_capped(log_path, output_cap)
    return Outcome(proc.returncode, timed_out, output, truncated, seconds)


def describe_ending(outcome, limits):
    """One sentence on how a process ended badly, or '' when it exited normally."""
    if outcome.timed_out:
        return (f"did not finish within {limits.wall_seconds:g} s and was stopped "
                "(an endless loop, or waiting for something that never comes?)")
    rc = outcome.returncode
    if rc >= 0:
        return ""
    sig = -rc
    reasons = {
        signal.SIGSEGV: "crashed with a segmentation fault (a bad pointer, an index out of range, "
                        "or a stack overflow from endless recursion)",
        signal.SIGBUS: "crashed with a bus error (a bad pointer)",
        signal.SIGFPE: "crashed with a floating-point exception (an integer division by zero?)",
        signal.SIGABRT: "aborted (abort(), a failed assert, or an exception nobody caught)",
        signal.SIGXCPU: f"used more than {limits.cpu_seconds} s of CPU time and was stopped",
        signal.SIGXFSZ: f"wrote more than {limits.file_bytes // MiB} MiB (output or files) and was stopped",
        signal.SIGKILL: "was killed (it went past a time or memory limit)",
        signal.SIGILL: "crashed with an illegal instruction",
    }
    return reasons.get(sig, f"was killed by signal {signal.Signals(sig).name if sig in signal.valid_signals() else sig}")
