"""Grading one submission: find its exercise files, compile them, link them
into the instructor's test executables, run every test case in its own
limited process, render each chapter's picture, and score the lot."""

import dataclasses
import itertools
import os
import queue
import re
import shutil
import stat
import subprocess
import tempfile
import threading
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

from . import fsutil, isolation, judge, manifest, picture, sandbox, tree
from .sandbox import MiB, Limits

MAX_SOURCE_BYTES = 1 * MiB
OUTPUT_SHOWN = 3000          # characters of a test's output put in results.json
COMPILER_SHOWN = 3000        # characters of a compiler message

# Words in a submission that deserve the instructor's eye (never shown as a score change).
# A word made of letters, digits and '_' is matched as a whole identifier only (`_exit`, not
# the `_exit` inside `widen_exit`); any other entry (`system(`, `#include "/`) as plain text.
SUSPICIOUS = ["getenv", "environ", "RT_GRADER", "/proc", "fork", "vfork", "clone", "execl", "execlp", "execv",
              "execve", "execvp", "fexecve", "system(", "popen", "_exit", "_Exit", "quick_exit", "abort(",
              "__attribute__", "asm", "__asm", "__asm__", "#include \"/", "#include </", "solutions/", "hidden",
              "signal(", "setrlimit", "socket", "ptrace", "dlsym", "results.json", "incbin", "extern \"C\"",
              "doctest", "#pragma", "weak", "syscall", "keyctl", "add_key", "unshare", "memfd_create", "prctl",
              # the test support's own types: code that looks for a callback's data instead of calling it
              "rt::test", "served_table", "object_server", "occlusion_server", "occlusion_table", "target_type",
              "reinterpret_cast"]
_IDENTIFIER = re.compile(r"\w+")


def _word_pattern(word):
    if _IDENTIFIER.fullmatch(word):
        return re.compile(r"(?<!\w)" + re.escape(word) + r"(?!\w)")
    return re.compile(re.escape(word))


_SUSPICIOUS_PATTERNS = [(w, _word_pattern(w)) for w in SUSPICIOUS]


def suspicious_words(text):
    """The SUSPICIOUS entries found in text (identifiers as whole identifiers), in list order."""
    return [w for w, pattern in _SUSPICIOUS_PATTERNS if pattern.search(text)]


@dataclass
class Options:
    chapters: list = None            # chapter ids ("ch01"); None: every chapter of the tree
    public_only: bool = False
    limits: Limits = field(default_factory=Limits)
    render_seconds: float = 60.0
    jobs: int = 2
    # Time budgets (README, "Time limits"): each case has its own limit (limits.wall_seconds); the cases
    # of one chapter in one phase share chapter_seconds; the visible phase (public tests and pictures of
    # every chapter) ends by visible_seconds after the start, the hidden phase by submission_seconds.
    chapter_seconds: float = 120.0
    visible_seconds: float = 240.0
    submission_seconds: float = 480.0


@dataclass
class TestResult:
    name: str
    kind: str
    chapter: str
    passed: bool
    output: str
    points: float = 0
    visibility: str = "visible"


# How far the grader looks for a chapter's folder below the submission's top (a zip with a
# folder of its own around the kit): a bounded look, breadth first, so a submission of a million
# files or of folders nested thousands deep costs little and never exhausts the grader's stack.
SEARCH_DEPTH = 6
SEARCH_ENTRIES = 20000


def _chapter_folders(submission, folder):
    """Folders named `folder` below submission (no link followed, no hidden or build folder)."""
    pending, seen = [(submission, 0)], 0
    while pending:
        parent, depth = pending.pop(0)
        try:
            with os.scandir(parent) as it:
                entries = sorted(it, key=lambda e: e.name)
        except OSError:
            continue
        for e in entries:
            seen += 1
            if seen > SEARCH_ENTRIES:
                return
            if e.name.startswith((".", "build")) or not e.is_dir(follow_symlinks=False):
                continue
            if e.name == folder:
                yield e.path
            if depth < SEARCH_DEPTH:
                pending.append((e.path, depth + 1))


def find_exercise(submission, ch, ex):
    """The contents of the submission's copy of exercise file ex, or (None, why)."""
    root = os.path.realpath(submission)
    usual = [os.path.join(submission, "chapters", ch["folder"], ex), os.path.join(submission, ch["folder"], ex),
             os.path.join(submission, ex)]
    found_below = (os.path.join(d, ex) for d in _chapter_folders(submission, ch["folder"]))
    candidates = itertools.chain(usual, found_below)
    for path in candidates:
        try:
            info = os.lstat(path)
        except OSError:
            continue
        if not os.path.realpath(path).startswith(root + os.sep) or stat.S_ISLNK(info.st_mode):
            return None, f"{ex} is a link, not a file: submit the file itself"
        # Read once, here, with no link of either kind followed (fsutil); the
        # grader compiles and scans these bytes, never the student's file again.
        try:
            return fsutil.read_student_file(submission, os.path.relpath(path, submission), MAX_SOURCE_BYTES), ""
        except fsutil.Refused as e:
            return None, str(e)
        except OSError as e:
            return None, f"{ex} cannot be read: {e.strerror}"
    return None, (f"the file {ex} of chapter {ch['number']} ({ch['title']}) is missing from the submission "
                  f"(expected at chapters/{ch['folder']}/{ex}, or {ex} at the top of the submission)")


def elf_section_names(data):
    """The section names of a 64-bit little-endian ELF object (bytes), or None when it is not one
    that can be read whole."""
    import struct
    try:
        if data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
            return None
        shoff, = struct.unpack_from("<Q", data, 0x28)
        shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
        if shoff and shnum == 0:                        # extended numbering: the count is in section 0
            shnum = struct.unpack_from("<Q", data, shoff + 0x20)[0]
        if shentsize < 0x40 or shnum > 65536 or shoff + shnum * shentsize > len(data):
            return None
        headers = [struct.unpack_from("<IIQQQQ", data, shoff + k * shentsize) for k in range(shnum)]
        names_at, names_size = headers[shstrndx][4], headers[shstrndx][5]
        names = data[names_at:names_at + names_size]
        return [names[h[0]:names.find(b"\0", h[0])].decode("latin-1") for h in headers]
    except (IndexError, struct.error):
        return None


def object_problem(data):
    """'' when the student's object file may be linked by the grader (root, outside the sandbox),
    else why not. Sections of link-time optimisation (.gnu.lto_*), which a file can write with
    inline asm, would make the linker run the compiler's LTO back end on the student's bytes,
    as root: refused, like an object the grader cannot read."""
    names = elf_section_names(data)
    if names is None:
        return "it is not an ELF object file the grader can read"
    odd = sorted({n for n in names if n.startswith((".gnu.lto_", ".gnu.debuglto_"))})
    if odd:
        return f"it has link-time-optimisation sections ({', '.join(odd[:3])}); remove the asm that makes them"
    return ""


def trim(text, limit):
    text = text.strip()
    if len(text) <= limit:
        return text
    return text[:limit] + f"\n... ({len(text) - limit} more characters not shown)"


def make_dir(path, owner, mode):
    os.makedirs(path, exist_ok=True)
    if owner is not None:
        os.chown(path, owner[0], owner[1])
    os.chmod(path, mode)


class Grader:
    def __init__(self, tree_, entries, options, log=print):
        self.tree = tree_
        self.entries = entries
        self.options = options
        self.log = log
        chapters = self.tree.chapters()
        self.chapter_ids = options.chapters or [cid for cid, ch in chapters.items() if ch.get("built")]
        self.names = manifest.test_names(chapters, self.chapter_ids, options.public_only)
        self._per = threading.local()   # this grading's folder and deadline (a batch grades in threads)
        self._hidden_system_lock = threading.Lock()   # see _hidden_system

    # --- one submission ---------------------------------------------------------------
    def grade(self, submission, out_dir):
        start = time.monotonic()
        out_dir = fsutil.own_folder(out_dir)
        fsutil.fresh_folder(out_dir, "renders", 0o700 if sandbox.is_root() else 0o755)
        work = tempfile.mkdtemp(prefix="rt-grade-")
        os.chmod(work, 0o711)
        # A worker slot no other grading on this machine holds (in this
        # process or another): its sandbox users are this grading's alone.
        with sandbox.worker_slot(sandbox.slots_folder(self.tree.folder)) as slot:
            user = sandbox.sandbox_user(slot) if sandbox.is_root() else None
            try:
                self._per.visible_seconds = None
                results, notes = self._grade_in(submission, out_dir, work, user, slot)
            finally:
                shutil.rmtree(work, ignore_errors=True)
        # What the student may see of the time: the visible phase's (the hidden phase's time could
        # carry what the code did with hidden inputs), counted from this grading's start.
        visible = self._per.visible_seconds
        total = time.monotonic() - start
        return results, notes, total if visible is None else min(total, visible + (self._per.start - start))

    def _grade_in(self, submission, out_dir, work, user, slot):
        chapters = self.tree.chapters()
        logs = os.path.join(work, "logs")
        make_dir(logs, None, 0o700)
        notes = []
        self.iso = isolation.detect()
        self.log("grader: " + self.iso.describe())
        notes += self.iso.notes
        self._per.work = work
        self._per.start = time.monotonic()
        self._per.deadline = self._per.start + self.options.submission_seconds
        if user is None and self.iso.mode == isolation.NAMESPACES:
            notes.append("not root: the submission's code runs as the grader's own user, inside a user namespace "
                         "of unprivileged bubblewrap (it sees only its own files)")
        elif user is None:
            notes.append("isolation by user is off (the grader is not running as root): the submission's code "
                         "runs as the grader's own user")
        if not os.path.isdir(submission):
            notes.append(f"the submission folder {submission} does not exist")

        # 1. Find and compile the exercise files, chapter by chapter. In a student kit the earlier
        # chapters a graded chapter builds on come from the student's own files too (there are no
        # solutions to take them from): they are compiled, not graded.
        problems = {}     # chapter id -> message (missing file, compile or link error)
        sources = {}
        needed = self._with_dependencies(chapters)
        for cid in needed:
            ch = chapters[cid]
            sources[cid] = {}
            for ex in ch["exercises"]:
                path, why = find_exercise(submission, ch, ex) if os.path.isdir(submission) else (None, "")
                if path is None:
                    problems[cid] = why or f"the file {ex} is missing (no submission folder)"
                    break
                sources[cid][ex] = path
        suspicious = self._scan({cid: files for cid, files in sources.items() if cid in self.chapter_ids})
        to_compile = [cid for cid in needed if cid not in problems]
        lanes = max(1, self.options.jobs)
        free_lanes = queue.Queue()
        for lane in range(lanes):
            free_lanes.put(lane)

        deadline = self._per.deadline      # self._per is this thread's: the compiles run in others

        def compile_one(cid):
            lane = free_lanes.get()   # a lane (user) no other compile is using now
            try:
                lane_user = sandbox.sandbox_user(slot, lane + 1) if user is not None else None
                found = self._compile(chapters[cid], sources[cid], work, logs, lane_user, deadline)
            finally:
                free_lanes.put(lane)
            if user is not None:
                # The compile folder was the lane user's; now it is the grader's alone. A folder the
                # sandbox user kept would outlive its run: in the fallback by user, a runner (which
                # sees hidden inputs) could leave them there for the chapter program to print.
                make_dir(os.path.join(work, cid), (os.geteuid(), os.getegid()), 0o700)
            return found

        phase = time.monotonic()
        self.log(f"grader: compiling the exercise files of {len(to_compile)} chapter"
                 f"{'' if len(to_compile) == 1 else 's'} ...")
        with ThreadPoolExecutor(max_workers=lanes) as pool:
            compiled = dict(zip(to_compile, pool.map(compile_one, to_compile)))
        objects = {}
        for cid, (objs, error) in compiled.items():
            if error:
                problems[cid] = error
            else:
                objects[cid] = objs

        # 2. Link them into the instructor's executables (one build tree: take the lock).
        ready = [cid for cid in self.chapter_ids if cid not in problems]
        self._per.times = {"compile": time.monotonic() - phase, "tests": 0.0, "renders": 0.0}
        phase = time.monotonic()
        with tree.locked(self.tree.folder):
            link_errors = self.tree.link(objects, ready, logs)
            for cid in ready:
                if link_errors[cid]:
                    problems[cid] = "linking failed:\n" + self._tidy(link_errors[cid], chapters[cid], work)
                else:
                    self._take_executables(chapters[cid], os.path.join(work, "bin", cid))
        ready = [cid for cid in ready if cid not in problems]

        self._per.times["link"] = time.monotonic() - phase

        # 3. Phase 1, visible: every public test and every graded picture of every chapter, before any
        # hidden input reaches the student's code. Phase 2: the hidden tests, last. Nothing the student's
        # code produces in phase 2 is shown before publication (README, "Visible before hidden"): the
        # machine's page cache, or anything else two runs share, could carry a hidden input from the
        # runner of phase 2 into a program or a public test of phase 1 only if phase 1 came later.
        by_chapter = {cid: {} for cid in self.chapter_ids}
        probes = {}
        visible_end = self._per.start + self.options.visible_seconds

        def visible(cid, lane_logs, lane_user, cpu):
            ch, folder = chapters[cid], os.path.join(work, cid)
            runner = self._runner_path(folder, cid)
            began = time.monotonic()     # progress, one line a chapter and phase (no verdicts: they come at the end)
            probes[cid] = self._probe(runner, lane_logs, lane_user) if self._cases(cid) else ""
            found = self._run_phase(ch, "public", folder, lane_logs, lane_user, probes[cid], visible_end, cpu)
            found.update(self._picture(ch, folder, lane_logs, out_dir, lane_user))
            self.log(f"grader: {cid} public tests and picture done ({time.monotonic() - began:.1f} s)")
            return found

        def hidden(cid, lane_logs, lane_user, cpu):
            began = time.monotonic()
            try:
                found = self._run_phase(chapters[cid], "hidden", os.path.join(work, cid), lane_logs, lane_user,
                                        probes[cid], self._per.deadline, cpu)
                if found:
                    self.log(f"grader: {cid} hidden tests done ({time.monotonic() - began:.1f} s)")
                return found
            except Exception:   # noqa: BLE001 - a grader fault here must not replace the visible results
                # Whatever happens in the hidden phase stays in the hidden tests' entries: a grader that
                # failed here and wrote only its own error would show the student one bit of phase 2.
                self.log("grader: the hidden phase of " + cid + " failed:\n" + traceback.format_exc()[-3000:])
                return {name: self._result(name, kind, cid, False,
                                           "Grader problem during the hidden tests (tell your instructor).")
                        for name, kind, _, _ in self._cases(cid, "hidden")}

        for cid, found in self._in_lanes(ready, visible, logs, user, slot).items():
            by_chapter[cid].update(found)
        self._per.visible_seconds = time.monotonic() - self._per.start
        for cid, found in self._in_lanes(ready, hidden, logs, user, slot).items():
            by_chapter[cid].update(found)

        # 4. The results, chapter by chapter in the manifest's order. A chapter that did not build has
        # its compilation entry; so has an earlier chapter it builds on (in a kit), and every failed
        # test of a chapter that builds on one that did not build names it.
        results = []
        shown = set()
        for cid in self.chapter_ids:
            broken_below = [d for d in self._dependencies(chapters, cid) if d in problems]
            for d in broken_below:
                if d not in self.chapter_ids and d not in shown:
                    results.append(self._compilation_entry(d, problems[d]))
                    shown.add(d)
            if cid in problems:
                results.append(self._compilation_entry(cid, problems[cid]))
                for name, kind, _, _ in self._names_of(cid):
                    results.append(self._result(name, kind, cid, False,
                                                f"not graded: chapter {chapters[cid]['number']} did not build "
                                                f"(see '{cid} compilation')"))
                continue
            why = self._broken_dependencies_note(chapters, broken_below, problems)
            for name, kind, _, _ in self._names_of(cid):
                r = by_chapter[cid].get(name) or self._result(name, kind, cid, False,
                                                              "not run: the grader stopped before this test")
                if why and not r.passed:
                    r.output = why + "\n" + r.output
                results.append(r)
        # Where the time went, for the instructor (tools/grader/README.md, "Measured").
        self.log(f"grader: {sandbox.counts['runs']} sandboxed processes, {judge.counts['judges']} judge processes; "
                 + ", ".join(f"{k} {v:.1f} s" for k, v in self._per.times.items())
                 + f"; visible phase {self._per.visible_seconds:.1f} s")
        if suspicious:   # for the instructor's eyes only: never in results.json, which the student sees
            self.log("grader: instructor note: words to look at in the submission: " + "; ".join(suspicious))
        return results, notes

    def _in_lanes(self, cids, step, logs, user, slot):
        """{cid: step(cid, logs, user, cpu)} for every chapter, options.jobs chapters at a time. Each lane
        has its own sandbox user (a run's clean-up kills every process of its user: it must not reach
        the other lane's runner), its own log folder (a run's output is captured in its log file) and,
        with more than one lane, its own CPU for its judges (a judge and its runner take turns on the
        judge's CPU, so one lane keeps one CPU busy: two lanes use two)."""
        lanes = max(1, min(self.options.jobs, len(cids)))
        if lanes == 1:
            return {cid: step(cid, logs, user, None) for cid in cids}
        cpus = sorted(os.sched_getaffinity(0))
        per = dict(self._per.__dict__)     # this grading's folder, deadline, times: thread-local
        pending = queue.Queue()
        for cid in cids:
            pending.put(cid)
        done = {}

        def lane(k):
            self._per.__dict__.update(per)
            lane_logs = os.path.join(logs, f"lane{k}")
            make_dir(lane_logs, None, 0o700)
            lane_user = sandbox.sandbox_user(slot, k + 1) if user is not None else None
            while True:
                try:
                    cid = pending.get_nowait()
                except queue.Empty:
                    return
                done[cid] = step(cid, lane_logs, lane_user, cpus[k % len(cpus)])

        with ThreadPoolExecutor(max_workers=lanes) as pool:
            list(pool.map(lane, range(lanes)))
        return {cid: done[cid] for cid in cids}

    def _dependencies(self, chapters, cid):
        """The chapters (ids) whose exercise code chapter cid's runner and program link from the
        submission: its earlier chapters in a kit, none when the tree has the solutions."""
        if self.tree.has_solutions:
            return []
        return [f"ch{d}" for d in chapters[cid].get("depends", []) if f"ch{d}" in chapters]

    def _with_dependencies(self, chapters):
        """The chapters whose exercise files this grading compiles, in chapter order."""
        wanted = set(self.chapter_ids)
        for cid in self.chapter_ids:
            wanted.update(self._dependencies(chapters, cid))
        return [cid for cid in chapters if cid in wanted]

    @staticmethod
    def _broken_dependencies_note(chapters, broken, problems):
        """The line every failed test of a chapter starts with when an earlier chapter it builds on did
        not build: names that chapter and its compiler's first error."""
        if not broken:
            return ""
        told = []
        for d in broken:
            first = first_error_line(problems[d])
            told.append(f"chapter {chapters[d]['number']} ({chapters[d]['title']}) did not build"
                        + (f" ({first})" if first else "") + f", see '{d} compilation'")
        return ("This chapter builds on " + "; ".join(told) + ": whatever calls its functions fails here "
                "(they throw \"... is missing\"). Fix that chapter first.")

    def _names_of(self, cid):
        return [n for n in self.names if n[2] == cid]

    def _scan(self, sources):
        found = []
        for cid, files in sources.items():
            for ex, data in files.items():
                text = data.decode("utf-8", errors="replace")
                words = suspicious_words(text)
                if words:
                    found.append(f"{cid}/{ex}: {', '.join(words)}")
        return found

    # --- compiling ----------------------------------------------------------------------
    def _compile(self, ch, files, work, logs, user, deadline):
        """Compiles the chapter's exercise files as the sandbox user; returns ({ex: object}, error).
        Each compile gets at most 60 s, and no more than what is left of the submission's time
        budget (deadline): eight files that each keep the compiler busy (a template bomb, an
        #include of /dev/zero) must not hold a grading for eight minutes."""
        folder = os.path.join(work, ch["id"])
        make_dir(folder, user, 0o700)
        kept = os.path.join(work, "objects", ch["id"])    # the grader's own copies of the objects
        os.makedirs(kept, mode=0o700, exist_ok=True)
        objects = {}
        for ex, data in files.items():
            src = os.path.join(folder, ex)
            fsutil.write_new(folder, ex, data)
            if user is not None:
                os.chown(src, *user)
            obj = os.path.join(folder, ex + ".o")
            args = [a for a in ch["compile"][ex]["args"] if a != "-Werror"]
            original = os.path.normpath(os.path.join(ch["chapter_dir"], ex))
            args = [src if os.path.normpath(a) == original else a for a in args]
            args[args.index("-o") + 1] = obj
            seconds = min(60.0, max(1.0, deadline - time.monotonic()))
            limits = Limits(wall_seconds=seconds, cpu_seconds=int(seconds) + 1, memory_bytes=4096 * MiB,
                            file_bytes=256 * MiB, processes=64, open_files=256, tmp_bytes=512 * MiB)
            outcome = sandbox.run(args, limits=limits, log_path=os.path.join(logs, f"{ch['id']}-{ex}.compile"),
                                  user=user, inputs=sandbox.include_inputs(args, self.tree.source),
                                  scratch=folder, private_root=work, output_cap=64 * 1024)
            if outcome.returncode != 0 or outcome.timed_out:
                how = sandbox.describe_ending(outcome, limits)
                message = self._tidy(outcome.output, ch, work)
                return None, f"compiling {ex} failed" + (f": the compiler {how}" if how else "") + ":\n" + message
            # The object is copied by root into the build tree: never through a link.
            try:
                data = fsutil.read_regular(obj, limits.file_bytes)
            except (OSError, fsutil.Refused):
                return None, f"compiling {ex} did not produce an object file"
            problem = object_problem(data)
            if problem:
                return None, f"compiling {ex} gave an object file the grader does not link: {problem}"
            fsutil.write_new(kept, ex + ".o", data, 0o600)
            objects[ex] = os.path.join(kept, ex + ".o")
        return objects, ""

    def _tidy(self, text, ch, work):
        """Compiler output with the grader's paths replaced by the student's."""
        text = text.replace(os.path.join(work, ch["id"]) + os.sep, f"chapters/{ch['folder']}/")
        # The build first: it lies inside the source's copy.
        text = text.replace(self.tree.build + os.sep, "").replace(self.tree.source + os.sep, "")
        return trim(text, COMPILER_SHOWN)

    def _take_executables(self, ch, folder):
        """Copies the freshly linked runner and program out of the build tree, into a
        folder the submission's user cannot write (a run must not be able to swap the
        next run's program). The judges stay in the build tree: they hold no student code."""
        make_dir(os.path.dirname(folder), None, 0o711)
        make_dir(folder, None, 0o711)
        for key in ("runner", "program"):
            if ch.get(key):
                dst = os.path.join(folder, key)
                shutil.copyfile(ch[key], dst)
                os.chmod(dst, 0o755)

    # --- running ------------------------------------------------------------------------
    def _cases(self, cid, kind=None):
        return [n for n in self._names_of(cid) if n[1] in ((kind,) if kind else ("public", "hidden"))]

    @staticmethod
    def _runner_path(folder, cid):
        return os.path.join(os.path.dirname(folder), "bin", cid, "runner")

    def _run_phase(self, ch, kind, folder, logs, user, probe, phase_end, cpu=None):
        """One judge's cases of a chapter (kind: public or hidden) against a runner of the student's code
        (one for the phase, replaced only when it broke); returns {name: TestResult}."""
        cases = self._cases(ch["id"], kind)
        if not cases:
            return {}
        started = time.monotonic()
        budget = _Budget(self.options, phase_end)
        outcomes = {}
        if not probe:
            runner = self._runner_path(folder, ch["id"])
            # A hidden phase's runner sees hidden inputs: it gets system files of its own (README, "Visible
            # before hidden"), so the pages it loads or evicts are no later run's, not even the next grading's.
            system = self._hidden_system(runner) if kind == "hidden" else None
            host = judge.RunnerHost(self._runner_starter(runner, logs, user, budget, system))
            try:
                outcomes = judge.run_cases(ch[f"{kind}_judge"], [case for *_, case in cases], host,
                                           self.options.limits, self._per.work,
                                           os.path.join(logs, f"{ch['id']}-{kind}-judge"), budget, cpu)
            finally:
                host.close()
        found = {}
        for name, kind_, cid, case in cases:
            outcome = outcomes.get(case)
            if probe or outcome is None:
                found[name] = self._result(name, kind_, cid, False, probe or budget.why_not_run(case) or
                                           "not run: the judge stopped before this test")
            else:
                found[name] = self._result(name, kind_, cid, outcome.passed, self._feedback(outcome, kind_))
        self._per.times["tests"] += time.monotonic() - started
        return found

    def _picture(self, ch, folder, logs, out_dir, user):
        """The chapter's graded picture, a step of the visible phase: {name: TestResult} (none when the
        chapter has no picture or the manifest grades none)."""
        if not (ch.get("reference") and any(n[1] == "render" for n in self._names_of(ch["id"]))):
            return {}
        started = time.monotonic()
        name = f"{ch['id']}.render"
        if time.monotonic() > self._per.deadline:
            passed, output = False, (f"not run: the submission's tests used their time budget "
                                     f"({self.options.submission_seconds:g} s)")
        else:
            passed, output = self._render(ch, folder, logs, out_dir, user)
        self._per.times["renders"] += time.monotonic() - started
        return {name: self._result(name, "render", ch["id"], passed, output)}

    def _run_runner(self, argv, log_path, user, work, env_extra=None, pass_fds=(), limits=None, stopper=None,
                    system=None):
        """Runs the student's runner in the sandbox (it reads only itself, writes only a private /tmp).
        work is passed in: the runner runs in a thread of its own, where self._per is not this grading's."""
        return sandbox.run(argv, limits=limits or self.options.limits, log_path=log_path, user=user,
                           inputs=[argv[0]], env_extra=env_extra, pass_fds=pass_fds, private_root=work,
                           stopper=stopper, system=system)

    def _hidden_system(self, runner):
        """The private system folder of this grading's hidden runners (namespaces mode only: elsewhere
        every run sees the machine's own files), made at the first hidden phase, removed with work."""
        if self.iso.mode != isolation.NAMESPACES:
            return None
        folder = os.path.join(self._per.work, "hidden-system")
        # Two lanes start their chapters' hidden phases at once: under the lock, the second waits
        # for the first's copy instead of finding a half-made folder (its runner then failed to
        # start, one grading in eight), and adds whatever its own runner needs that is not there yet.
        with self._hidden_system_lock:
            if not os.path.isdir(folder):
                make_dir(folder, None, 0o755)
            isolation.private_system(folder, [runner] + ([self.iso.setpriv] if self.iso.setpriv else []))
        return folder

    def _runner_starter(self, runner, logs, user, budget, system=None):
        """How the chapter's RunnerHost starts a runner. A runner serves many cases: each case's time
        limit is the grader's (judge.py); the runner's own wall-clock and CPU limits are the
        chapter's remaining budget."""
        work = self._per.work
        base = self.options.limits

        def start(env, fds, stopper):
            seconds = max(1.0, budget.seconds_left())
            limits = dataclasses.replace(base, wall_seconds=seconds, cpu_seconds=int(seconds) + 1)
            return self._run_runner([runner], os.path.join(logs, "runner"), user, work, env, fds, limits, stopper,
                                    system)
        return start

    def _probe(self, runner, logs, user):
        """'' if the student's code starts (its static initialisers end), else why not (every case then fails)."""
        work = self._per.work
        return judge.probe(lambda argv: self._run_runner(argv, os.path.join(logs, "probe"), user, work), runner,
                           self.options.limits)

    def _feedback(self, found, kind):
        """What results.json says about one case: the judge's report, trimmed (hidden: concepts only)."""
        output = _clean_doctest_output(found.judge_output)
        if kind == "hidden":
            output = _hidden_feedback(output)
        ending = "" if found.passed else judge.runner_ending(found.runner, self.options.limits)
        text = "\n".join(t for t in (found.reason, ending, trim(output, OUTPUT_SHOWN)) if t)
        return text.strip() or ("passed" if found.passed else "failed")

    def _render(self, ch, folder, logs, out_dir, user):
        limits = self.options.limits
        cores = os.cpu_count() or 1
        render_limits = Limits(wall_seconds=self.options.render_seconds,
                               cpu_seconds=int(self.options.render_seconds * cores) + 1,
                               memory_bytes=limits.memory_bytes, file_bytes=64 * MiB,
                               processes=limits.processes + cores)
        scratch = os.path.join(self._per.work, f"render-{ch['id']}")    # the only folder the program may write
        make_dir(scratch, user, 0o700)
        image = os.path.join(scratch, "render.png")
        program = os.path.join(os.path.dirname(folder), "bin", ch["id"], "program")
        try:
            return self._render_in(ch, scratch, image, program, render_limits, logs, out_dir, user)
        finally:
            fsutil.remove_tree(scratch)   # nothing a run wrote stays for a later run (or chapter) to read

    def _graded_view(self, ch):
        """(view, size) of the picture graded for this chapter in this grading, or None for the chapter's
        own view against its reference.png (a kit's preview: no solutions to draw another reference)."""
        if not (self.tree.has_solutions and ch.get("solution_program")):
            return None
        if getattr(self._per, "secret_of", None) != self._per.work:    # a fresh secret for every grading
            self._per.secret_of, self._per.secret = self._per.work, picture.draw_secret()
        size = picture.graded_size(ch["reference"])
        return (picture.view_for(self._per.secret, ch["id"]), size) if size else None

    def _render_in(self, ch, scratch, image, program, render_limits, logs, out_dir, user):
        graded = self._graded_view(ch)
        extra = picture.program_arguments(*graded) if graded else []
        outcome = sandbox.run([program, "--out", image] + extra, limits=render_limits,
                              log_path=os.path.join(logs, "render"), user=user, inputs=[program], scratch=scratch,
                              private_root=self._per.work)
        said = self._program_said(ch, outcome.output)
        if outcome.returncode == 3:
            return False, f"the chapter program reached an exercise that is not implemented yet:\n{said}"
        if outcome.returncode != 0 or outcome.timed_out:
            how = sandbox.describe_ending(outcome, render_limits) or f"exited with status {outcome.returncode}"
            return False, f"the chapter program {how}:\n{said}"
        renders = os.path.join(out_dir, "renders")      # made fresh by grade(), the grader's own
        actual = os.path.join(renders, f"{ch['id']}.png")
        diff = os.path.join(renders, f"{ch['id']}.diff.png")
        try:
            picture_bytes = fsutil.read_regular(image, 64 * MiB)
        except (OSError, fsutil.Refused):
            return False, "the chapter program did not write its picture"
        fsutil.write_new(renders, os.path.basename(actual), picture_bytes)
        if graded:
            # Drawn only now, after the student's program ended: while it ran, this picture did not exist.
            reference, why = self._draw_reference(ch, extra, render_limits)
            if reference is None:
                return False, f"the grader could not draw this chapter's reference picture ({why}): " \
                              "tell your instructor; the render is not scored"
            fsutil.write_new(renders, f"{ch['id']}.reference.png", reference)
            seen = (f"seen from --view {picture.view_argument(graded[0])} at {graded[1][0]}x{graded[1][1]} "
                    f"(a view drawn for this grading; {ch['id']}'s reference.png is the chapter's own view)")
        else:
            with open(ch["reference"], "rb") as f:
                reference = f.read()
            seen = ""
        figures, matched, diff_png = self._imgcmp(ch, picture_bytes, reference, logs, user)
        figures = self._figures_shown(ch, figures)
        if diff_png:
            fsutil.write_new(renders, os.path.basename(diff), diff_png)
        where = (f"{seen}\n" if seen else "") + f"your render: {actual}" + \
            (f"\ndifference image: {diff}" if diff_png else "")
        if matched:
            return True, f"the picture matches the reference within tolerance: {figures}\n{where}"
        return False, (f"the picture differs from the reference render beyond tolerance: {figures}\n{where}\n"
                       "Open the difference image to see where.")

    def _draw_reference(self, ch, extra, render_limits):
        """(PNG bytes, '') of the solutions' chapter program's picture with these options, or (None, why).
        Instructor code only (built in the instructor tree, holding no submission code): run as the
        grader, in a folder of its own."""
        folder = tempfile.mkdtemp(prefix=f"reference-{ch['id']}-", dir=self._per.work)
        out = os.path.join(folder, "reference.png")
        try:
            result = subprocess.run([ch["solution_program"], "--out", out] + extra, capture_output=True, text=True,
                                    timeout=render_limits.wall_seconds, cwd=folder)
            if result.returncode != 0:
                return None, f"the solutions' program exited with status {result.returncode}: " + \
                    trim(result.stderr or result.stdout, 300)
            with open(out, "rb") as f:
                return f.read(), ""
        except subprocess.TimeoutExpired:
            return None, f"the solutions' program took over {render_limits.wall_seconds:g} s"
        except OSError as e:
            return None, str(e)
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def _course_code_in(self, ch):
        """'' or the earlier chapters whose course code the chapter program holds. When grading with
        the solutions, a chapter's program links the earlier chapters it builds on from the
        solutions (one mistake is charged once): the student's code could read that code's bytes
        and carry them out in anything the feedback shows of the program's run."""
        if ch.get("depends") and self.tree.has_solutions:
            return ("chapters " if len(ch["depends"]) > 1 else "chapter ") + ", ".join(ch["depends"])
        return ""

    def _program_said(self, ch, output):
        """What the feedback shows of the chapter program's output: as it printed it (no pattern is
        run over a student's output), unless the program also holds the course's own code."""
        which = self._course_code_in(ch)
        if which:
            return f"(the program's output is not shown: it also holds the course's own code of {which}; " \
                   "run it in your kit to see it)"
        return trim(output, 1000)

    def _figures_shown(self, ch, figures):
        """imgcmp's figures on the program's picture (pixels that differ, the largest difference),
        unless the program holds the course's own code: its picture could encode those bytes in the
        figures (about 25 bits a grading). Then only match or not is shown, one bit."""
        which = self._course_code_in(ch)
        if which:
            return f"(figures not shown: the program also holds the course's own code of {which}; " \
                   "compare your render in your kit with imgcmp)"
        return figures

    def _imgcmp(self, ch, picture_bytes, reference, logs, user):
        """imgcmp on the student's picture against the reference (both bytes), as the sandbox user with
        limits (it decodes a file the student made). Returns (figures, matched, diff bytes or None)."""
        # The two pictures in a folder of the grader's (read-only for imgcmp: no process of the sandbox
        # user can swap them), the difference image in a scratch folder of imgcmp's own.
        pictures = os.path.join(self._per.work, f"imgcmp-in-{ch['id']}")
        make_dir(pictures, None, 0o711)
        fsutil.write_new(pictures, "render.png", picture_bytes, 0o644)
        fsutil.write_new(pictures, "reference.png", reference, 0o644)
        scratch = os.path.join(self._per.work, f"imgcmp-{ch['id']}")
        make_dir(scratch, user, 0o700)
        imgcmp = os.path.join(self.tree.build, "bin", "imgcmp")
        limits = Limits(wall_seconds=60, cpu_seconds=60, memory_bytes=1024 * MiB, file_bytes=64 * MiB, processes=8)
        # A Monte Carlo picture (chNN.json's noisy_picture) is compared by statistics: per tile, the mean
        # difference against its standard error (common/image_compare.hpp), never a pixel threshold.
        statistical = ["--statistical"] if ch.get("noisy_picture") else []
        outcome = sandbox.run([imgcmp, os.path.join(pictures, "render.png"), os.path.join(pictures, "reference.png"),
                               "--diff", os.path.join(scratch, "diff.png")] + statistical,
                              limits=limits, log_path=os.path.join(logs, "imgcmp"), user=user,
                              inputs=[imgcmp, pictures], scratch=scratch, private_root=self._per.work)
        figures = "\n".join(line for line in outcome.output.strip().splitlines()
                            if not line.startswith("difference image:"))
        try:
            diff_png = fsutil.read_regular(os.path.join(scratch, "diff.png"), 64 * MiB)
        except (OSError, fsutil.Refused):
            diff_png = None
        fsutil.remove_tree(scratch)
        fsutil.remove_tree(pictures)
        if outcome.timed_out or outcome.returncode < 0:
            figures = f"imgcmp {sandbox.describe_ending(outcome, limits)} on this picture"
        return figures, outcome.returncode == 0 and not outcome.timed_out, diff_png

    # --- scoring ------------------------------------------------------------------------
    def _result(self, name, kind, cid, passed, output):
        entry = self.entries.get(name, {"points": 0, "visibility": "visible"})
        return TestResult(name, kind, cid, passed, output, entry["points"], entry.get("visibility", "visible"))

    def _compilation_entry(self, cid, message):
        return TestResult(f"{cid} compilation", "compilation", cid, False, message, 0, "visible")


class _Budget:
    """The time of one chapter's cases in one phase. Every case has its own limit (the judge kills the
    runner at it); together they may take chapter_seconds, and none starts after the phase's end. A case
    that went past its limit marks its concept (the test's name without the scalar type, "...<float>"
    and "...<double>" are one concept): the concept's other cases are skipped, so a correct answer that
    is slow on one idea loses that idea's tests, and the time of one limit for it, nothing else."""

    def __init__(self, options, phase_end):
        self.options = options
        self.chapter_end = min(time.monotonic() + options.chapter_seconds, phase_end)
        self.phase_end = phase_end
        self.timeouts = 0
        self.slow = {}      # concept -> the case that went past its limit

    def seconds_left(self):
        return self.chapter_end - time.monotonic()

    def timed_out(self, case):
        self.timeouts += 1
        self.slow.setdefault(concept_of(case), case)

    def skipped(self, case):
        """'' when the case may run, else why it is skipped (its concept went past its limit)."""
        first = self.slow.get(concept_of(case))
        if first is None or first == case:
            return ""
        return (f"not run: '{first}' tests the same idea and did not finish in time, so this one was skipped "
                "(each idea that is too slow costs its own tests only)")

    def reason(self):
        """'' while the chapter may start more cases, else why its remaining cases are not run."""
        now = time.monotonic()
        if now > self.phase_end:
            return (f"not run: the submission's tests used their time budget (the visible tests "
                    f"{self.options.visible_seconds:g} s, all tests {self.options.submission_seconds:g} s)")
        if now > self.chapter_end:
            return f"not run: this chapter's tests used their time budget ({self.options.chapter_seconds:g} s)"
        return ""

    def why_not_run(self, case):
        return self.skipped(case) or self.reason()


_TYPE_SUFFIX = re.compile(r"<[^<>]*>$")


def concept_of(case):
    """A test case's idea: its name without doctest's template argument ("...<float>")."""
    return _TYPE_SUFFIX.sub("", case)


def first_error_line(message):
    """The compiler's first error line in a compilation message ('' when there is none)."""
    for line in message.splitlines():
        if re.search(r"\berror\b", line):
            return line.strip()
    return ""


_NOISE = re.compile(r"^(\[doctest\] .*|={20,})$\n?", re.M)
_LOCATION = re.compile(r"^\S*?([^/\s]+\.(?:cpp|hpp)):(\d+):", re.M)


def _clean_doctest_output(text):
    """doctest's report without its banner, rulers and counts (the grader
    gives the verdict), and with file names instead of the grader's paths."""
    text = _NOISE.sub("", text)
    text = _LOCATION.sub(r"\1:\2:", text)
    return re.sub(r"\n{3,}", "\n\n", text).strip()


def _hidden_feedback(text):
    """A hidden test shows only the concept it checks: the messages of its
    failed checks and exceptions, never values or expressions."""
    keep = []
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("logged:"):
            message = s[len("logged:"):].strip()
            if " := " not in message:    # CAPTURE(x) would print a value: never for hidden tests
                keep.append(message)
        elif "THREW exception:" in s or "threw exception:" in s:
            keep.append("the test threw an exception: " + s.split("exception:", 1)[1].strip())
        elif "CRASHED" in s:
            keep.append("the test crashed: " + s.split("CRASHED", 1)[1].strip(" :!"))
    seen = []
    for k in keep:
        if k not in seen:
            seen.append(k)
    return "\n".join(seen[:10])
