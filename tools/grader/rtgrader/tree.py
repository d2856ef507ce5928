"""The instructor's tree the grader builds against, prepared once and reused.

A grading folder (--build-dir, default build/grader) holds:

  source/      a copy of the repository (without build folders and .git),
               synchronised by content, so unchanged files keep their time
               stamps and nothing rebuilds; as root, solutions/ and
               tests/hidden/ in it are readable by root only
  source/build/tree/
               the CMake build of source/ with every chapter on the student
               side (RT_STUDENT_CHAPTERS=all) and each chapter's earlier
               chapters from the solutions (RT_DEPENDENCIES_FROM_SOLUTIONS);
               root's alone, like solutions/. It sits two folders below the
               copy, as a kit's own build (build/student) sits below the kit,
               so that every compile command of the two builds names the same
               relative paths: with a compiler cache told the kit's folder
               (ccache's base_dir), the preview's files that the student's
               build has compiled already (common/, the chapter programs, the
               public tests) are cache hits and are not compiled twice.
  stubs/       the compiled stubs' object files, put back for chapters a
               submission does not provide
  state.json   the chapters, their exercise files' compile commands and the
               test-case names, found once per change of the source

Grading a submission compiles only its exercise files (with the compile
command CMake wrote), drops the objects where the build expects them, and
lets ninja archive and link the chapter's executables: nothing else rebuilds.
"""

import filecmp
import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import time
from contextlib import contextmanager

from . import fsutil, sandbox, symbols

SKIP_AT_TOP = {".git", "out", "renders"}
# What a preview writes at a kit's top (README's `--out preview.json`, its report and renders/): not part
# of the course, and copying it would make every preview prepare the tree again.
SKIP_FILES_AT_TOP = {"preview.json", "report.html", "results.json"}
PRIVATE_DIRS = ("solutions", "tests/hidden", "tests/fixtures")
# Where the CMake build lives inside the copy of the source (why there: the
# opening comment). Its top folder is one the sync never copies (a name
# starting with "build", _skipped) and protect() keeps root's alone.
BUILD_IN_SOURCE = os.path.join("build", "tree")
BUILD_TOP = BUILD_IN_SOURCE.split(os.sep)[0]


def repository_root():
    return os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


@contextmanager
def locked(folder):
    """One grader at a time may change the build tree (the batch runs several)."""
    os.makedirs(folder, exist_ok=True)
    with fsutil.private_lock(os.path.join(folder, "grader.lock")):   # 0600: no sandbox user can hold it
        yield


def _skipped(rel):
    top = rel.split(os.sep, 1)[0]
    return (top in SKIP_AT_TOP or top.startswith("build") or "__pycache__" in rel.split(os.sep)
            or rel in SKIP_FILES_AT_TOP)


def sync_source(repo, dest, grading_folder=None, keep=()):
    """Makes dest a copy of repo, except the files in keep (paths relative to
    dest, left as they are); returns how many files changed."""
    changed = 0
    wanted = set(keep)
    for dirpath, dirnames, filenames in os.walk(repo):
        rel_dir = os.path.relpath(dirpath, repo)
        dirnames[:] = [d for d in dirnames if not _skipped(os.path.normpath(os.path.join(rel_dir, d)))
                       and os.path.join(dirpath, d) != grading_folder]   # never copy the copy into itself
        for name in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, name))
            src = os.path.join(dirpath, name)
            if _skipped(rel) or not os.path.isfile(src) or os.path.islink(src) or rel in keep:
                continue
            wanted.add(rel)
            dst = os.path.join(dest, rel)
            if os.path.isfile(dst) and filecmp.cmp(src, dst, shallow=False):
                continue
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            if os.path.exists(dst):
                os.chmod(dst, 0o644)
            # Copied with a new time stamp, not the source's: a source file may be older than the objects
            # built from its previous content (a copy or an archive keeps old time stamps) and ninja would
            # then keep the stale objects.
            shutil.copyfile(src, dst)
            shutil.copymode(src, dst)
            changed += 1
    for dirpath, dirnames, filenames in os.walk(dest):
        if dirpath == dest:  # the tree's build (BUILD_IN_SOURCE) lives in the copy; nothing of it is copied
            dirnames[:] = [d for d in dirnames if d != BUILD_TOP]
        for name in filenames:
            rel = os.path.relpath(os.path.join(dirpath, name), dest)
            if rel not in wanted:
                os.remove(os.path.join(dirpath, name))
                changed += 1
    return changed


def protect(folder):
    """As root: the grading folder is traversable, the build tree and the
    private sources are root's alone, the public sources readable."""
    os.chmod(folder, 0o711)
    source = os.path.join(folder, "source")
    for dirpath, dirnames, filenames in os.walk(source):
        if dirpath == source:   # the build (BUILD_IN_SOURCE), below
            dirnames[:] = [d for d in dirnames if d != BUILD_TOP]
        os.chmod(dirpath, 0o755)
        for name in filenames:
            os.chmod(os.path.join(dirpath, name), 0o644)
    for rel in PRIVATE_DIRS:
        path = os.path.join(source, rel)
        if os.path.isdir(path):
            os.chmod(path, 0o700)
    for rel in (os.path.join("source", BUILD_TOP), "stubs"):
        path = os.path.join(folder, rel)
        if os.path.isdir(path):
            os.chmod(path, 0o700)
    for path in (os.path.join(source, "tests", "manifest.json"), os.path.join(folder, "state.json")):
        if os.path.isfile(path):
            os.chmod(path, 0o600)     # the points and the hidden tests' names


def protect_repository(repo):
    """As root: the instructor repository's private folders are root's alone
    too, so a submission cannot read them by their absolute path."""
    for rel in PRIVATE_DIRS + (".git",):     # .git's packs hold every version of the private folders
        path = os.path.join(repo, rel)
        if os.path.isdir(path) and os.stat(path).st_mode & 0o077:
            os.chmod(path, 0o700)
    manifest_path = os.path.join(repo, "tests", "manifest.json")
    if os.path.isfile(manifest_path):
        os.chmod(manifest_path, 0o600)


class Tree:
    def __init__(self, folder, repo=None):
        self.folder = os.path.abspath(folder)
        self.repo = os.path.abspath(repo or repository_root())
        self.source = os.path.join(self.folder, "source")
        self.build = os.path.join(self.source, BUILD_IN_SOURCE)
        self.stubs = os.path.join(self.folder, "stubs")
        self.state_path = os.path.join(self.folder, "state.json")
        self.state = None

    @property
    def has_solutions(self):
        return os.path.isdir(os.path.join(self.source, "solutions"))

    def prepare(self, jobs, wanted=None, log=print):
        """Syncs the repository, and configures and builds the instructor tree
        for the chapters wanted (two-digit numbers; None: all) when needed."""
        with locked(self.folder):
            os.makedirs(self.source, exist_ok=True)
            old = None
            if os.path.isfile(self.state_path):
                with open(self.state_path) as f:
                    old = json.load(f)
            keep = self._placeholder_paths(old) if self.is_kit else set()
            if not os.path.isdir(self.build):
                old = None   # nothing built here yet (or a folder of the old layout, its build beside source/)
            changed = sync_source(self.repo, self.source, self.folder, keep)
            if sandbox.is_root():
                protect(self.folder)
                protect_repository(self.repo)
            if changed == 0 and old is not None:
                if wanted is None:
                    wanted = [ch["number"] for ch in old["chapters"].values()]
                wanted = self._with_dependencies(wanted, old["chapters"])
                if set(wanted) <= set(old["built"]):
                    self.state = old
                    return
            log(f"grader: preparing the instructor tree in {self.folder} ({changed} files changed)")
            self._restore_stubs(old)
            self._configure()
            chapters = self._chapters()
            if self.is_kit:
                self._write_placeholders(chapters)
            numbers = [ch["number"] for ch in chapters.values()]
            if wanted is None:
                wanted = numbers
            wanted = self._with_dependencies(wanted, chapters)
            unknown = sorted(set(wanted) - set(numbers))
            if unknown:
                raise SystemExit(f"grader: no chapter {', '.join(unknown)} in {self.repo}")
            # Chapters built before stay built (their objects are in the tree).
            built = sorted(set(wanted) | (set(old["built"]) & set(numbers) if old and changed == 0 else set()))
            targets = ["imgcmp"]
            for ch in chapters.values():
                if ch["number"] in built:
                    targets += ch["targets"] + ch["judge_targets"]
            returncode, output = build_with_progress(self.build, jobs, targets, log)
            if returncode != 0:
                raise SystemExit("grader: the instructor tree does not build:\n" + output[-6000:])
            for ch in chapters.values():
                ch["built"] = ch["number"] in built
                if ch["built"]:
                    self._save_stub(ch)
                    ch["tests"] = {kind: list_test_cases(ch[f"{kind}_judge"])
                                   for kind in ("public", "hidden") if ch.get(f"{kind}_judge")}
            self.state = {"chapters": chapters, "built": built, "has_solutions": self.has_solutions}
            with open(self.state_path, "w") as f:
                json.dump(self.state, f, indent=1)
            if sandbox.is_root():
                protect(self.folder)

    def _with_dependencies(self, wanted, chapters):
        """In a kit, the chapters wanted and the earlier chapters they build on: those are linked from
        the student's own files (grading.py), so they are built too. With solutions, as wanted."""
        if not self.is_kit:
            return list(wanted)
        found = set(wanted)
        for ch in chapters.values():
            if ch["number"] in wanted:
                found.update(d for d in ch.get("depends", []))
        return sorted(found)

    @property
    def is_kit(self):
        """A student kit: no solutions, and the exercise files are the student's own."""
        return not os.path.isdir(os.path.join(self.repo, "solutions"))

    def _placeholder_paths(self, state):
        if not state:
            return set()
        return {os.path.relpath(os.path.join(ch["chapter_dir"], ex), self.source)
                for ch in state["chapters"].values() for ex in ch["exercises"]}

    def _write_placeholders(self, chapters):
        """In a kit, the tree is built with placeholders instead of the student's
        exercise files (made from the chapter's RPC table, every function throws):
        one broken file must not stop the tree from building, and the tree never
        compiles student code outside the sandbox. Each submission's own files
        are then compiled and linked chapter by chapter, as on the instructor side."""
        for ch in chapters.values():
            for i, ex in enumerate(ch["exercises"]):
                text = ("// Written by the grader (tools/grader/rtgrader/tree.py): a stand-in for the student's file.\n"
                        + ("#define RT_RPC_PLACEHOLDER\n"
                           f"#include \"tests/support/rpc/{ch['id']}.cpp\"\n" if i == 0 else ""))
                path = os.path.join(ch["chapter_dir"], ex)
                with open(path) as f:
                    if f.read() == text:
                        continue
                with open(path, "w") as f:
                    f.write(text)

    def _configure(self):
        cmd = ["cmake", "-S", self.source, "-B", self.build, "-G", "Ninja",
               "-DCMAKE_BUILD_TYPE=RelWithDebInfo", "-DRT_WARNINGS_AS_ERRORS=OFF", "-DRT_SANITIZE=OFF",
               "-DRT_STUDENT_CHAPTERS=all", "-DRT_DISCOVER_TESTS=OFF", "-DRT_JUDGE=ON",
               # The tests' own files optimised where the hidden tests run (the instructor's tree:
               # there the judges' time is the student's wait); a kit's preview runs the public
               # tests only, which take seconds unoptimised, and compiles them in about half the time.
               "-DRT_OPTIMISE_TEST_FILES=" + ("OFF" if self.is_kit else "ON")]
        cmd.append("-DRT_DEPENDENCIES_FROM_SOLUTIONS=" + ("ON" if self.has_solutions else "OFF"))
        result = subprocess.run(cmd, capture_output=True, text=True)
        if result.returncode != 0:
            raise SystemExit("grader: configuring the instructor tree failed:\n" + result.stderr[-4000:])

    def _chapters(self):
        """Reads the chapter descriptions CMake wrote, and each exercise file's compile command."""
        with open(os.path.join(self.build, "compile_commands.json")) as f:
            commands = {os.path.normpath(e["file"]): e for e in json.load(f)}
        chapters = {}
        for path in sorted(glob.glob(os.path.join(self.build, "rt_chapters", "ch*.json"))):
            with open(path) as f:
                ch = json.load(f)
            ch["compile"] = {}
            for ex in ch["exercises"]:
                entry = commands.get(os.path.normpath(os.path.join(ch["chapter_dir"], ex)))
                if entry is None:
                    raise SystemExit(f"grader: no compile command for {ch['id']} {ex} in compile_commands.json")
                args = shlex.split(entry["command"])
                obj = args[args.index("-o") + 1]
                ch["compile"][ex] = {"args": args, "object": os.path.join(entry["directory"], obj)}
            judges = os.path.join(self.build, "rt_judges", ch["id"] + ".json")
            if not os.path.isfile(judges):
                raise SystemExit(f"grader: chapter {ch['id']} has no judge (write tests/support/rpc/{ch['id']}.cpp, "
                                 "see cmake/judge.cmake)")
            with open(judges) as f:
                ch.update(json.load(f))
            # Linked again for each submission: the runner and the program hold the student's code.
            ch["targets"] = [f"{ch['id']}_runner", ch["id"]]
            # Built once: the judges hold the tests and no student code.
            ch["judge_targets"] = [f"{ch['id']}_{kind}_judge" for kind in ("public", "hidden")
                                   if ch.get(f"{kind}_judge")]
            # The solutions' chapter program draws the graded picture's reference (picture.py).
            if ch.get("solution_program"):
                ch["judge_targets"].append(f"{ch['id']}_solution_program")
            chapters[ch["id"]] = ch
        return chapters

    def _save_stub(self, ch):
        for ex, c in ch["compile"].items():
            c["mtime_ns"] = os.stat(c["object"]).st_mtime_ns
            dst = os.path.join(self.stubs, ch["id"], ex + ".o")
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            shutil.copyfile(c["object"], dst)

    def _restore_stubs(self, old):
        """Puts the stubs' objects back, so the tree never keeps a submission's code."""
        if old is None:
            return
        for ch in old["chapters"].values():
            for ex, c in ch["compile"].items():
                saved = os.path.join(self.stubs, ch["id"], ex + ".o")
                if ch.get("built") and os.path.isfile(saved) and os.path.isdir(os.path.dirname(c["object"])):
                    shutil.copyfile(saved, c["object"])
                    os.utime(c["object"], ns=(c["mtime_ns"], c["mtime_ns"]))
            if ch.get("built") and os.path.exists(ch.get("student_library", "")):
                os.remove(ch["student_library"])

    def chapters(self):
        return self.state["chapters"]

    def exercise_symbols(self, ch):
        """The mangled names of chapter ch's exercise functions (symbols.py): what the instructor's
        objects linked with submission code (the runner tables, the chapter programs) call and the
        chapter's stubs (in a kit, its placeholders) define."""
        cache = self.__dict__.setdefault("_exercise_symbols", {})
        if "users" not in cache:
            users = {}
            for dirpath, dirnames, filenames in os.walk(self.build):
                target = os.path.basename(dirpath)
                if re.fullmatch(r"ch\d\d_(runner_table|program_objects)\.dir", target):
                    users[target[:4]] = users.get(target[:4], []) + [
                        os.path.join(d, f) for d, _, fs in os.walk(dirpath) for f in fs if f.endswith(".o")]
                    dirnames[:] = []
            cache["users"] = users
        if ch["id"] not in cache:
            users = cache["users"]
            if not users.get(ch["id"]):
                raise SystemExit(f"grader: the runner table and program objects of {ch['id']} are not in {self.build}")
            stubs = [os.path.join(self.stubs, ch["id"], ex + ".o") for ex in ch["compile"]]
            cache[ch["id"]] = symbols.exercise_symbols(stubs, sorted(p for found in users.values() for p in found))
        return cache[ch["id"]]

    def confine_objects(self, objects):
        """Each submission object checked against what it may define (symbols.py) before anything links
        or runs. Returns ({chapter id: {ex: bytes to link}}, {chapter id: why it is refused})."""
        confined, refused = {}, {}
        for cid, files in objects.items():
            allowed = self.exercise_symbols(self.chapters()[cid])
            for ex, path in files.items():
                with open(path, "rb") as f:
                    data, why = symbols.confine(f.read(), allowed, ex)
                if why:
                    refused[cid] = why
                    break
                confined.setdefault(cid, {})[ex] = data
        return confined, refused

    def link(self, objects, chapter_ids, log_dir):
        """Places each chapter's objects (the submission's, or the stubs') and
        links the executables of chapter_ids. Returns {chapter id: error text or ''}.
        A submission object that defines more than its exercise's functions is refused
        (its chapter then links the stubs, and its error says why); its weak copies of
        anything else are made its own (symbols.py). Call with the lock held."""
        confined, refused = self.confine_objects(objects)
        for ch in self.chapters().values():
            if not ch.get("built"):
                continue
            for ex, c in ch["compile"].items():
                mine = confined.get(ch["id"], {}).get(ex) if ch["id"] not in refused else None
                if mine is not None:
                    fsutil.write_new(os.path.dirname(c["object"]), os.path.basename(c["object"]), mine, 0o600)
                else:
                    shutil.copyfile(os.path.join(self.stubs, ch["id"], ex + ".o"), c["object"])
                # Ninja trusts an object whose time stamp is the one it recorded
                # (a newer one would make it recompile the stub from source) ...
                os.utime(c["object"], ns=(c["mtime_ns"], c["mtime_ns"]))
            # ... and archives the library again because it is gone.
            if os.path.exists(ch["student_library"]):
                os.remove(ch["student_library"])
        errors = {}
        for cid in chapter_ids:
            ch = self.chapters()[cid]
            if cid in refused:
                errors[cid] = refused[cid]
                continue
            result = subprocess.run(["ninja", "-C", self.build, "-j2"] + ch["targets"],
                                    capture_output=True, text=True)
            errors[cid] = "" if result.returncode == 0 else (result.stdout + result.stderr)
        return errors


_NINJA_STEP = re.compile(r"^\[(\d+)/(\d+)\]")


def build_with_progress(build, jobs, targets, log, every_seconds=5.0):
    """Runs ninja, telling how many build steps are done out of how many (the
    first preparation takes minutes on a busy machine: it must not look hung).
    Returns (exit status, ninja's output)."""
    started = time.monotonic()
    proc = subprocess.Popen(["ninja", "-C", build, f"-j{jobs}"] + targets, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, bufsize=1)
    lines = []
    last_told = started
    for line in proc.stdout:
        lines.append(line)
        step = _NINJA_STEP.match(line)
        now = time.monotonic()
        if step and (now - last_told >= every_seconds or step.group(1) == step.group(2)):
            log(f"grader: preparing: {step.group(1)}/{step.group(2)} build steps done ({now - started:.0f} s)")
            last_told = now
    proc.wait()
    return proc.returncode, "".join(lines[-200:])


def list_test_cases(executable):
    """The test-case names of a doctest executable built by the instructor."""
    result = subprocess.run([executable, "--list-test-cases", "--no-version"], capture_output=True, text=True,
                            timeout=60)
    lines = result.stdout.splitlines()
    separators = [i for i, line in enumerate(lines) if line.startswith("=====")]
    if result.returncode != 0 or len(separators) < 2:
        raise SystemExit(f"grader: cannot list the test cases of {executable}:\n{result.stdout}{result.stderr}")
    return [line for line in lines[separators[0] + 1:separators[1]] if line.strip()]
