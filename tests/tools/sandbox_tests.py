#!/usr/bin/env python3
"""Tests of the grader's sandbox (ctest label 'grader'; tests/tools/CMakeLists.txt).

  sandbox_tests.py --work DIR --build-dir TREE SandboxFixture.test_NAME   one hostile submission, every isolation mode
  sandbox_tests.py --work DIR --build-dir TREE Outputs                   root never writes through a planted link
  sandbox_tests.py --work DIR --imgcmp PATH Imgcmp                       a PNG claiming 8192x8192 pixels is never decoded
  sandbox_tests.py --work DIR PrivateClone                               a repository in a 0700 folder grades, both modes

A fixture (tests/fixtures/adversarial/sandbox-*/, test_sandbox_NAME) is graded
twice: with the isolation this machine allows (namespaces with bubblewrap
where possible) and with the fallback forced (RT_GRADER_ISOLATION=fallback).
sandbox.json says what must hold (see tests/fixtures/adversarial/README.md).
"""

import glob
import json
import os
import platform
import resource
import shutil
import stat
import struct
import subprocess
import sys
import tempfile
import time
import zlib

import tooltest
from tooltest import FIXTURES, add_fixture_tests, fixture_source, REPO, ROOT, ToolTest, compiler_cache, config, grade, main, matches, solution_folder, total_score

# A correct test case ends in milliseconds, but on a machine shared with builds (load 20-40) the
# hidden test with a thousand calls took over 3 s: the grader's own default, 10 s, costs nothing
# to a test that passes. No sandbox fixture hangs in a test case.
LIMITS = ["--timeout", "10", "--render-timeout", "10"]
# A fixture whose chapter program hangs waits the render's limit, in both modes: a shorter one
# for it (the render fails whatever the limit; chapter 01's takes 20 ms).
HANGING_RENDER = {"sandbox-hang-after-result"}
HANG_LIMITS = ["--timeout", "10", "--render-timeout", "4"]
sys.path.insert(0, os.path.join(REPO, "tools", "grader"))
sys.dont_write_bytecode = True
from rtgrader import isolation  # noqa: E402


def machine_mode():
    """The mode the grader will pick here when not forced."""
    os.environ.pop("RT_GRADER_ISOLATION", None)
    return isolation.detect().mode


def modes():
    """(label, environment) pairs to grade in: the machine's best, and the forced fallback."""
    best = machine_mode()
    out = [(best, {})]
    if best == isolation.NAMESPACES:
        out.append(("fallback", {"RT_GRADER_ISOLATION": "fallback"}))
    return out


def processes_named(comm):
    """Live processes called comm. A zombie (state Z) is left out: it is dead, runs no code and
    holds nothing but its exit status until init reaps it, which some inits (this VM's among
    them) do only after a while."""
    found = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                with open(f"/proc/{pid}/comm") as f:
                    name = f.read().strip()
                with open(f"/proc/{pid}/stat") as f:
                    state = f.read().rsplit(")", 1)[1].split()[0]
                if name == comm and state != "Z":
                    found.append(int(pid))
            except (OSError, IndexError):
                pass
    return found


def leftovers(prefix, depth=3):
    """Entries named prefix... in /tmp, /var/tmp, /dev/shm and the folders below them, down to
    depth (a folder nested thousands deep in /tmp, which anybody may make, must not stop the test)."""
    found, pending = [], [(folder, 0) for folder in ("/tmp", "/var/tmp", "/dev/shm")]
    while pending:
        folder, level = pending.pop()
        try:
            entries = list(os.scandir(folder))
        except OSError:
            continue
        found += [e.path for e in entries if e.name.startswith(prefix)]
        if level < depth:
            pending += [(e.path, level + 1) for e in entries if e.is_dir(follow_symlinks=False)]
    return found


def sysv_segments_of_sandbox_users(size=1 << 20):
    """System V segments of the sandbox users of the size the fixture makes (1 MiB): the sandbox
    users are machine-wide, and another grading running meanwhile may hold segments of its own."""
    import pwd
    uids = {str(p.pw_uid) for p in pwd.getpwall() if p.pw_name.startswith("rt-grader-")}
    try:
        with open("/proc/sysvipc/shm") as f:
            rows = [line.split() for line in f.readlines()[1:]]
        return [" ".join(r) for r in rows if r[7] in uids and r[3] == str(size)]
    except OSError:
        return []


def make_submission(name, spec):
    """The fixture's attack and the shared answer as chapter 01's file, with the real paths
    written in where it asks (substitute)."""
    places = {"@REPO@": REPO, "@TREE@": config.build_dir,
              "@RESULTS@": os.path.abspath(os.path.join(config.work, "..", "grader-tests"))}
    rel = os.path.join("chapters", os.path.basename(solution_folder("01")), "unit_sphere.cpp")
    return tooltest.make_submission(os.path.join(config.work, "sub", name),
                                    files={rel: fixture_source(name, places if spec.get("substitute") else None)})


PLANTED = "/tmp/rt-odd-files-cmake-ran"     # the odd submission's CMakeLists.txt would make it


def make_odd_submission(name):
    """A correct chapter 01 (the shared answer) among entries a student could put beside it
    (sandbox-odd-files/sandbox.json): headers and a CMakeLists.txt that break everything if the
    grader used them, a fifo as chapter 02's file, folders nested deeper than Python's recursion
    limit, a link loop, a link to /, long names and a name with escape codes."""
    sub = os.path.join(config.work, "sub", name)
    subprocess.run(["rm", "-rf", sub], check=True)     # shutil.rmtree recurses: too deep for it
    if os.path.exists(PLANTED):
        os.remove(PLANTED)
    ch01 = os.path.join("chapters", os.path.basename(solution_folder("01")))
    with open(os.path.join(FIXTURES, "answer.cpp")) as f:
        answer = f.read()
    files = {os.path.join(ch01, "unit_sphere.cpp"): answer,
             os.path.join(ch01, "unit_sphere.hpp"): "#error SHADOWED-HEADER\n",
             os.path.join("chapters", os.path.basename(solution_folder("03")), "scene_loop.hpp"): "#error SHADOWED\n",
             "CMakeLists.txt": f"execute_process(COMMAND touch {PLANTED})\nmessage(FATAL_ERROR SHADOWED-CMAKE)\n",
             ".gitattributes": "* filter=SHADOWED\n"}
    files.update({os.path.join("common", h): "#error SHADOWED-COMMON\n" for h in ("math.hpp", "ray.hpp", "stub.hpp")})
    tooltest.make_submission(sub, files=files)
    ch02 = os.path.join(sub, "chapters", os.path.basename(solution_folder("02")))
    os.makedirs(ch02)
    os.mkfifo(os.path.join(ch02, "sphere.cpp"))
    os.symlink(".", os.path.join(sub, "loop"))
    os.symlink("/", os.path.join(sub, "root"))
    os.mkdir(os.path.join(sub, "escape \x1b]0;owned\x07\x1b[2J"))
    for i in range(5):
        open(os.path.join(sub, "L" * 240 + str(i)), "w").close()
    fd = os.open(sub, os.O_RDONLY)
    for _ in range(1100):                      # deeper than Python's recursion limit (1000)
        os.mkdir("d", 0o755, dir_fd=fd)
        deeper = os.open("d", os.O_RDONLY, dir_fd=fd)
        os.close(fd)
        fd = deeper
    os.mkdir(os.path.basename(solution_folder("01")), dir_fd=fd)   # a chapter folder nobody should reach
    os.close(fd)
    return sub


class SandboxFixture(ToolTest):
    """One test per tests/fixtures/adversarial/sandbox-NAME/ (test_sandbox_NAME, '-' read as '_')."""

    def check_fixture(self, name):
        with open(os.path.join(FIXTURES, name, "sandbox.json")) as f:
            spec = json.load(f)
        if spec.get("make") == "links":
            return self.check_links()
        if spec.get("make") == "odd-files":
            # What the grader does with the rest of a submission does not depend on the isolation:
            # graded once, in the machine's mode.
            sub = make_odd_submission(name)
            # Removed afterwards: a folder 1100 deep in the build tree would stop any tool that walks it
            # recursively (shutil.rmtree, glob's '**') with Python's recursion limit.
            self.addCleanup(subprocess.run, ["rm", "-rf", sub], check=False)
            return self.check_mode(name, spec, sub, machine_mode(), {})
        sub = make_submission(name, spec)
        for label, env in modes():
            with self.subTest(mode=label):
                self.check_mode(name, spec, sub, label, env)

    def check_mode(self, name, spec, sub, label, env):
        fallback = label != isolation.NAMESPACES
        # "fallback_as_container_root": the fallback graded as root without CAP_SYS_ADMIN, as in a Docker
        # container (Gradescope's): bwrap cannot make namespaces there, and the grader must still
        # install its seccomp filter itself.
        prefix = ["setpriv", "--bounding-set=-sys_admin", "--"] \
            if fallback and ROOT and spec.get("fallback_as_container_root") else []
        out = os.path.join(config.work, "out", name, label, "results.json")
        graded = grade(sub, out, spec["chapters"], config.build_dir,
                       (HANG_LIMITS if name in HANGING_RENDER else LIMITS) + spec.get("options", []), env, timeout=400,
                       prefix=prefix)
        print(f"{name} [{label}{' as root without CAP_SYS_ADMIN' if prefix else ''}]: graded in {graded.seconds:.1f} s")
        data = self.assertGraded(graded)
        self.assertEqual("FALLBACK" in graded.stderr, fallback, "the grader did not say its mode")
        if platform.machine() == "x86_64":
            self.assertNotIn("no seccomp filter", data["output"], "the grader could not install its filter")
        if fallback:
            self.assertIn("WITHOUT the namespace sandbox", data["output"], "results.json does not warn that "
                          "namespaces were off")
            if not ROOT:
                print(f"NOTE: {name} [{label}]: no namespaces and not root: only the validity of results.json "
                      "was checked")
                return
        self.assertStatuses(f"{name} [{label}]", data, spec.get("must_fail", []), spec.get("may_differ", []),
                            {t["name"]: "passed" for t in data["tests"]})
        with open(out) as f:
            text = f.read()
        forbidden = spec.get("forbidden_in_results", []) + \
            ([] if fallback else spec.get("forbidden_in_results_namespaces", []))
        for word in forbidden:
            self.assertFalse(word in text, f"'{word}' appears in results.json")
        expected_words = dict(spec.get("output_contains", {}))
        if "memory limit per run: cgroup" in data["output"]:   # a memory cgroup, v1 or v2, held the run
            expected_words.update(spec.get("output_contains_with_memory_cgroup", {}))
        for pattern, words in expected_words.items():
            chosen = [t for t in data["tests"] if matches(t["name"], [pattern])]
            self.assertTrue(chosen, f"no test matches {pattern}")
            for t in chosen:
                self.assertIn(words, t["output"], t["name"])
        if "max_seconds" in spec:
            self.assertLess(graded.seconds, spec["max_seconds"], "grading took too long")
        if "no_leftovers" in spec:
            self.assertEqual(leftovers(spec["no_leftovers"])[:5], [], "files left behind")
            self.assertEqual(sysv_segments_of_sandbox_users(), [], "System V segments left behind")
        if spec.get("no_escape_in_summary"):
            self.assertFalse("\x1b" in graded.stdout or "\x07" in graded.stdout,
                             "raw escape codes reached the grader's terminal summary")
            self.assertIn("\\x1b", graded.stdout, "the summary does not show the escaped text")
        if name == "sandbox-fork-orphan":
            time.sleep(0.2)
            self.assertEqual(processes_named("rt-orphan"), [], "a test process outlived grading")
        if name == "sandbox-odd-files":
            self.assertFalse(os.path.exists(PLANTED), "the submission's CMakeLists.txt was run")
            self.assertFalse("\x1b" in graded.stdout + graded.stderr, "a raw escape code reached the terminal")
        if name == "sandbox-reads-secrets":
            self.assertIn("words to look at", graded.stderr, "the instructor note is missing from the log")

    def check_links(self):
        """Links of both kinds in a submission are refused, the solution never taken."""
        solution = os.path.join(solution_folder("01"), "unit_sphere.cpp")
        cases = {}
        base = os.path.join(config.work, "sub", "links")
        shutil.rmtree(base, ignore_errors=True)
        for kind in ("symlink", "hardlink", "linked-folder"):
            sub = os.path.join(base, kind)
            chapters = os.path.join(sub, "chapters")
            os.makedirs(chapters)
            target = os.path.join(chapters, os.path.basename(solution_folder("01")))
            if kind == "linked-folder":
                os.symlink(solution_folder("01"), target)
            else:
                os.makedirs(target)
                link = os.path.join(target, "unit_sphere.cpp")
                os.symlink(solution, link) if kind == "symlink" else os.link(solution, link)
            cases[kind] = sub
        for label, env in modes():
            for kind, sub in cases.items():
                with self.subTest(mode=label, link=kind):
                    out = os.path.join(config.work, "out", "links", label, kind, "results.json")
                    data = self.assertGraded(grade(sub, out, "01", config.build_dir, LIMITS, env, timeout=400))
                    self.assertEqual(total_score(data), 0, "scored with the instructor's file")
                    entry = [t for t in data["tests"] if t["name"] == "ch01 compilation"]
                    self.assertTrue(entry, "no 'ch01 compilation' entry")
                    self.assertIn("link", entry[0]["output"], "the compilation entry does not name the link")


add_fixture_tests(SandboxFixture, "sandbox-*/sandbox.json")


class Outputs(ToolTest):
    def test_root_never_writes_through_a_planted_link(self):
        """Links planted in the output folder are replaced, never written through;
        a world-writable output folder is closed; the lock is the grader's alone."""
        sub = os.path.join(config.work, "sub", "outputs")
        shutil.rmtree(sub, ignore_errors=True)
        shutil.copytree(solution_folder("01"), os.path.join(sub, "chapters", os.path.basename(solution_folder("01"))))
        out_dir = os.path.join(config.work, "out", "outputs")
        shutil.rmtree(out_dir, ignore_errors=True)
        os.makedirs(os.path.join(out_dir, "renders"))
        victim = os.path.join(config.work, "victim.txt")
        with open(victim, "w") as f:
            f.write("untouched\n")
        for rel in ("renders/ch01.png", "renders/ch01.diff.png", "results.json.tmp", "results.json"):
            os.symlink(victim, os.path.join(out_dir, rel))
        os.chmod(out_dir, 0o777)
        os.chmod(os.path.join(out_dir, "renders"), 0o777)
        graded = grade(sub, os.path.join(out_dir, "results.json"), "01", config.build_dir, LIMITS)
        with open(victim) as f:
            self.assertEqual(f.read(), "untouched\n", "the grader wrote through a link planted in the output folder")
        self.assertFullMarks(self.assertGraded(graded), "the solution")
        for rel in ("renders/ch01.png", "results.json"):
            self.assertTrue(stat.S_ISREG(os.lstat(os.path.join(out_dir, rel)).st_mode),
                            f"{rel} is not a regular file the grader wrote")
        if ROOT:
            self.assertEqual(os.stat(out_dir).st_mode & 0o022, 0, "the output folder is still writable by others")
        lock = os.path.join(config.build_dir, "grader.lock")
        self.assertEqual(stat.S_IMODE(os.stat(lock).st_mode), 0o600, f"{lock} can be opened by others")


def png(width, height, raw_rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw_rows, 9)) + chunk(b"IEND", b"")


class Imgcmp(ToolTest):
    def test_a_decompression_bomb_is_never_decoded(self):
        """A real decompression bomb (8192 x 8192 zeros in 200 KB): imgcmp reads
        its header and never decodes it, under a 256 MiB address-space limit."""
        bomb = os.path.join(config.work, "bomb.png")
        small = os.path.join(config.work, "small.png")
        with open(bomb, "wb") as f:
            f.write(png(8192, 8192, bytes(8192 * (8192 * 3 + 1))))
        with open(small, "wb") as f:
            f.write(png(4, 4, bytes(4 * 13)))

        def limit():
            resource.setrlimit(resource.RLIMIT_AS, (256 << 20, 256 << 20))
        for pair, status, words in (((bomb, small), 1, "differ in size"), ((bomb, bomb), 2, "claims 8192x8192"),
                                    ((small, small), 0, "match")):
            with self.subTest(pair=[os.path.basename(p) for p in pair]):
                start = time.monotonic()
                r = subprocess.run([config.imgcmp, *pair], capture_output=True, text=True, preexec_fn=limit,
                                   timeout=60)
                said = r.stdout + r.stderr
                print(f"imgcmp {os.path.basename(pair[0])} {os.path.basename(pair[1])}: {r.returncode} "
                      f"in {time.monotonic() - start:.2f} s: {said.strip()}")
                self.assertEqual(r.returncode, status, said)
                self.assertIn(words, said)


UNPRIVILEGED_USER = "rt-grader-unpriv"


def reachable_by_everyone(path):
    """Whether every folder from / down to path lets any user through (the x bit for others)."""
    path = os.path.abspath(path)
    while True:
        if not os.stat(path).st_mode & stat.S_IXOTH:
            return False
        parent = os.path.dirname(path)
        if parent == path:
            return True
        path = parent


class PrivateClone(ToolTest):
    def test_a_clone_in_a_private_folder_grades_in_both_modes(self):
        """The repository copied into a 0700 folder (like root's home) grades a
        correct chapter 01 fully, with namespaces and in the fallback; then, as
        root, the clone is given to an ordinary user, who grades in it again: with
        unprivileged bubblewrap (namespaces mode) where the kernel allows it, else
        with the loud fallback."""
        # The ordinary user must be able to reach the folders it is given. When this repository is
        # itself cloned in a private folder (root's home, 0700), the test's own work folder is out
        # of that user's reach: the test then works in a fresh folder under the system's temp folder.
        base = config.work
        if not reachable_by_everyone(base):
            base = tempfile.mkdtemp(prefix="rt-private-clone-")
            os.chmod(base, 0o755)       # the way in; "private" below stays 0700, as a home folder
        try:
            self.grade_private_clone(base)
        finally:
            if base != config.work:
                shutil.rmtree(base, ignore_errors=True)

    def grade_private_clone(self, base):
        private = os.path.join(base, "private")
        shutil.rmtree(private, ignore_errors=True)
        os.makedirs(private)
        os.chmod(private, 0o700)
        clone = os.path.join(private, "repo")
        shutil.copytree(REPO, clone, ignore=shutil.ignore_patterns("build", "build-*", ".git", "__pycache__"))
        sub = os.path.join(base, "sub", "private-clone")
        shutil.rmtree(sub, ignore_errors=True)
        shutil.copytree(solution_folder("01"), os.path.join(sub, "chapters", os.path.basename(solution_folder("01"))))
        for label, env in modes():
            with self.subTest(mode=label):
                out = os.path.join(config.work, "out", "private-clone", label, "results.json")
                graded = grade(sub, out, "01", None, LIMITS, dict(env, **compiler_cache(clone)), timeout=900,
                               grade_cmd=os.path.join(clone, "tools", "grader", "grade"))
                print(f"private clone [{label}]: {graded.seconds:.1f} s")
                self.assertFullMarks(self.assertGraded(graded), f"private clone [{label}]")
        if ROOT and shutil.which("runuser") and os.path.exists("/usr/bin/python3"):
            with self.subTest(mode="not root"):
                self.check_not_root(private, clone, sub)

    def check_not_root(self, private, clone, sub):
        """The clone, its grading tree (prepared above) and the submission given to an ordinary
        user, who grades there: no cgroup, no sandbox user, the code runs as that user."""
        try:
            subprocess.run(["id", UNPRIVILEGED_USER], check=True, capture_output=True)
        except subprocess.CalledProcessError:
            subprocess.run(["useradd", "--system", "--no-create-home", "--shell", "/usr/sbin/nologin",
                            UNPRIVILEGED_USER], check=True, capture_output=True)
        out_dir = os.path.join(private, "out")
        os.makedirs(out_dir, exist_ok=True)
        for folder in (private, sub):
            subprocess.run(["chown", "-R", UNPRIVILEGED_USER, folder], check=True)
        bwrap_works = subprocess.run(["runuser", "-u", UNPRIVILEGED_USER, "--", "bwrap", "--unshare-user",
                                      "--ro-bind", "/", "/", "/bin/true"], capture_output=True).returncode == 0
        graded = grade(sub, os.path.join(out_dir, "results.json"), "01", None, LIMITS, timeout=900,
                       grade_cmd=os.path.join(clone, "tools", "grader", "grade"), as_user=UNPRIVILEGED_USER)
        print(f"private clone [not root, bwrap {'works' if bwrap_works else 'fails'}]: {graded.seconds:.1f} s")
        data = self.assertGraded(graded)
        self.assertFullMarks(data, "private clone [not root]")
        if bwrap_works:
            self.assertIn("isolation: namespaces", graded.stderr, "unprivileged bubblewrap was not used")
            self.assertIn("inside a user namespace of unprivileged bubblewrap", data["output"])
        else:
            self.assertIn("FALLBACK", graded.stderr, "the fallback was not said")
            self.assertIn("WITHOUT the namespace sandbox", data["output"])


if __name__ == "__main__":
    main()
