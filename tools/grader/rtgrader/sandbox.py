"""Running a submission's code with limits, in a sandbox.

Every process that runs student code (the compiler on their file, each test
case, the chapter program) and every step that reads what it produced
(imgcmp) goes through run():

    run(argv, limits=..., log_path=..., user=(uid, gid) or None,
        inputs=[paths it may read], scratch=folder it may write or None, ...)

- namespaces mode (bubblewrap, see isolation.py): the process sees /usr,
  a few files of /etc, its `inputs` read-only at their own paths, `scratch`
  read-write (or, without one, only a private /tmp as its working folder),
  a private size-limited /tmp and /dev/shm, its own /proc (its own processes
  only), no network; nothing else of the machine exists for it (no .git, no
  hidden tests, no solutions, no other submission, no results, no grader).
  When the first process ends, its PID namespace ends and takes every other
  process with it. As root it runs as the unprivileged sandbox user.
- fallback (users / none): today's isolation by user; inputs the sandbox user
  cannot read (a repository in root's 0700 home) are copied to a readable
  place first; leftovers are killed and removed by user id.
- always: its own process group, no controlling terminal, killed at the wall-clock limit;
  resource limits (CPU seconds, address space, size of any file written,
  which also caps the captured output and every memfd, open files,
  processes); a cgroup per run where possible (v2: cgroup.kill, memory.max
  counting memfd and tmpfs, pids.max; memory and pids from cgroup v1 where v2
  lacks them: isolation.Cgroups); stdout and stderr go to a file the
  grader opened, read back capped.
"""

import fcntl
import os
import pwd
import resource
import secrets
import shutil
import signal
import stat
import subprocess
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

from . import fsutil, isolation

MiB = 1024 * 1024
_users_lock = threading.Lock()
_mirror_lock = threading.Lock()
counts = {"runs": 0}     # sandboxed processes started by this grader process (the grader's log says how many)
# World-writable places a sandbox user could leave files in when there is no
# private /tmp (fallback): emptied of that user's entries after every run.
WORLD_WRITABLE = ("/tmp", "/var/tmp", "/dev/shm", "/run/lock", "/dev/mqueue")


@dataclass
class Limits:
    wall_seconds: float = 10.0
    cpu_seconds: int = 11
    memory_bytes: int = 2048 * MiB
    file_bytes: int = 8 * MiB      # also the most output a process may print, and the largest memfd
    processes: int = 64
    open_files: int = 64           # with file_bytes, bounds what memfds can hold without a memory cgroup
    tmp_bytes: int = 64 * MiB      # size of the private /tmp (namespaces mode)
    shm_bytes: int = 16 * MiB      # size of the private /dev/shm (namespaces mode)


@dataclass
class Outcome:
    returncode: int                # negative: killed by that signal
    timed_out: bool
    output: str                    # stdout and stderr, capped
    output_truncated: bool
    seconds: float
    extra: dict = field(default_factory=dict)


class Stopper:
    """Lets another thread end a run before its wall-clock limit (the grader's
    time limit per test case, for a runner that serves many cases). The run
    then counts as timed out. It ends the whole run, as the run's own end
    does (run() hands it the way): killing the process group alone missed a
    runner that had moved itself into another group of the grader's session
    (setpgid to the grader's own group, fallback by user), and the grading
    then waited for the chapter's whole budget."""

    def __init__(self):
        self._lock = threading.Lock()
        self._kill = None
        self.stopped = False

    def _started(self, kill):
        with self._lock:
            self._kill = kill
            if self.stopped:
                kill()

    def _ended(self):
        with self._lock:
            self._kill = None

    def stop(self):
        with self._lock:
            self.stopped = True
            if self._kill is not None:
                self._kill()


def _kill_group(pgid):
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


_libc_handle = []


def _libc():
    """ctypes' C library, loaded once in the grader (never in a child after fork)."""
    if not _libc_handle:
        import ctypes
        _libc_handle.append(ctypes.CDLL(None, use_errno=True))
    return _libc_handle[0]


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


def _statuses():
    """(pid, {field: value}) of every process, from /proc/PID/status."""
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/status") as f:
                yield int(name), dict(line.split(":", 1) for line in f if ":" in line)
        except (OSError, ValueError):
            pass


def _real_uid(fields):
    return int(fields["Uid"].split()[0])


def _processes_of_uid(uid):
    """Live processes (not zombies, which only wait to be reaped) of uid."""
    return [pid for pid, fields in _statuses()
            if "Uid" in fields and uid in (int(x) for x in fields["Uid"].split())
            and not fields.get("State", "").strip().startswith(("Z", "X"))]


def _zombies_of_uid(uid):
    """How many processes of uid have ended but are not reaped yet."""
    return sum(1 for _, fields in _statuses()
               if "Uid" in fields and _real_uid(fields) == uid and fields.get("State", "").strip().startswith("Z"))


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


def _kill_as(uid, gid):
    """kill(-1, SIGKILL) sent by the sandbox user itself: the kernel delivers it
    to every process of that user in one pass, so a process that keeps forking
    and letting its parent exit cannot slip between listing and killing."""
    def kill_all():   # runs in the child after it became uid (and never execs)
        os.kill(-1, signal.SIGKILL)
        os._exit(0)
    subprocess.Popen(["/bin/true"], user=uid, group=gid, extra_groups=[], preexec_fn=kill_all,
                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).wait()


def _stop_and_kill(find):
    """Without root: stop what find() lists (a stopped process cannot fork),
    list again until nothing new appears, then kill them all."""
    stopped = set()
    for _ in range(100):
        new = [p for p in find() if p != os.getpid() and p not in stopped]
        if not new:
            break
        for p in new:
            try:
                os.kill(p, signal.SIGSTOP)
            except OSError:
                pass
            stopped.add(p)
    for p in stopped:
        try:
            os.kill(p, signal.SIGKILL)
            os.kill(p, signal.SIGCONT)
        except OSError:
            pass


def _kill_run(pgid, iso, user, token, cgroup):
    """Kills every process of a run that is still going (a Stopper's work): its process group,
    its cgroups, and in the fallbacks every process of its user (or with its token)."""
    _kill_group(pgid)
    if cgroup:
        iso.cgroup.kill(cgroup)
    if iso.mode != isolation.NAMESPACES:
        if user is not None:
            _kill_as(*user)
        else:
            _stop_and_kill(lambda: _processes_with_token(token))


def _end_run(pgid, iso, user, token, cgroup):
    """Ends everything the run started."""
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    if cgroup:
        iso.cgroup.kill_and_remove(cgroup)
    if iso.mode == isolation.NAMESPACES:
        return      # the PID namespace ended with its first process, taking every other one along
    if user is not None:
        for _ in range(20):
            _kill_as(*user)
            if not _processes_of_uid(user[0]):
                return
            time.sleep(0.01)
    else:
        _stop_and_kill(lambda: _processes_with_token(token))


def _remove_leftovers(uid, gid):
    """Fallback by user: what the run left in world-writable folders and
    System V IPC (there is no private /tmp to discard)."""
    for folder in WORLD_WRITABLE:
        _remove_entries_of(uid, folder, depth=4)
    # System V objects are removed by their owner, the sandbox user itself: root may remove another
    # user's only with CAP_SYS_ADMIN, which root in a Docker container lacks (a segment left there
    # could carry what a runner saw to the next run of that user).
    remove = []
    for kind, flag, column in (("shm", "-m", 7), ("sem", "-s", 4), ("msg", "-q", 7)):
        try:
            with open(f"/proc/sysvipc/{kind}") as f:
                rows = [line.split() for line in f.readlines()[1:]]
        except OSError:
            continue
        remove += [a for row in rows if len(row) > column and row[column] == str(uid) for a in (flag, row[1])]
    if remove and shutil.which("ipcrm"):
        subprocess.run(["ipcrm", *remove], user=uid, group=gid, extra_groups=[], capture_output=True)


def _remove_entries_of(uid, folder, depth):
    """Removes what uid owns in folder, and in the folders below it that others may write
    (/tmp/.X11-unix, a classmate's 1777 folder): a file hidden one level down would
    otherwise outlive the run. Links are removed, never followed."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        path = os.path.join(folder, name)
        try:
            info = os.lstat(path)
            if info.st_uid == uid:
                fsutil.remove_tree(path)
            elif depth > 0 and stat.S_ISDIR(info.st_mode) and info.st_mode & 0o002:
                _remove_entries_of(uid, path, depth - 1)
        except OSError:
            pass


def _count_own_threads():
    """RLIMIT_NPROC counts threads, not processes, of the real user."""
    uid = os.getuid()
    return sum(int(fields.get("Threads", 0)) for _, fields in _statuses()
               if "Uid" in fields and _real_uid(fields) == uid)


def read_capped(path, cap):
    with open(path, "rb") as f:
        data = f.read(cap + 1)
    truncated = len(data) > cap
    return data[:cap].decode("utf-8", errors="replace"), truncated


def _readable_by_others(path):
    """Can a user that is neither owner nor in the group read path (and reach it)?"""
    path = os.path.abspath(path)
    try:
        info = os.stat(path)
    except OSError:
        return False
    if stat.S_ISDIR(info.st_mode):
        if info.st_mode & 0o005 != 0o005:
            return False
    elif not info.st_mode & 0o005:      # readable, or executable only (the hidden tests' program)
        return False
    parent = os.path.dirname(path)
    while True:
        if os.stat(parent).st_mode & 0o001 == 0:
            return False
        if parent == "/":
            return True
        parent = os.path.dirname(parent)


def _reachable_by_others(folder):
    """Can a user that is neither owner nor in the group enter folder?"""
    while True:
        if os.stat(folder).st_mode & 0o001 == 0:
            return False
        if folder == "/":
            return True
        folder = os.path.dirname(folder)


def _mirror(inputs, mirror_root):
    """Fallback: inputs the sandbox user cannot read (e.g. a repository in
    root's 0700 home) are copied under mirror_root (a folder the grader made,
    traversable by the sandbox user), once per grading. Returns {original: copy}."""
    moved = {}
    for path in inputs:
        path = os.path.abspath(path)
        if _readable_by_others(path):
            continue
        copy = os.path.join(mirror_root, "inputs", path.lstrip(os.sep))
        with _mirror_lock:
            if not os.path.exists(copy):
                os.makedirs(os.path.dirname(copy), mode=0o755, exist_ok=True)
                for d in _ancestors(os.path.dirname(copy), mirror_root):
                    os.chmod(d, 0o755)
                if os.path.isdir(path):
                    shutil.copytree(path, copy, symlinks=True)
                else:
                    shutil.copy2(path, copy)
                _open_up(copy)
        moved[path] = copy
        # An unreadable folder above an input (the repository root on the
        # include path) maps to its copy too, which holds only the inputs.
        parent = os.path.dirname(path)
        while parent != "/" and not _reachable_by_others(parent):
            moved.setdefault(parent, os.path.join(mirror_root, "inputs", parent.lstrip(os.sep)))
            parent = os.path.dirname(parent)
    return moved


def _ancestors(path, stop):
    out = []
    while path.startswith(stop) and path != stop:
        out.append(path)
        path = os.path.dirname(path)
    return out


def _open_up(path):
    if os.path.isdir(path):
        for dirpath, dirnames, filenames in os.walk(path):
            os.chmod(dirpath, 0o755)
            for n in filenames:
                os.chmod(os.path.join(dirpath, n), 0o644)
    else:
        os.chmod(path, 0o755 if os.stat(path).st_mode & 0o100 else 0o644)


def _replace_prefixes(arg, moved):
    """arg with the first (longest) original path in it replaced by its copy."""
    for original in sorted(moved, key=len, reverse=True):
        at = arg.find(original)
        end = at + len(original)
        if at >= 0 and (end == len(arg) or arg[end] == os.sep):
            return arg[:at] + moved[original] + arg[end:]
    return arg


def _bwrap_command(iso, argv, limits, inputs, scratch, cwd, user, seccomp_fd=None, system=None):
    args = [iso.bwrap] + isolation.namespace_args(limits.tmp_bytes, limits.shm_bytes) + isolation.system_binds(system)
    if seccomp_fd is not None:
        args += ["--seccomp", str(seccomp_fd)]
    binds = [("--ro-bind", p) for p in sorted({os.path.abspath(p) for p in inputs})]
    if scratch:
        binds.append(("--bind", os.path.abspath(scratch)))
    made = {"/", "/usr", "/etc", "/tmp", "/dev", "/dev/shm", "/proc"}
    for how, path in sorted(binds, key=lambda b: b[1]):
        parent = os.path.dirname(path)
        missing = []
        while parent not in made:
            missing.append(parent)
            parent = os.path.dirname(parent)
        for d in reversed(missing):   # bwrap would make them 0700, unreachable for the sandbox user
            args += ["--perms", "0755", "--dir", d]
            made.add(d)
        args += [how, path, path]
        made.add(path)
    args += ["--chdir", cwd, "--"]
    if user is not None:
        args += isolation.drop_privileges(iso.setpriv, *user)
    return args + list(argv)


def run(argv, *, limits, log_path, user=None, inputs=(), scratch=None, env_extra=None, pass_fds=(),
        output_cap=64 * 1024, private_root=None, iso=None, stopper=None, system=None):
    """Runs argv in the sandbox under the limits; returns an Outcome.

    user:     (uid, gid) of the sandbox user (root), or None (the grader's own user)
    inputs:   files and folders it may read (bound read-only at their own path;
              in the fallback, copied under private_root when the user cannot read them)
    scratch:  a folder it may write, its working folder; None: a private empty
              folder (/tmp of its own in namespaces mode), discarded afterwards
    private_root: a folder of the grader's, traversable by the sandbox user, for
              the fallback's copies and private folders (default: the system's temp folder)
    pass_fds: descriptors it inherits (pipes to the grader)
    stopper:  a Stopper another thread may use to end the run early (then timed out)
    system:   namespaces mode: a private copy of the system files it needs (isolation.private_system),
              bound in place of /usr and /etc's files
    """
    iso = iso or isolation.detect()
    counts["runs"] += 1
    inputs = list(inputs)
    program = os.path.abspath(argv[0]) if os.path.isabs(argv[0]) else None
    if program and not program.startswith(("/usr/", "/bin/")) and not (
            scratch and program.startswith(os.path.abspath(scratch) + os.sep)):
        inputs.append(program)     # the program itself is always an input
    token = secrets.token_hex(8)
    private_root = private_root or "/tmp"
    moved, own_cwd = {}, None
    seccomp_fd = None
    program_bytes = iso.syscall_filter   # no user namespaces, no keyrings, no 32-bit calls (isolation.py)
    install_filter = isolation.syscall_filter_installer(program_bytes, _libc()) \
        if program_bytes and iso.mode != isolation.NAMESPACES else None
    if iso.mode == isolation.NAMESPACES:
        cwd = os.path.abspath(scratch) if scratch else "/tmp"
        if program_bytes:
            seccomp_fd, w = os.pipe()
            os.write(w, program_bytes)
            os.close(w)
            pass_fds = tuple(pass_fds) + (seccomp_fd,)
        cmd = _bwrap_command(iso, argv, limits, inputs, scratch, cwd, user, seccomp_fd, system)
    else:
        if user is not None:
            moved = _mirror(inputs, private_root)
        if scratch:
            cwd = os.path.abspath(scratch)
        else:
            own_cwd = cwd = fsutil.new_private_folder(private_root, user)
        cmd = [_replace_prefixes(a, moved) for a in argv]
        if user is not None and iso.setpriv:
            cmd = isolation.drop_privileges(iso.setpriv, *user) + cmd
    env = {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": cwd,
        "TMPDIR": "/tmp" if iso.mode == isolation.NAMESPACES else cwd,
        "LANG": "C.UTF-8",
        "MALLOC_ARENA_MAX": "2",        # threads' malloc arenas would eat the address-space limit
        "RT_GRADER_TOKEN": token,
    }
    env.update(env_extra or {})
    if user is None and iso.mode != isolation.NAMESPACES:
        nproc = _count_own_threads() + limits.processes
    elif user is None:
        nproc = _count_own_threads() + limits.processes + 8
    else:
        # RLIMIT_NPROC counts the user's zombies too, until init reaps them (slowly on some machines):
        # those a previous run left (killed orphans) must not take this run's processes.
        nproc = limits.processes + _zombies_of_uid(user[0])
    cgroup = iso.cgroup.create(limits.memory_bytes, limits.processes + 8) if iso.cgroup else None

    def prepare_child():  # runs in the child (as root when root), just before exec
        isolation.leave_terminal()
        if cgroup and os.geteuid() == os.getuid():
            isolation.join_cgroup(cgroup)
        resource.setrlimit(resource.RLIMIT_CPU, (limits.cpu_seconds, limits.cpu_seconds + 1))
        resource.setrlimit(resource.RLIMIT_AS, (limits.memory_bytes, limits.memory_bytes))
        resource.setrlimit(resource.RLIMIT_FSIZE, (limits.file_bytes, limits.file_bytes))
        resource.setrlimit(resource.RLIMIT_NPROC, (nproc, nproc))
        resource.setrlimit(resource.RLIMIT_NOFILE, (limits.open_files, limits.open_files))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        if install_filter is not None:      # without bwrap, the filter is installed here
            install_filter()

    kwargs = {}
    if user is not None and iso.mode != isolation.NAMESPACES and not iso.setpriv:
        kwargs.update(user=user[0], group=user[1], extra_groups=[])
    start = time.monotonic()
    try:
        with open(log_path, "wb") as log:
            proc = subprocess.Popen(cmd, cwd=cwd if iso.mode != isolation.NAMESPACES else "/",
                                    env=env, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                    process_group=0, preexec_fn=prepare_child, pass_fds=pass_fds,
                                    close_fds=True, **kwargs)
        if seccomp_fd is not None:
            os.close(seccomp_fd)
            seccomp_fd = None
        if stopper is not None:
            stopper._started(lambda: _kill_run(proc.pid, iso, user, token, cgroup))
        timed_out = False
        try:
            proc.wait(timeout=limits.wall_seconds)
        except subprocess.TimeoutExpired:
            timed_out = True
        if stopper is not None:
            stopper._ended()
            timed_out = timed_out or stopper.stopped
        oom = bool(cgroup) and iso.cgroup.oom_killed(cgroup)
        _end_run(proc.pid, iso, user, token, cgroup)
        proc.wait()
    finally:
        if seccomp_fd is not None:
            os.close(seccomp_fd)
        if cgroup and any(os.path.isdir(p) for p in cgroup):
            iso.cgroup.kill_and_remove(cgroup)
        if iso.mode != isolation.NAMESPACES and user is not None:
            _remove_leftovers(*user)
        if own_cwd:
            fsutil.remove_tree(own_cwd)
    seconds = time.monotonic() - start
    output, truncated = read_capped(log_path, output_cap)
    for original, copy in sorted(moved.items(), key=lambda m: len(m[1]), reverse=True):
        output = output.replace(copy, original)
    rc = proc.returncode
    if iso.mode == isolation.NAMESPACES and 128 < rc < 128 + 65:
        rc = -(rc - 128)      # bwrap reports "killed by signal N" as exit status 128 + N
    if oom and rc >= 0:
        rc = -signal.SIGKILL
    return Outcome(rc, timed_out, output, truncated, seconds, {"oom": oom, "mode": iso.mode})


def run_limited(cmd, cwd, limits, log_path, user=None, env_extra=None, pass_fds=(), output_cap=64 * 1024,
                inputs=()):
    """Earlier interface: cwd becomes the run's scratch folder."""
    return run(cmd, limits=limits, log_path=log_path, user=user, inputs=inputs, scratch=cwd, env_extra=env_extra,
               pass_fds=pass_fds, output_cap=output_cap, private_root=os.path.dirname(os.path.abspath(cwd)))


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
        signal.SIGKILL: "was killed (it went past a time or memory limit; the memory limit counts memfd and "
                        "/dev/shm files too)",
        signal.SIGILL: "crashed with an illegal instruction",
    }
    return reasons.get(sig, f"was killed by signal {signal.Signals(sig).name if sig in signal.valid_signals() else sig}")


# Top folders of the instructor's source a compile may see when its include
# path names the repository root (`#include "common/math.hpp"`): the shared
# code and the chapters' headers. Never solutions/, tests/ or tools/.
PUBLIC_TOP = ("common", "chapters")


def include_inputs(args, source_root, public_top=PUBLIC_TOP):
    """What a compile command may read of the instructor's tree: its include
    folders, the repository root narrowed to public_top. Folders outside the
    tree (the system's) are already part of every sandbox."""
    source_root = os.path.abspath(source_root)
    folders = []
    it = iter(args)
    for a in it:
        for flag in ("-I", "-isystem", "-iquote", "-idirafter"):
            if a == flag:
                folders.append(next(it, ""))
            elif a.startswith(flag) and len(a) > len(flag) and flag == "-I":
                folders.append(a[2:])
    inputs = []
    for d in folders:
        d = os.path.abspath(d)
        if d == source_root:
            inputs += [os.path.join(d, t) for t in public_top if os.path.isdir(os.path.join(d, t))]
        elif d.startswith(source_root + os.sep) and os.path.isdir(d):
            rel = os.path.relpath(d, source_root).split(os.sep)[0]
            if rel in public_top:
                inputs.append(d)
    return sorted(set(inputs))
