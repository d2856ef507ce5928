"""What the tests of the course's tools share (tests/tools/*_tests.py, ctest label 'grader').

The runner: ctest gives the folders on the command line, then the tests to
run, named as unittest names them (a class, or a class and a method):

    grader_tests.py --work DIR --build-dir TREE Baseline
    grader_tests.py --work DIR --build-dir TREE Adversarial.test_segfault

Grading: grade() runs the real command line (tools/grader/grade) and keeps
what it said; ToolTest.assertGraded() checks what every grading must give, a
valid results.json in Gradescope's schema whose score is the sum of its tests'.
"""

import argparse
import fnmatch
import glob
import json
import os
import shutil
import subprocess
import sys
import time
import unittest
from dataclasses import dataclass

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GRADE = os.path.join(REPO, "tools", "grader", "grade")
FIXTURES = os.path.join(REPO, "tests", "fixtures", "adversarial")
ROOT = os.geteuid() == 0

# The folders the tests work in, from the command line (see main()).
config = argparse.Namespace(work=None, build_dir=None, kit=None, imgcmp=None, program=None)


def main():
    """Reads the folders, then lets unittest run the tests named on the rest of the command line."""
    p = argparse.ArgumentParser(add_help=False)
    p.add_argument("--work", required=True, help="a scratch folder of these tests")
    p.add_argument("--build-dir", help="the instructor's grading tree (made by grader.baseline)")
    p.add_argument("--kit", help="the student kit exported by grader.export.kit")
    p.add_argument("--imgcmp", help="the imgcmp program of this build")
    p.add_argument("--program", help="a chapter program of this build")
    args, names = p.parse_known_args()
    for key, value in vars(args).items():
        setattr(config, key, os.path.abspath(value) if value else None)
    os.makedirs(config.work, exist_ok=True)
    unittest.main(module="__main__", argv=[sys.argv[0], "-v", *names])


@dataclass
class Graded:
    """One run of the grader: its results.json (None when missing or not JSON) and what it printed."""
    path: str
    data: dict
    returncode: int
    stdout: str
    stderr: str
    seconds: float


def grade(submission, out, chapters, build_dir=None, limits=(), env_extra=None, grade_cmd=GRADE, timeout=300,
          as_user=None, prefix=()):
    """Grades submission with the grader's own command line; never raises on a failed grading.
    as_user: run it as that user (root only; with Debian's python3, which every user may run).
    prefix: a command the grader runs under (e.g. setpriv dropping a capability)."""
    env = dict(os.environ)
    env.pop("RT_GRADER_ISOLATION", None)
    env.update(env_extra or {})
    cmd = [sys.executable, grade_cmd, submission, "--out", out, "--chapters", chapters, *limits]
    if as_user:
        cmd = ["runuser", "-u", as_user, "--", "/usr/bin/python3", *cmd[1:]]
    cmd = [*prefix, *cmd]
    if build_dir:
        cmd += ["--build-dir", build_dir]
    if os.path.exists(out):
        os.remove(out)
    start = time.monotonic()
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    seconds = time.monotonic() - start
    print(result.stdout[-3000:])
    print(result.stderr[-3000:], file=sys.stderr)
    data = None
    try:
        with open(out) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        print(f"{out}: {e}", file=sys.stderr)
    print(f"graded {submission} in {seconds:.1f} s: {total_score(data) if data else '-'}")
    return Graded(out, data, result.returncode, result.stdout, result.stderr, seconds)


def total_score(data):
    """Every test's points, hidden ones too (results.json has a top-level score only when all are visible)."""
    return sum(t["score"] for t in data["tests"])


def compiler_cache(root):
    """Environment entries that let CMake builds under root use ccache when it is installed,
    with root's paths made relative, so a copy built again elsewhere (a new kit, a new clone)
    finds its objects in the cache. The commands themselves stay as a user types them."""
    if not shutil.which("ccache") or "CMAKE_CXX_COMPILER_LAUNCHER" in os.environ:
        return {}
    return {"CMAKE_CXX_COMPILER_LAUNCHER": "ccache", "CCACHE_BASEDIR": os.environ.get("CCACHE_BASEDIR", root),
            "CCACHE_NOHASHDIR": os.environ.get("CCACHE_NOHASHDIR", "true")}


def solution_folder(chapter):
    """solutions/NN-name of a chapter number NN."""
    return glob.glob(os.path.join(REPO, "solutions", f"{chapter}-*"))[0]


def fixture_source(name, substitutions=None):
    """Chapter 01's exercise file of the adversarial fixture NAME: its attack.cpp followed by the
    correct answer all fixtures share (FIXTURES/answer.cpp), or preceded by the file its expect.json
    names as "prelude" (a shared wrong answer, FIXTURES/own_picture.cpp), or its own unit_sphere.cpp
    when it answers wrongly anyway; None when it has none. substitutions: {placeholder: text}."""
    folder = os.path.join(FIXTURES, name)
    parts = [os.path.join(folder, "attack.cpp"), os.path.join(FIXTURES, "answer.cpp")]
    expect = os.path.join(folder, "expect.json")
    prelude = json.load(open(expect)).get("prelude") if os.path.isfile(expect) else None
    if prelude:     # a shared wrong answer written before the attack (own_picture.cpp)
        parts = [os.path.join(FIXTURES, prelude), parts[0]]
    if not os.path.isfile(parts[0]):
        parts = [os.path.join(folder, "unit_sphere.cpp")]
        if not os.path.isfile(parts[0]):
            return None
    text = ""
    for path in parts:
        with open(path) as f:
            text += f.read()
    for key, value in (substitutions or {}).items():
        text = text.replace(key, value)
    return text


def fixture_files(name):
    """The other files of fixture NAME that go into its submission as they are."""
    keep = lambda p: os.path.basename(p) not in ("attack.cpp", "unit_sphere.cpp", "expect.json", "sandbox.json")
    return [p for p in sorted(glob.glob(os.path.join(FIXTURES, name, "*"))) if keep(p)]


def make_submission(dest, sources=(), solutions=(), files=None):
    """A fresh submission folder: the given files at its top, the solution
    files of the given chapters in chapters/NN-name/, and files ({path in
    the submission: text}) written as given."""
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(dest)
    for path in sources:
        shutil.copy(path, dest)
    for rel, text in (files or {}).items():
        os.makedirs(os.path.dirname(os.path.join(dest, rel)) or dest, exist_ok=True)
        with open(os.path.join(dest, rel), "w") as f:
            f.write(text)
    for chapter in solutions:
        folder = solution_folder(chapter)
        shutil.copytree(folder, os.path.join(dest, "chapters", os.path.basename(folder)))
    for dirpath, _, _ in os.walk(dest):
        os.chmod(dirpath, 0o755)
    return dest


def matches(name, patterns):
    return any(fnmatch.fnmatchcase(name, p) for p in patterns)


def add_fixture_tests(cls, marker):
    """One test method per fixture folder FIXTURES/NAME/ that matches `marker`
    (a glob such as "*/expect.json"): test_NAME ('-' read as '_') calls
    cls.check_fixture(NAME), so each fixture is its own ctest entry."""
    for path in sorted(glob.glob(os.path.join(FIXTURES, marker))):
        name = os.path.basename(os.path.dirname(path))

        def test(self, name=name):
            self.check_fixture(name)
        test.__doc__ = f"tests/fixtures/adversarial/{name}"
        setattr(cls, "test_" + name.replace("-", "_"), test)


class ToolTest(unittest.TestCase):
    maxDiff = 4000

    def assertGraded(self, graded):
        """The grader ended normally and wrote a valid results.json; returns its data."""
        self.assertEqual(graded.returncode, 0, f"grade exited with {graded.returncode}:\n{graded.stderr[-2000:]}")
        return self.assertValidResults(graded.path)

    def assertValidResults(self, path):
        """results.json exists, is JSON, follows Gradescope's schema, and its score is its tests' sum."""
        self.assertTrue(os.path.isfile(path), f"{path} was not written")
        with open(path) as f:
            try:
                data = json.load(f)
            except ValueError as e:
                self.fail(f"{path} is not valid JSON: {e}")
        for key, kind in (("execution_time", (int, float)), ("output", str), ("stdout_visibility", str),
                          ("tests", list)):
            self.assertIsInstance(data.get(key), kind, f"results.json: '{key}' missing or of the wrong type")
        for t in data["tests"]:
            for key, kind in (("name", str), ("number", str), ("score", (int, float)),
                              ("max_score", (int, float)), ("status", str), ("output", str), ("tags", list),
                              ("visibility", str)):
                self.assertIsInstance(t.get(key), kind, f"results.json test {t.get('name')}: '{key}' missing or wrong")
            self.assertIn(t["status"], ("passed", "failed"), f"{t['name']}: status")
            self.assertTrue(0 <= t["score"] <= t["max_score"], f"{t['name']}: score {t['score']} outside [0, max]")
        # Before publication the student sees the visible tests only: the top-level score (which Gradescope
        # shows at once) is there only when every test is visible, and the summary line counts visible ones.
        visible = [t for t in data["tests"] if t["visibility"] == "visible"]
        shown = sum(t["score"] for t in visible)
        if len(visible) == len(data["tests"]):
            self.assertIsInstance(data.get("score"), (int, float), "results.json: 'score' missing")
            self.assertAlmostEqual(shown, data["score"], delta=1e-9, msg="the score is not the sum of the tests")
        else:
            self.assertNotIn("score", data, "a top-level score while some tests are hidden: it counts them")
        self.assertTrue(data["output"].startswith(f"Score {shown:g} / {sum(t['max_score'] for t in visible):g}")
                        or data["tests"][0]["name"] == "grader",
                        f"the summary line counts more than the visible tests: {data['output'][:200]}")
        return data

    def assertFullMarks(self, data, who):
        total = sum(t["max_score"] for t in data["tests"])
        failed = [f"{t['name']}: {t['output'][:200]}" for t in data["tests"] if t["status"] != "passed"]
        self.assertGreater(total, 0, f"{who}: no test has points")
        score = total_score(data)
        self.assertEqual(score, total, f"{who} scored {score} of {total}:\n" + "\n".join(failed)[:2000])
        self.assertEqual(failed, [], f"{who}: tests failed")

    def assertStatuses(self, label, data, must_fail, may_differ, expected):
        """Every test named by must_fail fails; every other one not named by may_differ has the status
        expected says (a name -> status map, e.g. the solutions'); none passes where expected fails."""
        mine = {t["name"]: t for t in data["tests"]}
        for name, status in expected.items():
            with self.subTest(test=name):
                self.assertIn(name, mine, f"{label}: test {name} is missing from the results")
                got = mine[name]["status"]
                if matches(name, must_fail):
                    self.assertEqual(got, "failed", f"{label}: {name} passed, but this submission must fail it")
                elif not matches(name, may_differ):
                    self.assertEqual(got, status, f"{label}: {name} is {got}, but {status} for the solutions: "
                                                  f"{mine[name]['output'][:300]}")
                self.assertFalse(got == "passed" and status == "failed", f"{label}: false pass of {name}")
