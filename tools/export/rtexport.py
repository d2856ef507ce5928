"""The student-kit exporter and the Gradescope bundle (see tools/grader/README.md).

The kit is built from an allow-list: only what a student needs is copied,
so a new private folder never leaks by accident. Every export then runs a
leak check that compares the kit with the private files (solutions/,
tests/hidden/, tests/fixtures/) and fails the export on any match.
"""

import fnmatch
import json
import os
import re
import shutil
import stat
import zipfile

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# What a kit holds: files or folders relative to the repository (missing ones are skipped).
KIT_ALLOW = [
    "CMakeLists.txt", "CMakePresets.json", ".gitignore",
    "cmake", "common", "chapters", "scenes",
    "tests/CMakeLists.txt", "tests/support", "tests/public", "tests/common", "tests/scenes",
    "tools/CMakeLists.txt", "tools/imgcmp.cpp", "tools/setup", "tools/debian-packages.txt", "tools/render",
    "tools/grader",
]
# Never in a kit, even inside an allowed folder.
KIT_DENY = ["*/__pycache__/*", "*.pyc", "*/.DS_Store"]
PRIVATE = ["solutions", "tests/hidden", "tests/fixtures"]
# Text that a stub or a public test shares with a solution or a hidden test
# legitimately (the same header, the same explicit instantiation lines...).
SHARED_SOURCES = ["chapters", "tests/public", "tests/support"]
MIN_DISTINCTIVE = 24    # characters: shorter lines ("return std::nullopt;") prove nothing
LEAK_RUN = 3            # consecutive private lines that make a leak

STUDENT_README = """# {title}: student kit

This folder is your copy of the course: the chapters (lecture, exercise
stubs, programs, reference pictures), the shared core in `common/`, the
public tests and the scenes. It builds on its own.

## Start

```sh
tools/setup                                  # installs the Debian packages (once)
cmake --preset student                       # configure (RT_SIDE=student: your code)
cmake --build --preset student --target ch01 ch01_public_tests
ctest --preset student -L ch01               # chapter 01's public tests
build/student/bin/ch01-unit-sphere --out out/ch01.png --compare chapters/01-unit-sphere/reference.png
```

Each chapter's `README.md` is its lecture and tells you which file to fill in
(`chapters/NN-name/*.cpp`). Until you do, the tests fail politely with
"not implemented yet".

## Preview your score

The course's grader runs here too, on the public tests and the pictures
(the hidden tests are only on the instructor's side):

```sh
tools/grader/grade . --out preview.json            # every chapter
tools/grader/grade . --out preview.json --chapters 01
```

It prints one line per chapter and writes `preview.json` (the same format
as the real grading). Submit only your exercise files: tests, headers and
build files always come from the instructor's copy.
"""


def _walk(root, rel):
    path = os.path.join(root, rel)
    if os.path.isfile(path):
        yield rel
        return
    for dirpath, dirnames, filenames in os.walk(path):
        dirnames.sort()
        for name in sorted(filenames):
            yield os.path.relpath(os.path.join(dirpath, name), root)


def kit_files(repo):
    files = []
    for rel in KIT_ALLOW:
        if not os.path.exists(os.path.join(repo, rel)):
            continue
        for f in _walk(repo, rel):
            if any(fnmatch.fnmatch("/" + f, pattern) for pattern in KIT_DENY):
                continue
            if any(f == p or f.startswith(p + os.sep) for p in PRIVATE):
                continue
            files.append(f)
    return files


def export_kit(out, repo=REPO, log=print):
    """Writes the student kit into out (which must not exist or be empty); returns the file count."""
    if os.path.exists(out) and os.listdir(out):
        raise SystemExit(f"kit: {out} exists and is not empty")
    files = kit_files(repo)
    for rel in files:
        dst = os.path.join(out, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(os.path.join(repo, rel), dst)
    # The public part of the grading manifest, for the score preview.
    manifest_path = os.path.join(repo, "tests", "manifest.json")
    if os.path.exists(manifest_path):
        with open(manifest_path) as f:
            data = json.load(f)
        public = {n: e for n, e in data["tests"].items() if ".hidden." not in n}
        with open(os.path.join(out, "tests", "manifest.json"), "w") as f:
            json.dump({"comment": "Points of the public tests and pictures (the preview's share of the grade).",
                       "tests": public}, f, indent=1)
            f.write("\n")
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write(STUDENT_README.format(title="A ray tracer, chapter by chapter"))
    problems = leak_check(out, repo)
    if problems:
        raise SystemExit("kit: LEAK CHECK FAILED, the kit is not safe to hand out:\n" + "\n".join(problems[:50]))
    log(f"kit: {len(files) + 2} files written to {out}; leak check passed")
    return len(files) + 2


def _text_lines(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None, b""
    if b"\0" in data[:4096]:
        return None, data
    return [line.strip() for line in data.decode("utf-8", errors="replace").splitlines()], data


def leak_check(kit, repo=REPO):
    """Problems found: private paths, private files, or distinctive private lines in the kit."""
    problems = []
    kit_files_ = [os.path.relpath(os.path.join(d, n), kit) for d, _, names in os.walk(kit) for n in names]
    for rel in kit_files_:
        if any(rel == p or rel.startswith(p + os.sep) for p in PRIVATE):
            problems.append(f"private path in the kit: {rel}")

    def lines_of(folders):
        found = set()
        for rel in folders:
            if os.path.exists(os.path.join(repo, rel)):
                for f in _walk(repo, rel):
                    lines, _ = _text_lines(os.path.join(repo, f))
                    found.update(lines or [])
        return found

    # A solution shares only its chapter's header, stub and lecture with the
    # kit: a solution line anywhere else (common/ included) is a leak. Tests
    # and fixtures also use the public API of common/ and the tools, so those
    # lines are public for them.
    shared_with_solutions = lines_of(SHARED_SOURCES)
    public_files = [f for f in kit_files(repo)]
    shared_with_tests = lines_of(public_files)
    distinctive = {}      # line -> the private file it comes from
    private_blobs = {}    # file contents -> private file
    for rel in PRIVATE:
        if not os.path.exists(os.path.join(repo, rel)):
            continue
        shared = shared_with_solutions if rel == "solutions" else shared_with_tests
        for f in _walk(repo, rel):
            lines, data = _text_lines(os.path.join(repo, f))
            if len(data) >= 64:
                private_blobs[data] = f
            for line in lines or []:
                if len(line) >= MIN_DISTINCTIVE and line not in shared:
                    distinctive.setdefault(line, f)
    hidden_names = {}     # test-case names of the hidden tests
    if os.path.isdir(os.path.join(repo, "tests", "hidden")):
        for f in _walk(repo, "tests/hidden"):
            lines, _ = _text_lines(os.path.join(repo, f))
            for line in lines or []:
                m = re.match(r'(?:TEST_CASE|TEST_CASE_TEMPLATE|SCENARIO)\s*\(\s*"([^"]{12,})"', line)
                if m:
                    hidden_names[m.group(1)] = f
    for rel in kit_files_:
        path = os.path.join(kit, rel)
        if rel == os.path.join("tests", "manifest.json"):
            with open(path) as f:
                if any(".hidden." in n for n in json.load(f).get("tests", {})):
                    problems.append("the kit's manifest names hidden tests")
            continue
        lines, data = _text_lines(path)
        if data in private_blobs:
            problems.append(f"{rel} is a copy of the private file {private_blobs[data]}")
            continue
        # A leak is a run of consecutive private lines (a pasted function, a
        # copied test): single lines like "for (int i = 0; i < 3; ++i) {" are
        # everyone's. Blank lines and lone braces do not break a run.
        run = []
        for number, line in enumerate((lines or []) + ["<end>"], 1):
            if line in ("", "{", "}", "};"):
                continue
            if line in distinctive:
                run.append((number, line))
                continue
            if len(run) >= LEAK_RUN:
                first, text = run[0]
                problems.append(f"{rel}:{first}-{run[-1][0]} holds {len(run)} consecutive lines of the private "
                                f"file {distinctive[text]}, from: {text[:80]}")
            run = []
        text = "\n".join(lines or [])
        for name, origin in hidden_names.items():
            if name in text:
                problems.append(f"{rel} names the hidden test '{name}' ({origin})")
    return problems


# --- Gradescope ------------------------------------------------------------------------------

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, when it builds the autograder's image: install the
# Debian packages, then build the instructor tree the grader links against, so
# that grading a submission only compiles its exercise files.
# AUTOGRADER_ROOT (default /autograder) lets the tests run it anywhere;
# RT_SKIP_APT=1 skips the package installation (packages already there);
# RT_GRADER_BUILD_DIR and RT_GRADER_CHAPTERS override where the tree is built
# and which chapters are graded.
set -euo pipefail
root="${AUTOGRADER_ROOT:-/autograder}"
source_dir="$root/source"
if [ -z "${RT_SKIP_APT:-}" ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update
  apt-get install -y --no-install-recommends $(grep -v '^\\s*#' "$source_dir/tools/debian-packages.txt")
fi
# The submission's code runs as unprivileged users: nothing of the instructor's
# source (solutions, hidden tests) may be readable by them.
chmod 700 "$source_dir"
chmod o+x "$root"      # ... but they must reach the grading folder's public copy
build_dir="${RT_GRADER_BUILD_DIR:-$root/grader}"
python3 "$source_dir/tools/grader/grade" --prepare-only --build-dir "$build_dir" \\
        ${RT_GRADER_CHAPTERS:+--chapters "$RT_GRADER_CHAPTERS"}
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission: grade /autograder/submission and
# write /autograder/results/results.json (the grader always writes it).
set -uo pipefail
root="${AUTOGRADER_ROOT:-/autograder}"
mkdir -p "$root/results"
python3 "$root/source/tools/grader/grade" "$root/submission" --out "$root/results/results.json" \\
        --build-dir "${RT_GRADER_BUILD_DIR:-$root/grader}" ${RT_GRADER_CHAPTERS:+--chapters "$RT_GRADER_CHAPTERS"}
exit 0
"""

BUNDLE_SKIP_TOP = {".git", "out"}


def bundle_files(repo):
    """The whole instructor repository, without build folders and caches."""
    files = []
    for dirpath, dirnames, filenames in os.walk(repo):
        rel_dir = os.path.relpath(dirpath, repo)
        top = rel_dir.split(os.sep, 1)[0]
        if rel_dir != "." and (top in BUNDLE_SKIP_TOP or top.startswith("build")):
            dirnames[:] = []
            continue
        dirnames[:] = sorted(d for d in dirnames if d != "__pycache__"
                             and not (rel_dir == "." and (d in BUNDLE_SKIP_TOP or d.startswith("build"))))
        for name in sorted(filenames):
            if not name.endswith(".pyc"):
                files.append(os.path.normpath(os.path.join(rel_dir, name)))
    return files


def _add(zf, arcname, data=None, path=None, executable=False):
    info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))
    mode = 0o755 if executable else 0o644
    if path is not None:
        mode = 0o755 if os.stat(path).st_mode & stat.S_IXUSR else 0o644
        with open(path, "rb") as f:
            data = f.read()
    info.external_attr = (stat.S_IFREG | mode) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    zf.writestr(info, data)


def export_gradescope(out_zip, repo=REPO, log=print):
    """Writes the Gradescope autograder zip: setup.sh and run_autograder at the
    top, next to the instructor repository (which becomes /autograder/source)."""
    files = bundle_files(repo)
    os.makedirs(os.path.dirname(os.path.abspath(out_zip)), exist_ok=True)
    with zipfile.ZipFile(out_zip + ".tmp", "w") as zf:
        _add(zf, "setup.sh", SETUP_SH, executable=True)
        _add(zf, "run_autograder", RUN_AUTOGRADER, executable=True)
        for rel in files:
            if rel in ("setup.sh", "run_autograder"):
                continue
            _add(zf, rel, path=os.path.join(repo, rel))
    os.replace(out_zip + ".tmp", out_zip)
    log(f"gradescope: {len(files) + 2} files in {out_zip}")


def unpack_bundle(zip_path, dest):
    """Unzips keeping the executable bits (zipfile drops them)."""
    with zipfile.ZipFile(zip_path) as zf:
        for info in zf.infolist():
            target = zf.extract(info, dest)
            mode = (info.external_attr >> 16) & 0o777
            if mode:
                os.chmod(target, mode)
