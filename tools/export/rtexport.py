"""The student-kit exporter and the Gradescope bundle (see tools/grader/README.md).

The kit is built from an allow-list: only what a student needs is copied,
so a new private folder never leaks by accident. READMEs lose their
instructor-only passages and CMakePresets.json keeps only the student preset.
Every export then checks the written kit twice, and fails naming the file:
every file must be on the list of what may ship (KIT_SHIP: chapter stubs and
programs as the chapters' CMakeLists.txt name them, headers, READMEs,
pictures, common/, public tests, scenes, build files, the grader), and the
leak check compares the kit with the private files (solutions/, tests/hidden/,
tests/fixtures/). That nothing in the kit computes an answer when the
chapters are stubs (the semantic check) needs a build of the kit: it is in
tests/tools/export_tests.py.
"""

import fnmatch
import glob
import json
import os
import re
import shutil
import stat
import zipfile

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# What a kit holds: files or folders relative to the repository (missing ones are skipped).
# tools/render, tools/bench and tools/study stay out: the renderer's fast path
# and the study compute the exercises' answers (sphere, plane, triangle, robust
# sphere) with their own code, and the benchmark needs them.
KIT_ALLOW = [
    "CMakeLists.txt", "CMakePresets.json",
    "cmake", "common", "chapters", "scenes",
    "tests/CMakeLists.txt", "tests/support", "tests/public", "tests/common", "tests/scenes",
    "tools/CMakeLists.txt", "tools/imgcmp.cpp", "tools/setup", "tools/check", "tools/debian-packages.txt",
    "tools/grader",
]
# Never in a kit, even inside an allowed folder.
KIT_DENY = ["*/__pycache__/*", "*.pyc", "*/.DS_Store",
            "/tests/scenes/scene_plan_test.cpp",    # tests tools/render, which is not in the kit
            "/tests/scenes/bvh_test.cpp",           # part of scene_plan_test's executable (tools/render's tree)
            "/tests/scenes/far-sphere-up-close.json",  # a scene of rt-render's acne test (tools/render)
            "/tests/scenes/far-sphere-instanced.json", # the same, for rt-render's two-level path
            "/tools/grader/README.md",              # the instructor's manual: the kit's README says how to preview
            "/tools/grader/screenshots/*",          # its pictures
            "/tools/grader/results/*",              # where and when the instructor's figures were measured
            "/tests/support/rpc/README.md",                # the judge/runner layer's page for contributors
            "/chapters/07-precision/worked_values.cpp",    # evaluates the stable root pair: step 2's answer
            # computes answers itself: the mirror direction (reflect's) and refract's cos_t^2 four ways
            "/chapters/09-reflection/spawn_study.cpp",
            # computes answers itself: its exact reference intersects spheres (the stable pair over
            # the perpendicular foot: chapter 07's steps) and triangles (Cramer's rule) in long double
            "/chapters/10-transforms/rounding_study.cpp",
            # computes no answer (it only draws the chapter's picture with the student's functions and
            # compares the bits), but it is an instructor-side test, built on the solutions side only
            "/chapters/11-sampling/same_on_every_thread_count.cpp"]
PRIVATE = ["solutions", "tests/hidden", "tests/fixtures"]

# What may ship, by kind: every file of a written kit must match one of these
# patterns ('*' stays inside one folder, '**' crosses folders, NN is a
# chapter number), or the export fails naming the file. A chapter's .cpp
# files may ship only when its CMakeLists.txt names them as EXERCISES (the
# stubs) or PROGRAM (the chapter program, which runs the student's code), or
# when they are listed under "programs" here.
CHAPTER = "chapters/NN-*/"
KIT_SHIP = {
    "build files": ["CMakeLists.txt", "CMakePresets.json", ".gitignore", "cmake/*.cmake",
                    "common/CMakeLists.txt", "common/*.cmake", CHAPTER + "CMakeLists.txt", CHAPTER + "*.cmake", "tests/CMakeLists.txt",
                    "tests/common/CMakeLists.txt", "tests/scenes/CMakeLists.txt", "tools/CMakeLists.txt"],
    "READMEs": ["README.md", CHAPTER + "README.md", "scenes/README.md"],
    "chapter headers": [CHAPTER + "*.hpp"],
    # A measurement that runs the student's own shadow_ray_origin (chapter 06's README, "Shadow acne").
    "programs": ["chapters/06-shading/acne_study.cpp",
                 # Chapter 11's error study: it draws with the student's own sampling code.
                 "chapters/11-sampling/sampling_study.cpp",
                 # Chapter 12's error study: it draws with the student's own path_radiance.
                 "chapters/12-path-tracing/path_study.cpp"],
    "pictures": [CHAPTER + "**.png", CHAPTER + "**.svg", "tests/common/data/*.png"],
    # Numbers, not code: the reference solution's t for every ray of chapter
    # 07's picture, written by ch07-reference-hits and kept equal to the
    # solution's answers by ctest ch07.reference_hits. The kit's --error
    # measures against them instead of the student's own long double code.
    "reference answers": ["chapters/07-precision/reference_hits.bin"],
    "common/": ["common/*.hpp", "common/*.cpp", "common/*.html"],
    "public tests": ["tests/public/chNN_*.cpp", "tests/public/chNN_*.hpp", "tests/manifest.json",
                     "tests/support/**.hpp", "tests/support/**.cpp", "tests/common/*.cpp",
                     "tests/scenes/*_test.cpp", "tests/scenes/*.cmake", "tests/scenes/broken/*.json"],
    "scenes": ["scenes/*.json", "scenes/*.obj"],
    "student tools": ["tools/imgcmp.cpp", "tools/setup", "tools/check", "tools/debian-packages.txt"],
    "the grader (for previews)": ["tools/grader/**"],
}
# The kit's own files, written by the exporter from these templates.
TEMPLATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "templates")
# Passages of a README that only work in the instructor's repository (they
# name solutions/, the dev preset, tools that stay out): the kit's copy drops
# everything from the opening marker line to the closing one.
INSTRUCTOR_ONLY = ("<!-- instructor-only -->", "<!-- /instructor-only -->")
# Words of a README that name something the kit leaves out, and what the
# kit's copy says instead (for mentions inside a sentence, where a marker
# line cannot cut). tools/diagrams stays out: its figures compute crossings,
# slabs and boxes, i.e. the exercises' geometry.
KIT_REWRITES = [
    (r"\(drawn by `tools/diagrams/make_diagrams\.py`\.\)", "(drawn by the course's figure script.)"),
]
# The presets a kit keeps (and the hidden ones they inherit): the others build
# the solutions, which the kit does not have.
KIT_PRESETS = ["student"]
# Text that a stub or a public test shares with a solution or a hidden test
# legitimately (the same header, the same explicit instantiation lines...).
SHARED_SOURCES = ["chapters", "tests/public", "tests/support"]
MIN_DISTINCTIVE = 24    # characters: shorter lines ("return std::nullopt;") prove nothing
LEAK_RUN = 3            # consecutive private lines that make a leak


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
    """The repository files the kit copies (before the ship check)."""
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


def _pattern_re(pattern):
    out = ""
    i = 0
    while i < len(pattern):
        if pattern.startswith("**", i):
            out += ".*"
            i += 2
        elif pattern.startswith("NN", i):
            out += "[0-9][0-9]"
            i += 2
        elif pattern[i] == "*":
            out += "[^/]*"
            i += 1
        else:
            out += re.escape(pattern[i])
            i += 1
    return re.compile(out + r"\Z")


def _chapter_sources(kit):
    """chapters/NN-name/FILE for every EXERCISES and PROGRAM file a chapter's CMakeLists.txt names."""
    allowed = {}
    for cmake in sorted(glob.glob(os.path.join(kit, "chapters", "[0-9][0-9]-*", "CMakeLists.txt"))):
        folder = os.path.relpath(os.path.dirname(cmake), kit)
        with open(cmake) as f:
            text = re.sub(r"#[^\n]*", "", f.read())
        for call in re.findall(r"rt_chapter\s*\((.*?)\)", text, re.S):
            words = re.findall(r'"[^"]*"|\S+', call)
            kind = None
            for w in words:
                if w in ("EXERCISES", "PROGRAM"):
                    kind = "chapter exercises (stubs)" if w == "EXERCISES" else "chapter programs"
                elif w in ("TITLE", "DEPENDS"):
                    kind = None
                elif kind:
                    allowed[f"{folder}/{w}"] = kind
    return allowed


def ship_check(kit):
    """Files of the written kit that are on no list of what may ship, as problems naming them."""
    patterns = [(kind, _pattern_re(p)) for kind, ps in KIT_SHIP.items() for p in ps]
    chapter_sources = _chapter_sources(kit)
    problems = []
    for dirpath, dirnames, filenames in os.walk(kit):
        dirnames[:] = sorted(d for d in dirnames if not (dirpath == kit and d in ("build", "out", "renders")))
        for name in sorted(filenames):
            rel = os.path.relpath(os.path.join(dirpath, name), kit).replace(os.sep, "/")
            if rel in chapter_sources or any(r.match(rel) for _, r in patterns):
                continue
            problems.append(f"not on the list of what may ship: {rel}")
    return problems


def strip_instructor_only(text, where):
    """text without its instructor-only passages; an unbalanced marker is an error naming the line."""
    kept, inside = [], None
    for number, line in enumerate(text.splitlines(keepends=True), 1):
        marker = line.strip()
        if marker == INSTRUCTOR_ONLY[0]:
            if inside:
                raise SystemExit(f"kit: {where}:{number}: instructor-only passage opened twice (line {inside})")
            inside = number
        elif marker == INSTRUCTOR_ONLY[1]:
            if not inside:
                raise SystemExit(f"kit: {where}:{number}: {INSTRUCTOR_ONLY[1]} without an opening marker")
            inside = None
        elif not inside:
            kept.append(line)
    if inside:
        raise SystemExit(f"kit: {where}:{inside}: instructor-only passage never closed")
    return re.sub(r"\n{3,}", "\n\n", "".join(kept))


def kit_presets(text):
    """CMakePresets.json with only the presets that build in a kit (and the hidden ones they inherit)."""
    data = json.loads(text)
    for kind in ("configurePresets", "buildPresets", "testPresets"):
        presets = {p["name"]: p for p in data.get(kind, [])}
        keep, todo = set(), [n for n in KIT_PRESETS if n in presets]
        while todo:
            name = todo.pop()
            if name in keep:
                continue
            keep.add(name)
            inherits = presets[name].get("inherits", [])
            todo += [inherits] if isinstance(inherits, str) else list(inherits)
        data[kind] = [p for p in data.get(kind, []) if p["name"] in keep]
    return json.dumps(data, indent=2) + "\n"


def _copy(repo, rel, dst):
    src = os.path.join(repo, rel)
    if rel == "CMakePresets.json":
        with open(src) as f, open(dst, "w") as g:
            g.write(kit_presets(f.read()))
    elif rel.endswith(".md"):
        with open(src) as f:
            text = strip_instructor_only(f.read(), rel)
        for pattern, replacement in KIT_REWRITES:
            text = re.sub(pattern, replacement, text)
        with open(dst, "w") as g:
            g.write(text)
    else:
        shutil.copy2(src, dst)


def export_kit(out, repo=REPO, log=print):
    """Writes the student kit into out (which must not exist or be empty); returns the file count."""
    if os.path.exists(out) and os.listdir(out):
        raise SystemExit(f"kit: {out} exists and is not empty")
    files = kit_files(repo)
    for rel in files:
        dst = os.path.join(out, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        _copy(repo, rel, dst)
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
    for template, name in (("README.md", "README.md"), ("gitignore", ".gitignore")):
        shutil.copyfile(os.path.join(TEMPLATES, template), os.path.join(out, name))
    problems = ship_check(out) + leak_check(out, repo) + answer_check(out, repo)
    if problems:
        raise SystemExit("kit: LEAK CHECK FAILED, the kit is not safe to hand out:\n" + "\n".join(problems[:50]))
    count = sum(len(names) for _, _, names in os.walk(out))
    log(f"kit: {count} files written to {out}; every file is on the list of what may ship; leak check passed")
    return count


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


# --- The answer check -------------------------------------------------------------------------
#
# The leak check finds private lines pasted into the kit. An exercise's answer written again with
# other names (a test helper's brute force that is chapter 03's loop, a study program's offset that
# is shadow_ray_origin's formula) shares no line with the solution, but its statements are the
# solution's once the names are taken out. So every code file of the kit is compared, statement by
# statement with local names replaced by one placeholder, with the solutions: a long statement of a
# solution, or a run of consecutive ones, is an answer in the kit. Statements a solution shares with
# the kit's chapter headers and stubs (declarations, explicit instantiations) prove nothing.
ANSWER_STATEMENT = 64   # characters, names taken out: one solution statement this long is an answer
ANSWER_RUN = 3          # or this many consecutive solution statements, two of them its own...
ANSWER_RUN_CHARS = 36   # ...with this many characters together
# ...as long as one of them touches the course's own data (a member that is not a standard
# container's: .t, ->object, .max, .x), so that idioms such as a stack loop prove nothing.
_CONTAINER_MEMBERS = set("""back begin clear data emplace emplace_back empty end erase find front insert pop_back
    push_back reserve resize size swap value has_value""".split())
_KEEP_WORDS = set("""alignas auto bool break case catch char class const constexpr continue default delete do double
    else enum explicit false float for if inline int long namespace new noexcept nullptr operator private protected
    public return short signed sizeof static static_cast struct switch template this throw true try typename union
    unsigned using virtual void volatile while T size_t""".split())
_CODE_FILE = (".cpp", ".hpp", ".h", ".cc")


def _code_of(text):
    """The text without comments, string and character literals and preprocessor lines."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            out.append(" ")
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "\n".join(line for line in "".join(out).splitlines() if not line.lstrip().startswith("#"))


def _statements(text):
    """The code's statements (split after ';', and after '{' and '}' at the end of a line), whitespace collapsed, local names replaced by 'ID'
    (a name after '.', '->' or '::', before '::' or '(', or a keyword, stays)."""
    def name(m):
        word, before, after = m.group(0), text_[max(0, m.start() - 2):m.start()], text_[m.end():m.end() + 2]
        if word in _KEEP_WORDS or before.endswith(".") or before == "->" or before == "::" or \
                after == "::" or after.startswith("("):
            return word
        return "ID"
    # Split after ';' outside parentheses (a for header stays whole) and after '{' or '}' at a line's end.
    code, pieces, depth, start = _code_of(text), [], 0, 0
    for i, c in enumerate(code):
        depth += (c == "(") - (c == ")")
        if (c == ";" and depth <= 0) or (c in "{}" and code[i + 1:i + 2] in ("", "\n")):
            pieces.append(code[start:i + 1])
            start = i + 1
    pieces.append(code[start:])
    statements = []
    for piece in pieces:
        text_ = " ".join(piece.split())
        if text_ in ("", "{", "}", "};"):
            continue
        statements.append(re.sub(r"[A-Za-z_]\w*", name, text_))
    return statements


def answer_check(kit, repo=REPO):
    """Problems found: kit code files holding an exercise's statements written again with other names."""
    def statements_of(root, rel):
        lines, _ = _text_lines(os.path.join(root, rel))
        return _statements("\n".join(lines or []))
    sources = _chapter_sources(kit)
    stubs = [f for f, kind in sources.items() if kind == "chapter exercises (stubs)"]
    # The exercises' own files in the solutions (solutions/NN-name/FILE for each stub), not the
    # solutions' study tools.
    answers = [os.path.join("solutions", os.path.relpath(f, "chapters")) for f in stubs]
    answers = [f for f in answers if os.path.isfile(os.path.join(repo, f))]
    if not answers:
        return []
    # What an answer legitimately shares with the kit: its chapter's header and stub, and the shared
    # vocabulary of common/ and the test support (a run of statements may pass through them, but
    # must hold one of the answer's own).
    shared = set()
    for top in ("chapters", "common", os.path.join("tests", "support")):
        for f in _walk(kit, top):
            if f.endswith(_CODE_FILE) and (f.endswith((".hpp", ".h")) or f in stubs or not f.startswith("chapters")):
                shared.update(statements_of(kit, f))
    where, follows = {}, set()   # each answer statement's file, and which statement follows which
    files_of = {}                # the answer files each statement appears in
    for f in answers:
        statements = statements_of(repo, f)
        follows.update(zip(statements, statements[1:]))
        for st in statements:
            where.setdefault(st, f)
            files_of.setdefault(st, set()).add(f)
    def own(statement):
        # One of an answer's own statements: not shared with the kit, not a loop or branch head, and
        # not the course's vocabulary that several exercises write alike (filling in a hit record).
        return statement not in shared and len(files_of.get(statement, ())) == 1 and \
            not re.match(r"(for|while|if|else|switch|do)\b", statement)

    def touches_data(statement):
        return any(m not in _CONTAINER_MEMBERS for m in re.findall(r"(?:\.|->)([A-Za-z_]\w*)", statement))
    problems = []
    for rel in sorted(os.path.relpath(os.path.join(d, n), kit) for d, _, names in os.walk(kit) for n in names):
        if not rel.endswith(_CODE_FILE) or rel in stubs:
            continue
        run, found = [], None
        for st in statements_of(kit, rel) + ["<end>"]:
            if st in where and st not in shared and len(st) >= ANSWER_STATEMENT and touches_data(st):
                found = found or [st]
            if st in where and (not run or (run[-1], st) in follows):
                run.append(st)
                continue
            if len(run) >= ANSWER_RUN and sum(len(x) for x in run) >= ANSWER_RUN_CHARS and \
                    any(touches_data(x) for x in run) and sum(own(x) for x in run) >= 2:
                found = found or run
            run = [st] if st in where else []
        if found:
            problems.append(f"{rel} computes an exercise's answer: its code is {where[found[0]]}'s with other "
                            f"names, from: {' '.join(found)[:100]}")
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
