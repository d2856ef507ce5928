"""Files the grader (often root) reads from or writes next to a student.

Root must never follow a link a student planted: a symbolic link would make
it read the instructor's files into the submission, or write results through
the link onto a file the student chose; a hard link to a file the student
cannot read looks like a plain file but is the instructor's. So:

- a submission's file is opened component by component with O_NOFOLLOW
  (a linked folder on the way is refused too), must be a regular file with a
  single link, and is read once, capped;
- what the grader writes (results, renders, the lock) goes into folders it
  created itself and checked (a real folder, owned by the grader, writable
  by nobody else), with O_CREAT|O_EXCL|O_NOFOLLOW, so an existing entry of
  any kind is never written through.
"""

import errno
import fcntl
import os
import stat
from contextlib import contextmanager


class Refused(Exception):
    """A file the grader will not take or write; the text says why."""


def _open_beneath(root, rel):
    """An O_RDONLY descriptor of root/rel, no link followed below root."""
    parts = [p for p in rel.split(os.sep) if p not in ("", ".")]
    if not parts or ".." in parts:
        raise Refused(f"{rel}: not a path inside the submission")
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        for part in parts[:-1]:
            try:
                nxt = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
            except OSError as e:
                if e.errno in (errno.ELOOP, errno.ENOTDIR):
                    raise Refused(f"{part} (on the way to {rel}) is a link or not a folder: "
                                  "submit real folders and files") from None
                raise
            os.close(fd)
            fd = nxt
        # Looked at before it is opened: opening a device node (a tar unpacked by root makes them)
        # can act on the device (a watchdog, a tape), and a fifo or socket is nothing to compile.
        seen = os.stat(parts[-1], dir_fd=fd, follow_symlinks=False)
        if stat.S_ISLNK(seen.st_mode):
            raise Refused(f"{parts[-1]} is a link, not a file: submit the file itself")
        if not stat.S_ISREG(seen.st_mode):
            raise Refused(f"{parts[-1]} is not a regular file")
        try:
            opened = os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_NOCTTY, dir_fd=fd)
        except OSError as e:
            if e.errno == errno.ELOOP:
                raise Refused(f"{parts[-1]} is a link, not a file: submit the file itself") from None
            raise
        now = os.fstat(opened)
        if (now.st_dev, now.st_ino) != (seen.st_dev, seen.st_ino):
            os.close(opened)
            raise Refused(f"{parts[-1]} changed while the grader read it")
        return opened
    finally:
        os.close(fd)


def read_student_file(root, rel, cap):
    """The bytes of the student's file root/rel (a relative path), read once.
    Raises Refused for a link (symbolic or hard), a special file or a file
    over cap bytes; OSError when it does not exist."""
    fd = _open_beneath(root, rel)
    try:
        info = os.fstat(fd)
        name = os.path.basename(rel)
        if not stat.S_ISREG(info.st_mode):
            raise Refused(f"{name} is not a regular file")
        if info.st_nlink != 1:
            raise Refused(f"{name} is a hard link ({info.st_nlink} names for one file): submit a copy of the file")
        if info.st_size > cap:
            raise Refused(f"{name} is larger than {cap // (1024 * 1024)} MiB")
        return _read_fd(fd, cap, name)
    finally:
        os.close(fd)


def read_regular(path, cap):
    """The bytes of a file the sandbox user wrote (an object file, a picture),
    with the same refusals: no link of either kind, regular, at most cap bytes."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise Refused(f"{os.path.basename(path)} is a link, not a file") from None
        raise
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_nlink != 1:
            raise Refused(f"{os.path.basename(path)} is not a plain file")
        if info.st_size > cap:
            raise Refused(f"{os.path.basename(path)} is larger than {cap // (1024 * 1024)} MiB")
        return _read_fd(fd, cap, os.path.basename(path))
    finally:
        os.close(fd)


def _read_fd(fd, cap, name):
    chunks, total = [], 0
    while True:
        chunk = os.read(fd, min(1 << 20, cap + 1 - total))
        if not chunk:
            break
        chunks.append(chunk)
        total += len(chunk)
        if total > cap:
            raise Refused(f"{name} is larger than {cap // (1024 * 1024)} MiB")
    return b"".join(chunks)


def own_folder(path, mode=0o755):
    """Creates path (and its parents) if missing and checks it is a real
    folder of this user that nobody else can write; returns its absolute path.
    A folder a student could write into is refused: a link planted there
    would redirect what the grader writes."""
    path = os.path.abspath(path)
    os.makedirs(path, mode=mode, exist_ok=True)
    info = os.lstat(path)
    if not stat.S_ISDIR(info.st_mode):
        raise Refused(f"{path} is not a folder (a link?): the grader writes only into its own folders")
    if info.st_uid != os.geteuid():
        raise Refused(f"{path} belongs to user {info.st_uid}, not to the grader: choose another output folder")
    if info.st_mode & 0o022:      # ours, but others could plant links in it: close it
        os.chmod(path, stat.S_IMODE(info.st_mode) & ~0o022)
    return path


def fresh_folder(parent, name, mode=0o755):
    """parent/name as an empty folder this user owns: whatever was there
    (a file, a link, a folder with anything in it) is removed first, never followed."""
    parent = own_folder(parent)
    target = os.path.join(parent, name)
    remove_tree(target)
    os.mkdir(target, mode)
    return own_folder(target, mode)


def remove_tree(path):
    """Removes path whatever it is, following no link (a link is removed itself)."""
    import shutil
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return
    if stat.S_ISDIR(info.st_mode):
        shutil.rmtree(path)          # fd-based on Linux: never follows a link inside
    else:
        os.unlink(path)


def write_new(folder, name, data, mode=0o644):
    """Writes data into folder/name, a new file: an existing entry (file or
    link) is unlinked first, and the file is created with O_EXCL|O_NOFOLLOW
    relative to the folder's descriptor."""
    dfd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW)
    try:
        try:
            os.unlink(name, dir_fd=dfd)
        except FileNotFoundError:
            pass
        except IsADirectoryError:
            raise Refused(f"{os.path.join(folder, name)} is a folder") from None
        fd = os.open(name, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, mode, dir_fd=dfd)
        with os.fdopen(fd, "wb") as f:
            f.write(data)
    finally:
        os.close(dfd)


def write_atomic(path, data, mode=0o644):
    """Writes path atomically (a new temporary file in the same folder, then a
    rename, which replaces a link rather than following it)."""
    folder, name = os.path.split(os.path.abspath(path))
    tmp = f".{name}.{os.getpid()}.tmp"
    write_new(folder, tmp, data, mode)
    dfd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW)
    try:
        os.rename(tmp, name, src_dir_fd=dfd, dst_dir_fd=dfd)
    finally:
        os.close(dfd)


@contextmanager
def private_lock(path):
    """An exclusive flock on path, a file only this user can open (0600,
    never through a link): a sandboxed process that could open the lock
    could hold it and stall every later grading."""
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_uid != os.geteuid():
            raise Refused(f"{path} is not the grader's own lock file; remove it")
        os.fchmod(fd, 0o600)
        fcntl.flock(fd, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


@contextmanager
def closed_to_others(folder):
    """As root: folder is closed to group and others while the block runs, its mode restored
    afterwards (the grader reads it as root; no sandbox user needs it). Not root: unchanged."""
    mode = stat.S_IMODE(os.stat(folder).st_mode)
    close = os.geteuid() == 0 and mode & 0o077
    if close:
        os.chmod(folder, mode & ~0o077)
    try:
        yield
    finally:
        if close:
            os.chmod(folder, mode)


def new_private_folder(parent, user=None):
    """A new empty folder in parent for one run, owned by the sandbox user
    (uid, gid) when given, reachable by nobody else."""
    import tempfile
    path = tempfile.mkdtemp(prefix="rt-run-", dir=parent)
    if user is not None:
        os.chown(path, user[0], user[1])
    os.chmod(path, 0o700)
    return path
