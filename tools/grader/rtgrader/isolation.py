"""What this machine lets the grader use to contain a student's code.

Three modes, best first (tools/grader/README.md, "Isolation"):

  namespaces  bubblewrap (Debian's `bwrap`) runs each process in its own mount
              namespace (only the files it needs, a private /tmp and
              /dev/shm), PID namespace (nothing outlives the run), network,
              IPC and UTS namespaces. As root the code then runs as an
              unprivileged sandbox user.
  users       no namespaces (a container that forbids them, or forced):
              as root, the code runs as an unprivileged sandbox user that
              cannot read the private files; leftovers are found and removed
              by that user's id. Said loudly in the output and results.json.
  none        no namespaces and not root: the code runs as the grader's own
              user with resource limits only. Said loudly too.

Independently, a cgroup per run when the grader may create cgroups (class
Cgroups): in cgroup v2, cgroup.kill ends every process of the run at once, and
memory.max (which counts memfd and tmpfs pages, unlike the address-space
limit) and pids.max when those controllers can be enabled; a controller that
v2 lacks is taken from a cgroup v1 hierarchy where the machine has one
(memory.limit_in_bytes counts the same pages).

RT_GRADER_ISOLATION=fallback (or users / none) forces the fallback, e.g.
in the grader's own tests; RT_GRADER_CGROUP=off turns cgroups off.
"""

import os
import re
import shutil
import subprocess
import threading
from dataclasses import dataclass, field

NAMESPACES, USERS, NONE = "namespaces", "users", "none"
_lock = threading.Lock()
_cached = {}


@dataclass
class Isolation:
    mode: str
    bwrap: str = None
    setpriv: str = None
    cgroup: "Cgroups" = None
    notes: list = field(default_factory=list)   # loud warnings for the output and results.json
    syscall_filter: bytes = None                 # syscall_filter()'s program when it can be used here

    def describe(self):
        """One line for the grader's output."""
        what = {NAMESPACES: "namespaces (bubblewrap: private files, /tmp, processes and network)",
                USERS: "FALLBACK by user (no namespaces): unprivileged user, limits, clean-up by user id",
                NONE: "FALLBACK, limits only (no namespaces, not root)"}[self.mode]
        cg = self.cgroup.describe() if self.cgroup else "no cgroup"
        return f"isolation: {what}; {cg}"


def system_binds(root=None):
    """bwrap arguments for the read-only system: /usr and the usual links to it,
    and only the few files of /etc the compiler and the dynamic loader read.
    root: a private copy of the few system files a program needs (private_system), bound in
    their place."""
    args = ["--ro-bind", os.path.join(root, "usr") if root else "/usr", "/usr"]
    for top in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        path = "/" + top
        if os.path.islink(path):
            args += ["--symlink", os.readlink(path), path]
        elif os.path.isdir(path):
            args += ["--ro-bind", path, path]
    args += ["--perms", "0755", "--dir", "/etc"]
    for name in ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "alternatives"):
        if os.path.exists((root or "") + "/etc/" + name):
            args += ["--ro-bind", (root or "") + "/etc/" + name, "/etc/" + name]
    return args


def _needed(path):
    """The sonames an ELF file asks the dynamic loader for (readelf reads it; nothing runs it)."""
    out = subprocess.run(["readelf", "-dW", path], capture_output=True, text=True, timeout=30).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]/]+)\]", out)


# Where the loader looks for a soname by default (Debian's multiarch folders first).
LIBRARY_FOLDERS = ("/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu", "/lib64", "/usr/lib64", "/lib", "/usr/lib")


def _library_path(soname):
    """The file the dynamic loader would take for soname from the system's folders, or None."""
    for folder in LIBRARY_FOLDERS:
        path = os.path.join(folder, soname)
        if os.path.exists(path):
            return path
    return None


def private_system(folder, programs, interpreter="/lib64/ld-linux-x86-64.so.2"):
    """Copies into folder (its usr/ and etc/) the system files programs need to start: the dynamic
    loader, the libraries they ask for (and those ask for), /etc/ld.so.cache. A sandbox given this
    folder (system_binds(root=folder)) in place of /usr shares no system file with any other run:
    which of its pages are cached (the page cache is the machine's) then says nothing to a later
    run, which sees only its own files ("Visible before hidden", the hidden phase). Returns folder."""
    wanted, pending, seen = {interpreter}, list(programs), set()
    while pending:
        path = pending.pop()
        if path in seen:
            continue
        seen.add(path)
        for soname in _needed(path):
            found = _library_path(soname)
            if found:
                wanted.add(found)
                pending.append(found)
    for path in sorted(wanted | {p for p in programs if p.startswith(("/usr/", "/bin/", "/sbin/"))}) + \
            ["/etc/ld.so.cache"]:
        if not os.path.exists(path):
            continue
        # Where the sandbox will look for it: /lib, /lib64 and /bin are links into /usr.
        at = os.path.join(os.path.realpath(os.path.dirname(path)), os.path.basename(path))
        copy = os.path.join(folder, at.lstrip("/"))
        os.makedirs(os.path.dirname(copy), mode=0o755, exist_ok=True)
        if not os.path.exists(copy):
            shutil.copy2(os.path.realpath(path), copy)
    for top, dirs, _ in os.walk(folder):
        os.chmod(top, 0o755)
    return folder


def namespace_args(tmp_bytes, shm_bytes):
    """The namespaces and the private, size-limited /tmp and /dev/shm."""
    args = ["--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try",
            "--die-with-parent", "--proc", "/proc", "--dev", "/dev",
            "--perms", "1777", "--size", str(tmp_bytes), "--tmpfs", "/tmp",
            "--perms", "1777", "--size", str(shm_bytes), "--tmpfs", "/dev/shm"]
    if os.geteuid() != 0:
        # Unprivileged bwrap works in a user namespace; forbid the code a further one.
        args = ["--unshare-user", "--disable-userns"] + args
    return args


def leave_terminal():
    """In the child, before exec: give up the controlling terminal (TIOCNOTTY), so the sandboxed
    code cannot write to the instructor's terminal or push input into it (TIOCSTI) through
    /dev/tty. This, not a new session (setsid, bwrap --new-session), because a new session is a
    new scheduling group (autogroup): under load every call between the judge, in the grader's
    session, and a runner in a session of its own waited for the other group's turn (a chapter's
    calls took 6 times longer)."""
    import fcntl
    import termios
    try:
        fd = os.open("/dev/tty", os.O_RDWR | os.O_NOCTTY)
    except OSError:
        return      # no controlling terminal
    try:
        fcntl.ioctl(fd, termios.TIOCNOTTY)
    finally:
        os.close(fd)


def drop_privileges(setpriv, uid, gid):
    """As root: the command that turns the process into the sandbox user
    (no groups, no capabilities, no setuid programs)."""
    return [setpriv, f"--reuid={uid}", f"--regid={gid}", "--clear-groups", "--inh-caps=-all",
            "--bounding-set=-all", "--no-new-privs", "--"]


def _probe_bwrap(bwrap, setpriv):
    """'' when a bwrap sandbox starts here (and can drop to an unprivileged
    user when root), else why not."""
    cmd = [bwrap] + namespace_args(1 << 20, 1 << 20) + system_binds() + ["--"]
    if os.geteuid() == 0:
        cmd += drop_privileges(setpriv, 65534, 65534)
    cmd += ["/bin/sh", "-c", "test ! -e /etc/passwd && test -d /proc/self && echo ok"]
    try:
        result = subprocess.run(cmd, capture_output=True, text=True, timeout=30, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired) as e:
        return f"bwrap could not be run: {e}"
    if result.returncode == 0 and result.stdout.strip() == "ok":
        return ""
    return f"bwrap failed here (exit {result.returncode}): {(result.stderr or result.stdout).strip()[:300]}"


def detect():
    """The isolation this machine allows (found once per process)."""
    forced = os.environ.get("RT_GRADER_ISOLATION", "auto").strip().lower()
    with _lock:
        if forced in _cached:
            return _cached[forced]
        root = os.geteuid() == 0
        fallback = USERS if root else NONE
        iso = None
        bwrap = shutil.which("bwrap")
        setpriv = shutil.which("setpriv")
        if forced in ("fallback", "users", "none"):
            iso = Isolation(fallback, setpriv=setpriv,
                            notes=[f"namespaces turned off (RT_GRADER_ISOLATION={forced})"])
        else:
            if not bwrap:
                why = "bubblewrap (bwrap) is not installed (Debian package bubblewrap, tools/debian-packages.txt)"
            elif root and not setpriv:
                why = "setpriv (util-linux) is missing"
            else:
                why = _probe_bwrap(bwrap, setpriv)
            if why:
                iso = Isolation(fallback, setpriv=setpriv, notes=[f"no namespaces: {why}"])
            else:
                iso = Isolation(NAMESPACES, bwrap=bwrap, setpriv=setpriv)
        if iso.mode != NAMESPACES:
            iso.notes.append(
                "WARNING: the submission ran WITHOUT the namespace sandbox, "
                + ("as an unprivileged user with resource limits (files readable by every user, the grader's "
                   "command line and the network were within its reach)" if root else
                   "as the grader's own user with resource limits only (it could read anything this user can)"))
        if os.environ.get("RT_GRADER_CGROUP", "auto").lower() != "off":
            iso.cgroup = Cgroups.detect()
        iso.notes.append(_memory_note(iso.cgroup))
        iso.syscall_filter = syscall_filter()
        why = _probe_filter(iso.syscall_filter) if iso.syscall_filter and iso.mode != NAMESPACES else ""
        if why or not iso.syscall_filter:
            iso.syscall_filter = None
            iso.notes.append("no seccomp filter here (" + (why or "not x86-64") + "): the kernel's keyrings, "
                             "user namespaces and the 32-bit system calls were within the code's reach")
        _cached[forced] = iso
        return iso


def _probe_filter(program):
    """'' when a process here can install the filter itself (the fallbacks; a container may forbid it),
    else why not."""
    import ctypes
    install = syscall_filter_installer(program, ctypes.CDLL(None, use_errno=True))
    try:
        done = subprocess.run(["/bin/true"], preexec_fn=install, timeout=30, capture_output=True)
    except (OSError, subprocess.SubprocessError) as e:
        return str(e)
    return "" if done.returncode == 0 else "prctl(PR_SET_SECCOMP) is refused"


def _memory_note(cgroup):
    """Which mechanism bounds a run's memory, memfd and /dev/shm included (results.json's notes)."""
    if cgroup and "memory" in cgroup.controllers:
        return "memory limit per run: cgroup v2 memory.max (memfd and /dev/shm pages included)"
    if cgroup and "memory" in cgroup.v1:
        return "memory limit per run: cgroup v1 memory controller (memfd and /dev/shm pages included)"
    return ("memory limit per run: address-space and file-size limits only (no memory cgroup here): memfd and "
            "/dev/shm pages are bounded by the file-size limit times the open-files limit")


class Cgroups:
    """A cgroup per run, below one the grader creates inside its own: in the
    cgroup v2 hierarchy (cgroup.kill; memory.max and pids.max when those
    controllers are delegated there) and, for a controller v2 lacks but a
    cgroup v1 hierarchy has (the course VM binds memory and pids to v1), in
    that v1 hierarchy: memory.limit_in_bytes and memory.memsw.limit_in_bytes
    (which count the shmem pages of memfd, /dev/shm and tmpfs files, like
    memory.max) and pids.max. A run's cgroup is the list of its folders."""

    def __init__(self, base, controllers, can_kill, v1=None):
        self.base = base                      # v2 folder of this grader, or None
        self.controllers = controllers        # subset of {"memory", "pids"} enabled in v2
        self.can_kill = can_kill              # cgroup.kill exists (Linux 5.14)
        self.v1 = v1 or {}                    # controller -> v1 folder of this grader
        self._counter = 0
        self._count_lock = threading.Lock()

    def describe(self):
        parts = []
        if self.base:
            enabled = ", ".join(sorted(self.controllers)) or "no memory/pids controllers (not delegated here)"
            parts.append(f"cgroup v2 per run in {self.base} ({enabled}{'; cgroup.kill' if self.can_kill else ''})")
        for c, folder in sorted(self.v1.items()):
            what = {"memory": "memory.limit_in_bytes + memsw, counting memfd and /dev/shm",
                    "pids": "pids.max"}[c]
            parts.append(f"cgroup v1 {c} per run in {folder} ({what})")
        return "; ".join(parts) or "no cgroup"

    def counted(self):
        """Which limits a run's cgroup enforces: {'memory', 'pids'} or a part of it."""
        return set(self.controllers) | set(self.v1)

    @classmethod
    def detect(cls):
        v2 = cls._detect_v2()
        base, controllers, can_kill = v2 if v2 else (None, set(), False)
        v1 = {}
        for c in ("memory", "pids"):
            if c not in controllers:
                folder = _make_v1_base(c)
                if folder:
                    v1[c] = folder
        if not base and not v1:
            return None
        import atexit
        for folder in [base] + list(v1.values()):
            if folder:
                atexit.register(_remove_quietly, folder)
        return cls(base, controllers, can_kill, v1)

    @staticmethod
    def _detect_v2():
        mount = _mount_points().get("cgroup2")
        own = _own_cgroups().get("")
        if not mount or own is None:
            return None
        parent = os.path.normpath(mount + "/" + own)
        _remove_stale(parent)
        base = os.path.join(parent, f"rt-grader-{os.getpid()}")
        try:
            os.makedirs(base, exist_ok=True)
        except OSError:
            return None
        controllers = set()
        for c in ("memory", "pids"):
            # A controller reaches our runs only when enabled in the parent's and our base's subtree.
            if _enable(parent, c) and _enable(base, c):
                controllers.add(c)
        return base, controllers, os.path.exists(os.path.join(base, "cgroup.kill"))

    def create(self, memory_bytes, processes):
        """New cgroups for one run, with its limits; returns their folders (a list) or None."""
        with self._count_lock:
            self._counter += 1
            n = self._counter
        made = []
        if self.base:
            path = os.path.join(self.base, f"run-{n}")
            try:
                os.mkdir(path)
                made.append(path)
            except OSError:
                pass
            else:
                if "memory" in self.controllers:
                    _write(path, "memory.max", str(memory_bytes))
                    _write(path, "memory.swap.max", "0")
                if "pids" in self.controllers:
                    _write(path, "pids.max", str(processes))
        for c, folder in sorted(self.v1.items()):
            path = os.path.join(folder, f"run-{n}")
            try:
                os.mkdir(path)
            except OSError:
                continue
            made.append(path)
            if c == "memory":
                # memsw (memory + swap) after the memory limit: it may never be below it.
                _write(path, "memory.limit_in_bytes", str(memory_bytes))
                _write(path, "memory.memsw.limit_in_bytes", str(memory_bytes))
            else:
                _write(path, "pids.max", str(processes))
        return made or None

    @staticmethod
    def oom_killed(paths):
        for path in paths:
            for name, key in (("memory.events", "oom_kill"), ("memory.oom_control", "oom_kill")):
                try:
                    with open(os.path.join(path, name)) as f:
                        if any(line.split()[0] == key and int(line.split()[1]) > 0 for line in f if line.strip()):
                            return True
                except (OSError, ValueError, IndexError):
                    pass
        return False

    def kill(self, paths):
        """Ends every process of the run now (cgroup.kill, or one by one), leaving the cgroups."""
        for path in paths:
            _kill_members(path)

    def kill_and_remove(self, paths):
        """Ends every process of the run (all at once with cgroup.kill) and removes its cgroups."""
        import time
        done = True
        for path in paths:
            for _ in range(200):
                _kill_members(path)
                try:
                    os.rmdir(path)
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(0.005)  # still populated: the kill takes a moment
            else:
                done = False
        return done


def _mount_points():
    """{'cgroup2': folder, 'memory': folder, 'pids': folder, ...} of the cgroup mounts."""
    found = {}
    try:
        with open("/proc/self/mountinfo") as f:
            for line in f:
                left, _, right = line.partition(" - ")
                fields = right.split()
                if not fields:
                    continue
                if fields[0] == "cgroup2":
                    found.setdefault("cgroup2", left.split()[4])
                elif fields[0] == "cgroup" and len(fields) >= 3:
                    for option in fields[2].split(","):
                        found.setdefault(option, left.split()[4])
    except OSError:
        pass
    return found


def _own_cgroups():
    """{'': v2 path, 'memory': v1 path, ...} of this process (/proc/self/cgroup)."""
    found = {}
    try:
        with open("/proc/self/cgroup") as f:
            for line in f:
                _, controllers, path = line.rstrip("\n").split(":", 2)
                for c in controllers.split(",") if controllers else [""]:
                    found[c] = path
    except (OSError, ValueError):
        pass
    return found


def _make_v1_base(controller):
    """This grader's folder in the cgroup v1 hierarchy of controller, inside its own cgroup there
    (so whatever contains the grader still contains its runs), or None."""
    mount = _mount_points().get(controller)
    own = _own_cgroups().get(controller)
    if not mount or own is None:
        return None
    parent = os.path.normpath(mount + "/" + own)
    _remove_stale(parent)
    base = os.path.join(parent, f"rt-grader-{os.getpid()}")
    limit = "memory.limit_in_bytes" if controller == "memory" else "pids.max"
    try:
        os.makedirs(base, exist_ok=True)
        probe = os.path.join(base, "probe")
        os.makedirs(probe, exist_ok=True)
        ok = _write(probe, limit, str(1 << 30) if controller == "memory" else "64")
        os.rmdir(probe)
    except OSError:
        ok = False
    if not ok:
        _remove_quietly(base)
        return None
    return base


def join_cgroup(paths):
    """In the child, before exec: move this process into the run's cgroups."""
    for path in paths:
        fd = os.open(os.path.join(path, "cgroup.procs"), os.O_WRONLY)
        try:
            os.write(fd, b"0")
        finally:
            os.close(fd)


def _pids(path):
    try:
        with open(os.path.join(path, "cgroup.procs")) as f:
            return [int(x) for x in f.read().split()]
    except OSError:
        return []


def _enable(folder, controller):
    try:
        with open(os.path.join(folder, "cgroup.subtree_control")) as f:
            if controller in f.read().split():
                return True
        with open(os.path.join(folder, "cgroup.controllers")) as f:
            if controller not in f.read().split():
                return False
        return _write(folder, "cgroup.subtree_control", "+" + controller)
    except OSError:
        return False


def _write(folder, name, value):
    try:
        with open(os.path.join(folder, name), "w") as f:
            f.write(value)
        return True
    except OSError:
        return False


def _kill_members(path):
    """Kills the processes of a cgroup: all at once with cgroup.kill (v2), else one by one (v1:
    called again until the cgroup can be removed, so a process forked meanwhile is caught too)."""
    import signal
    if _write(path, "cgroup.kill", "1"):
        return
    for pid in _pids(path):
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def _remove_quietly(base):
    try:
        for name in os.listdir(base):
            path = os.path.join(base, name)
            if name.startswith(("run-", "probe")) and os.path.isdir(path):
                _kill_members(path)
                try:
                    os.rmdir(path)
                except OSError:
                    pass
        os.rmdir(base)
    except OSError:
        pass


def _remove_stale(parent):
    """Cgroups left by graders that were killed (their process is gone)."""
    try:
        names = os.listdir(parent)
    except OSError:
        return
    for name in names:
        pid = name[len("rt-grader-"):]
        if name.startswith("rt-grader-") and pid.isdigit() and not os.path.exists(f"/proc/{pid}"):
            _remove_quietly(os.path.join(parent, name))


def syscall_filter():
    """A seccomp program (classic BPF, as bwrap --seccomp reads it and
    prctl(PR_SET_SECCOMP) takes it) for every sandboxed process, x86-64 only
    (elsewhere None: every call is allowed). It refuses:
    - user namespaces of its own: unshare() and clone() with CLONE_NEWUSER fail
      with EPERM, clone3() (whose flags live in memory a filter cannot read)
      with ENOSYS, so the C library falls back to clone(). Without it, root's
      sandbox user could still reach the kernel's namespace code;
    - the kernel's keyrings (add_key, request_key, keyctl: ENOSYS). A user's
      keyring belongs to its user id, not to a mount or PID namespace: a key
      the runner adds (holding hidden inputs) would still be there for the
      chapter program of the same user, which prints into visible feedback,
      and for the next submission graded by that user;
    - every call of the other system call ABIs (32-bit `int $0x80`, x32):
      ENOSYS. The filter reads call numbers of one ABI; without this, the
      32-bit numbers would pass unchecked.
    Returns bytes."""
    import platform
    import struct
    if platform.machine() != "x86_64":
        return None
    ld_abs, jeq, jge, jset, ret = 0x20, 0x15, 0x35, 0x45, 0x06   # BPF_LD|W|ABS, BPF_JMP|{JEQ,JGE,JSET}|K, BPF_RET|K
    allow, eperm, enosys = 0x7fff0000, 0x00050000 | 1, 0x00050000 | 38
    arch_x86_64, x32_bit = 0xc000003e, 0x40000000
    nr_clone, nr_unshare, nr_clone3, nr_add_key, nr_request_key, nr_keyctl = 56, 272, 435, 248, 249, 250
    clone_newuser = 0x10000000
    # (code, label if true, label if false, k); labels become the jump offsets below.
    program = [
        ("start", ld_abs, None, None, 4),               # A = arch
        (None, jeq, None, "deny", arch_x86_64),         # another ABI: ENOSYS
        (None, ld_abs, None, None, 0),                  # A = system call number
        (None, jge, "deny", None, x32_bit),             # x32 calls: ENOSYS
        (None, jeq, "flags", None, nr_clone),
        (None, jeq, "flags", None, nr_unshare),
        (None, jeq, "deny", None, nr_clone3),
        (None, jeq, "deny", None, nr_add_key),
        (None, jeq, "deny", None, nr_request_key),
        (None, jeq, "deny", None, nr_keyctl),
        (None, ret, None, None, allow),
        ("flags", ld_abs, None, None, 16),              # A = low half of the first argument (the flags)
        (None, jset, "refuse", None, clone_newuser),
        (None, ret, None, None, allow),
        ("refuse", ret, None, None, eperm),
        ("deny", ret, None, None, enosys),
    ]
    where = {label: i for i, (label, *_) in enumerate(program) if label}

    def offset(i, label):       # a jump skips that many instructions after the next one
        return 0 if label is None else where[label] - i - 1
    return b"".join(struct.pack("=HBBI", code, offset(i, yes), offset(i, no), k)
                    for i, (_, code, yes, no, k) in enumerate(program))


def syscall_filter_installer(program, libc):
    """Where no bwrap installs it: a function for the child, before exec, that installs
    program (syscall_filter()'s bytes) with prctl (then inherited by setpriv and the code).
    Everything is prepared here, in the grader: the child only makes two calls. libc is
    ctypes' C library, loaded in the grader. A child that cannot install it ends (126):
    detect() checks once that it can (_probe_filter)."""
    import ctypes

    class SockFprog(ctypes.Structure):
        _fields_ = [("len", ctypes.c_ushort), ("filter", ctypes.c_char_p)]
    prog = SockFprog(len(program) // 8, program)
    pointer = ctypes.byref(prog)

    def install():
        # No new privileges first, root too: a root without CAP_SYS_ADMIN (a container's) may not
        # install a filter otherwise; setpriv, run next, gives privileges up and gains none.
        if libc.prctl(38, 1, 0, 0, 0) != 0:                           # PR_SET_NO_NEW_PRIVS
            os._exit(126)
        if libc.prctl(22, 2, pointer, 0, 0) != 0:                     # PR_SET_SECCOMP, SECCOMP_MODE_FILTER
            os._exit(126)
    install.keep = (prog, program)      # alive as long as the function
    return install
