#!/usr/bin/env python3
"""Tests of the exporters (ctest label 'grader'; see tests/tools/CMakeLists.txt).

  export_tests.py kit --work DIR
      exports the student kit, checks it holds nothing private (and that the
      leak check does catch a pasted solution or a hidden test's name), then
      grades the kit with its own copy of the grader: the kit configures and
      builds on its own, and every public test fails politely.
  export_tests.py gradescope --work DIR --build-dir TREE
      writes the Gradescope zip, unpacks it into a folder laid out like
      /autograder/, runs setup.sh and run_autograder there on the solutions
      and on the stubs, and checks results/results.json.
"""

import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(REPO, "tools", "export"))
import rtexport  # noqa: E402

failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)
    return ok


def run(cmd, **kwargs):
    print("$", " ".join(cmd))
    result = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    print(result.stdout[-4000:])
    print(result.stderr[-4000:], file=sys.stderr)
    return result


def test_kit(args):
    kit = os.path.join(args.work, "kit")
    shutil.rmtree(kit, ignore_errors=True)
    result = run([sys.executable, os.path.join(REPO, "tools", "export", "kit"), kit])
    check(result.returncode == 0, "tools/export/kit failed")

    # Nothing private, by path or by content.
    for rel in ("solutions", "tests/hidden", "tests/fixtures", "tests/tools", "tools/export"):
        check(not os.path.exists(os.path.join(kit, rel)), f"the kit contains {rel}")
    check(rtexport.leak_check(kit) == [], "the leak check finds something in the exported kit")
    # The leak check must catch a pasted solution and a hidden test's name.
    for solution in sorted(glob.glob(os.path.join(REPO, "solutions", "*", "*.cpp")))[:2]:
        spoiled = os.path.join(args.work, "kit-spoiled")
        shutil.rmtree(spoiled, ignore_errors=True)
        shutil.copytree(kit, spoiled)
        with open(solution) as f_in, open(os.path.join(spoiled, "common", "math.hpp"), "a") as f_out:
            f_out.write(f_in.read())
        check(rtexport.leak_check(spoiled) != [], f"the leak check misses {solution} pasted into common/")
    for hidden in sorted(glob.glob(os.path.join(REPO, "tests", "hidden", "*.cpp")))[:1]:
        spoiled = os.path.join(args.work, "kit-spoiled")
        shutil.rmtree(spoiled, ignore_errors=True)
        shutil.copytree(kit, spoiled)
        shutil.copy(hidden, os.path.join(spoiled, "tests", "public", "extra_test.cpp"))
        check(rtexport.leak_check(spoiled) != [], f"the leak check misses a copy of {hidden}")
    shutil.rmtree(os.path.join(args.work, "kit-spoiled"), ignore_errors=True)

    # The kit builds on its own and previews its score with its own grader.
    preview = os.path.join(args.work, "kit-preview", "results.json")
    result = run([sys.executable, os.path.join(kit, "tools", "grader", "grade"), kit, "--out", preview,
                  "--chapters", "01", "--timeout", "5", "--render-timeout", "20"], timeout=900)
    check(result.returncode == 0, "the kit's grader failed")
    if check(os.path.isfile(preview), "no preview results"):
        with open(preview) as f:
            data = json.load(f)
        check(data["score"] == 0, f"the untouched kit scored {data['score']}")
        check(all(".hidden." not in t["name"] for t in data["tests"]), "the kit graded hidden tests")
        public = [t for t in data["tests"] if t["tags"][1] == "public"]
        check(len(public) > 0, "the kit has no public test")
        for t in public + [t for t in data["tests"] if t["tags"][1] == "render"]:
            check("not implemented yet" in t["output"], f"{t['name']} does not fail politely: {t['output'][:200]}")


def test_gradescope(args):
    zip_path = os.path.join(args.work, "gradescope", "autograder.zip")
    result = run([sys.executable, os.path.join(REPO, "tools", "export", "gradescope"), zip_path])
    check(result.returncode == 0, "tools/export/gradescope failed")
    root = os.path.join(args.work, "gradescope", "autograder")
    shutil.rmtree(root, ignore_errors=True)
    source = os.path.join(root, "source")
    os.makedirs(source)
    rtexport.unpack_bundle(zip_path, source)
    for name in ("setup.sh", "run_autograder", "tools/grader/grade", "solutions", "tests/hidden"):
        check(os.path.exists(os.path.join(source, name)), f"the bundle lacks {name}")
    shutil.copy(os.path.join(source, "run_autograder"), os.path.join(root, "run_autograder"))
    env = dict(os.environ, AUTOGRADER_ROOT=root, RT_SKIP_APT="1", RT_GRADER_BUILD_DIR=args.build_dir,
               RT_GRADER_CHAPTERS="01")
    result = run(["bash", os.path.join(source, "setup.sh")], cwd=source, env=env, timeout=900)
    check(result.returncode == 0, "setup.sh failed")

    cases = {"solutions": os.path.join(REPO, "solutions", "01-unit-sphere", "unit_sphere.cpp"),
             "stubs": os.path.join(REPO, "chapters", "01-unit-sphere", "unit_sphere.cpp")}
    for who, exercise in cases.items():
        submission = os.path.join(root, "submission")
        shutil.rmtree(submission, ignore_errors=True)
        os.makedirs(submission)
        shutil.copy(exercise, submission)          # a flat upload of the exercise file
        results = os.path.join(root, "results", "results.json")
        if os.path.exists(results):
            os.remove(results)
        result = run([os.path.join(root, "run_autograder")], cwd=root, env=env, timeout=900)
        check(result.returncode == 0, f"run_autograder failed on the {who}")
        if not check(os.path.isfile(results), f"no results.json for the {who}"):
            continue
        with open(results) as f:
            data = json.load(f)
        total = sum(t["max_score"] for t in data["tests"])
        if who == "solutions":
            check(total > 0 and data["score"] == total, f"the solutions scored {data['score']} of {total}")
        else:
            check(data["score"] == 0, f"the stubs scored {data['score']}")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("what", choices=["kit", "gradescope"])
    p.add_argument("--work", required=True)
    p.add_argument("--build-dir")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    {"kit": test_kit, "gradescope": test_gradescope}[args.what](args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
