#!/usr/bin/env python3
"""Tests of the autograder itself (ctest label 'grader'; see tests/tools/CMakeLists.txt).

  grader_tests.py baseline   --work DIR --build-dir TREE   solutions score full marks, stubs zero (politely)
  grader_tests.py fixture NAME --work DIR --build-dir TREE one adversarial submission behaves as expected
  grader_tests.py batch      --work DIR --build-dir TREE   a folder of submissions, one results file each + CSV
  grader_tests.py kit        --work DIR                    a kit's preview with chapter 03 broken: the others count

Every grading runs the real command line (tools/grader/grade) on chapter 01
(and 02 where a fixture needs a second chapter) against one prebuilt
instructor tree, so the tests are quick after the first.
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

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GRADE = os.path.join(REPO, "tools", "grader", "grade")
FIXTURES = os.path.join(REPO, "tests", "fixtures", "adversarial")
GRADING_TIME_LIMIT = 300          # seconds: grading must end well before this
PREPARE_TIME_LIMIT = 850          # seconds: the first build of the grading tree (ctest gives 900)
TEST_LIMITS = ["--timeout", "6", "--render-timeout", "20"]

failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)
    return ok


def solution_files(chapter):
    """A submission's worth of the reference files of one chapter (a folder name NN-*)."""
    folder = glob.glob(os.path.join(REPO, "solutions", f"{chapter}-*"))[0]
    return folder, sorted(os.listdir(folder))


def make_submission(dest, sources=(), solutions=()):
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(dest)
    for path in sources:
        shutil.copy(path, dest)
    for chapter in solutions:
        folder, names = solution_files(chapter)
        target = os.path.join(dest, "chapters", os.path.basename(folder))
        os.makedirs(target, exist_ok=True)
        for n in names:
            shutil.copy(os.path.join(folder, n), target)
    os.chmod(dest, 0o755)


def grade(submission, out, build_dir, chapters, extra=()):
    start = time.monotonic()
    cmd = [sys.executable, GRADE, submission, "--out", out, "--build-dir", build_dir, "--chapters", chapters,
           *TEST_LIMITS, *extra]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=GRADING_TIME_LIMIT)
    seconds = time.monotonic() - start
    print(result.stdout[-3000:])
    print(result.stderr[-3000:], file=sys.stderr)
    check(result.returncode == 0, f"grade exited with {result.returncode}")
    data = load_results(out)
    print(f"graded {submission} in {seconds:.1f} s: {data['score'] if data else '-'}")
    return data


def load_results(path):
    """results.json must exist, be valid JSON, and follow Gradescope's schema."""
    if not check(os.path.isfile(path), f"{path} was not written"):
        return None
    try:
        with open(path) as f:
            data = json.load(f)
    except ValueError as e:
        check(False, f"{path} is not valid JSON: {e}")
        return None
    for key, kind in (("score", (int, float)), ("execution_time", (int, float)), ("output", str),
                      ("stdout_visibility", str), ("tests", list)):
        check(isinstance(data.get(key), kind), f"results.json: '{key}' missing or of the wrong type")
    for t in data.get("tests", []):
        for key, kind in (("name", str), ("number", str), ("score", (int, float)), ("max_score", (int, float)),
                          ("status", str), ("output", str), ("tags", list), ("visibility", str)):
            check(isinstance(t.get(key), kind), f"results.json test {t.get('name')}: '{key}' missing or wrong")
        check(t.get("status") in ("passed", "failed"), f"{t.get('name')}: status {t.get('status')}")
        check(0 <= t.get("score", 0) <= t.get("max_score", 0), f"{t.get('name')}: score outside [0, max]")
    check(abs(sum(t["score"] for t in data["tests"]) - data["score"]) < 1e-9, "score is not the sum of the tests")
    return data


def statuses(data):
    return {t["name"]: t["status"] for t in data["tests"]}


def baseline_path(work):
    return os.path.join(work, "baseline.json")


def run_baseline(args):
    """The solutions score full marks; the stubs score zero and say why, politely."""
    # Preparing the tree first, with its own time limit: on a busy machine the first build takes minutes.
    prepared = subprocess.run([sys.executable, GRADE, "--prepare-only", "--build-dir", args.build_dir,
                               "--chapters", "01,02"], capture_output=True, text=True, timeout=PREPARE_TIME_LIMIT)
    print(prepared.stdout[-2000:], prepared.stderr[-3000:])
    check(prepared.returncode == 0, f"preparing the grading tree failed ({prepared.returncode})")
    check("build steps done" in prepared.stderr or "preparing" not in prepared.stderr,
          "preparing the tree shows no progress (build steps done of total)")
    sub = os.path.join(args.work, "solutions")
    make_submission(sub, solutions=["01", "02"])
    data = grade(sub, os.path.join(args.work, "solutions-results", "results.json"), args.build_dir, "01,02")
    if data:
        total = sum(t["max_score"] for t in data["tests"])
        check(total > 0 and data["score"] == total, f"the solutions scored {data['score']} of {total}")
        for t in data["tests"]:
            check(t["status"] == "passed", f"solution failed {t['name']}: {t['output'][:300]}")
        shutil.copy(os.path.join(args.work, "solutions-results", "results.json"), baseline_path(args.work))

    stub = os.path.join(args.work, "stubs")
    make_submission(stub, sources=[os.path.join(REPO, "chapters", "01-unit-sphere", "unit_sphere.cpp")])
    data = grade(stub, os.path.join(args.work, "stub-results", "results.json"), args.build_dir, "01")
    if data:
        check(data["score"] == 0, f"the stubs scored {data['score']}")
        for t in data["tests"]:
            polite = "not implemented yet" in t["output"]
            check(polite, f"stub test {t['name']} does not say 'not implemented yet': {t['output'][:300]}")
            if t["tags"][1] == "hidden":
                check("logged" not in t["output"] and "values:" not in t["output"],
                      f"hidden test {t['name']} shows more than the concept: {t['output'][:300]}")


def run_fixture(args):
    name = args.name
    folder = os.path.join(FIXTURES, name)
    with open(os.path.join(folder, "expect.json")) as f:
        expect = json.load(f)
    root = os.geteuid() == 0
    sub = os.path.join(args.work, "fixtures", name)
    sources = [p for p in glob.glob(os.path.join(folder, "*")) if not p.endswith("expect.json")]
    make_submission(sub, sources=sources, solutions=expect.get("add_solutions", []))
    out = os.path.join(args.work, "fixtures-results", name, "results.json")
    start = time.monotonic()
    data = grade(sub, out, args.build_dir, expect["chapters"])
    seconds = time.monotonic() - start
    if data is None:
        return
    if expect.get("root_only") and not root:
        print(f"NOTE: '{name}' needs user isolation, which is off when the grader is not run as root: "
              "only the validity of results.json was checked.")
        return
    with open(baseline_path(args.work)) as f:
        base = statuses(json.load(f))
    mine = statuses(data)
    graded = [n for n in base if n.split(".", 1)[0] in {f"ch{c}" for c in expect["chapters"].split(",")}]
    for test in graded:
        check(test in mine, f"{name}: test {test} is missing from the results")
        if test not in mine:
            continue
        if any(fnmatch.fnmatchcase(test, p) for p in expect["must_fail"]):
            check(mine[test] == "failed", f"{name}: {test} passed, but this submission must fail it")
        elif not any(fnmatch.fnmatchcase(test, p) for p in expect["may_differ"]):
            check(mine[test] == base[test], f"{name}: {test} is {mine[test]}, but {base[test]} for the solutions")
        check(not (mine[test] == "passed" and base[test] == "failed"), f"{name}: false pass of {test}")
    for chapter, words in expect.get("compilation", {}).items():
        entry = [t for t in data["tests"] if t["name"] == f"{chapter} compilation"]
        check(entry and words in entry[0]["output"] and entry[0]["visibility"] == "visible",
              f"{name}: no visible '{chapter} compilation' entry saying '{words}'")
    forbidden = expect.get("forbidden_in_results")
    if forbidden:
        with open(out) as f:
            check(forbidden not in f.read(), f"{name}: '{forbidden}' appears in the results")
    hidden_forbidden = expect.get("forbidden_in_hidden")
    if hidden_forbidden:
        for t in data["tests"]:
            if t["tags"][1] == "hidden":
                check(hidden_forbidden not in t["output"], f"{name}: hidden test {t['name']} shows '{hidden_forbidden}'")
        check(any(hidden_forbidden in t["output"] for t in data["tests"] if t["tags"][1] == "public"),
              f"{name}: the public feedback should still show the exception's own message")
    print(f"{name}: graded in {seconds:.1f} s, score {data['score']}")


def run_batch(args):
    folder = os.path.join(args.work, "batch-in")
    shutil.rmtree(folder, ignore_errors=True)
    make_submission(os.path.join(folder, "alice"), solutions=["01"])
    make_submission(os.path.join(folder, "bob"), sources=[os.path.join(FIXTURES, "segfault", "unit_sphere.cpp")])
    make_submission(os.path.join(folder, "carol"))
    out = os.path.join(args.work, "batch-out")
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, os.path.join(REPO, "tools", "grader", "grade-batch"), folder, "--out", out,
           "--build-dir", args.build_dir, "--chapters", "01", "--jobs", "2", *TEST_LIMITS]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=GRADING_TIME_LIMIT)
    print(result.stdout, result.stderr)
    check(result.returncode == 0, f"grade-batch exited with {result.returncode}")
    scores = {}
    for who in ("alice", "bob", "carol"):
        data = load_results(os.path.join(out, who, "results.json"))
        scores[who] = data["score"] if data else None
    with open(os.path.join(out, "scores.csv")) as f:
        rows = f.read().splitlines()
    check(rows[0].startswith("submission,score,max_score,ch01") and len(rows) == 4, f"scores.csv: {rows}")
    check(scores["alice"] and scores["carol"] == 0 and 0 < scores["bob"] < scores["alice"],
          f"implausible batch scores {scores}")


def run_kit(args):
    """In a student kit the grading tree is built from the kit itself: a chapter whose file does not
    compile must cost that chapter only. A kit-like copy of the repository (no solutions,
    hidden tests or fixtures) with the solutions of 01, 02 and 04 and a broken 03 is previewed."""
    kit = os.path.join(args.work, "kit")
    shutil.rmtree(kit, ignore_errors=True)
    private = {"solutions", "tests/hidden", "tests/fixtures", ".git"}

    def ignore(folder, names):
        rel = os.path.relpath(folder, REPO)
        return [n for n in names if os.path.normpath(os.path.join(rel, n)) in private or
                (rel == "." and n.startswith("build")) or n == "__pycache__"]

    shutil.copytree(REPO, kit, ignore=ignore)
    for chapter in ("01", "02", "03", "04"):
        folder, names = solution_files(chapter)
        for n in names:
            shutil.copy(os.path.join(folder, n), os.path.join(kit, "chapters", os.path.basename(folder), n))
    broken = glob.glob(os.path.join(kit, "chapters", "03-*", "scene_loop.cpp"))[0]
    with open(broken, "a") as f:
        f.write("\nthis line is not C++\n")
    out = os.path.join(kit, "preview.json")
    cmd = [sys.executable, os.path.join(kit, "tools", "grader", "grade"), kit, "--out", out, "--chapters",
           "01,02,03,04", "--build-dir", os.path.join(args.work, "kit-tree"), *TEST_LIMITS]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=PREPARE_TIME_LIMIT)
    print(result.stdout[-4000:], result.stderr[-3000:])
    check(result.returncode == 0, f"grading the kit exited with {result.returncode}")
    data = load_results(out)
    if not data:
        return
    for t in data["tests"]:
        chapter, kind = t["tags"]
        if chapter in ("ch01", "ch02") or (chapter == "ch04" and kind == "public"):
            check(t["status"] == "passed", f"kit: {t['name']} failed although its chapter is correct: {t['output'][:300]}")
        elif chapter == "ch03":
            check(t["status"] == "failed", f"kit: {t['name']} passed although chapter 03 does not compile")
    entry = [t for t in data["tests"] if t["name"] == "ch03 compilation"]
    check(entry and "error" in entry[0]["output"], "kit: no 'ch03 compilation' entry with the compiler's message")
    check("does not build" not in data["output"], "kit: the whole preview failed")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("what", choices=["baseline", "fixture", "batch", "kit"])
    p.add_argument("name", nargs="?")
    p.add_argument("--work", required=True)
    p.add_argument("--build-dir", required=True)
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    {"baseline": run_baseline, "fixture": run_fixture, "batch": run_batch, "kit": run_kit}[args.what](args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
