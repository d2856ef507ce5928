#!/usr/bin/env python3
"""Tests of the exporters (ctest label 'grader'; see tests/tools/CMakeLists.txt).

  export_tests.py kit --work DIR
      exports the student kit and checks it: every file is on the list of
      what may ship, nothing private by path or content (and the checks do
      catch a pasted solution, a hidden test's name, the renderer's fast path,
      a helper next to an exercise), only the student preset, no README names
      a path the kit lacks; then runs every command of every README of the
      kit, in the kit (builds with the student preset; programs and tests stop
      politely with the stubs; the score preview is 0), builds the rest, and
      checks semantically that nothing computes an answer: every chapter
      program exits with status 3, no public test case passes, and no other
      program draws a reference picture.
  export_tests.py gradescope --work DIR --build-dir TREE
      writes the Gradescope zip, unpacks it into a folder laid out like
      /autograder/, runs setup.sh and run_autograder there on the solutions
      and on the stubs, and checks results/results.json.
"""

import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import time

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
    static_checks(kit, args.work)
    env = kit_environment()
    # One build of the kit (build/student) serves every check below: the
    # READMEs' commands build their chapters (and preview the score with the
    # kit's own grader), then the rest is built.
    readme_commands(kit, env)
    result = run(["cmake", "--build", "--preset", "student"], cwd=kit, env=env, timeout=1800)
    if check(result.returncode == 0, "the kit does not build with the student preset"):
        readme_paths(kit, after_build=True)
        semantic_check(kit, args.work)


def kit_environment():
    """The shared compiler cache when there is one (the kit's commands stay as written)."""
    env = dict(os.environ)
    if shutil.which("ccache") and "CMAKE_CXX_COMPILER_LAUNCHER" not in env:
        env["CMAKE_CXX_COMPILER_LAUNCHER"] = "ccache"
    return env


def static_checks(kit, work):
    # Nothing private or instructor-only, by path or by content.
    for rel in ("solutions", "tests/hidden", "tests/fixtures", "tests/tools", "tests/fuzz", "tests/numerics",
                "tools/export", "tools/render", "tools/bench", "tools/study", "tools/diagrams", "tools/test-all",
                "tools/render-all",
                "tests/scenes/scene_plan_test.cpp"):
        check(not os.path.exists(os.path.join(kit, rel)), f"the kit contains {rel}")
    check(rtexport.ship_check(kit) == [], f"files of the kit not on the list: {rtexport.ship_check(kit)}")
    check(rtexport.leak_check(kit) == [], "the leak check finds something in the exported kit")
    with open(os.path.join(kit, "CMakePresets.json")) as f:
        presets = json.load(f)
    for kind in ("configurePresets", "buildPresets", "testPresets"):
        visible = [p["name"] for p in presets[kind] if not p.get("hidden")]
        check(visible == ["student"], f"the kit's {kind} are {visible}, not only 'student'")
    with open(os.path.join(kit, ".gitignore")) as f:
        ignored = f.read().split()
    for name in ("build/", "out/", "renders/", "preview.json"):
        check(name in ignored, f"the kit's .gitignore does not ignore {name}")
    readme_paths(kit, after_build=False)

    def spoiled_copy():
        spoiled = os.path.join(work, "kit-spoiled")
        shutil.rmtree(spoiled, ignore_errors=True)
        shutil.copytree(kit, spoiled)
        return spoiled

    # The leak check must catch a pasted solution and a hidden test's name.
    for solution in sorted(glob.glob(os.path.join(REPO, "solutions", "*", "*.cpp")))[:2]:
        spoiled = spoiled_copy()
        with open(solution) as f_in, open(os.path.join(spoiled, "common", "math.hpp"), "a") as f_out:
            f_out.write(f_in.read())
        check(rtexport.leak_check(spoiled) != [], f"the leak check misses {solution} pasted into common/")
    for hidden in sorted(glob.glob(os.path.join(REPO, "tests", "hidden", "*.cpp")))[:1]:
        spoiled = spoiled_copy()
        shutil.copy(hidden, os.path.join(spoiled, "tests", "public", "extra_test.cpp"))
        check(rtexport.leak_check(spoiled) != [], f"the leak check misses a copy of {hidden}")
    # The list of what may ship names the file that is not on it: the
    # renderer's fast path, or a helper next to a chapter's exercise.
    chapter = sorted(glob.glob(os.path.join(kit, "chapters", "[0-9][0-9]-*")))[-1]
    extras = [os.path.join("tools", "render", "fast_path.cpp"),
              os.path.relpath(os.path.join(chapter, "answer_helper.cpp"), kit)]
    for rel in extras:
        spoiled = spoiled_copy()
        os.makedirs(os.path.dirname(os.path.join(spoiled, rel)), exist_ok=True)
        with open(os.path.join(spoiled, rel), "w") as f:
            f.write("// anything\n")
        problems = rtexport.ship_check(spoiled)
        check(any(rel in p for p in problems), f"the ship check misses {rel}: {problems}")
    shutil.rmtree(os.path.join(work, "kit-spoiled"), ignore_errors=True)


# --- The READMEs of the kit ---------------------------------------------------------------------

KIT_TOP_FOLDERS = ("chapters", "common", "tests", "tools", "scenes", "cmake", "solutions", "build")


def kit_readmes(kit):
    found = []
    for dirpath, dirnames, filenames in os.walk(kit):
        dirnames[:] = sorted(d for d in dirnames if not (dirpath == kit and d in ("build", "out", "renders")))
        found += [os.path.join(dirpath, n) for n in sorted(filenames) if n.endswith(".md")]
    return found


def readme_paths(kit, after_build):
    """Every repository path a kit README names (in `code` or as a link) exists in the kit;
    build/ paths are checked once the kit is built."""
    for readme in kit_readmes(kit):
        rel_readme = os.path.relpath(readme, kit)
        with open(readme) as f:
            text = f.read()
        if not after_build:
            for marker in rtexport.INSTRUCTOR_ONLY:
                check(marker not in text, f"{rel_readme} still holds the marker {marker}")
            for target in re.findall(r"\]\(([^)\s#]+)(?:#[^)]*)?\)", text):
                if "://" in target or target.startswith("mailto:"):
                    continue
                path = os.path.normpath(os.path.join(os.path.dirname(readme), target))
                check(os.path.exists(path), f"{rel_readme} links to {target}, which is not in the kit")
        names = set()
        for span in re.findall(r"`([^`\n]+)`", re.sub(r"```.*?```", "", text, flags=re.S)):
            for word in re.findall(r"(?<![\w./-])((?:%s)/[\w./-]*)" % "|".join(KIT_TOP_FOLDERS), span):
                names.add(word.rstrip("."))
        for name in sorted(names):
            if re.search(r"NN|XX", name) or (name.startswith("build/") != after_build):
                continue
            check(os.path.exists(os.path.join(kit, name)), f"{rel_readme} names {name}, which is not in the kit")


def sh_commands(readme):
    """The command lines of the fenced sh blocks of a README (continuations joined)."""
    with open(readme) as f:
        text = f.read()
    commands = []
    for block in re.findall(r"^```(?:sh|bash|shell)\s*\n(.*?)^```", text, flags=re.S | re.M):
        pending = ""
        for line in block.replace("\\\n", " ").splitlines():
            if not pending and (not line.strip() or line.strip().startswith("#")):
                continue
            pending = pending + "\n" + line if pending else line.strip()
            # A quoted argument or a loop may span lines: bash -n says when the command is complete.
            if subprocess.run(["bash", "-n", "-c", pending], capture_output=True).returncode != 0:
                continue
            commands.append(pending)
            pending = ""
        if pending:
            commands.append(pending)    # incomplete: bash will say so
    return commands


NOT_FOUND = re.compile(r"not found|No such file|No such preset|[Uu]nknown preset|No such build preset|"
                       r"does not exist|unknown target|No rule to make target", re.I)


def readme_commands(kit, env):
    """Runs every command of every kit README, in the kit, in order: each must work, or stop
    politely because the chapters are still stubs."""
    ran = 0
    for readme in kit_readmes(kit):
        rel_readme = os.path.relpath(readme, kit)
        for command in sh_commands(readme):
            where = f"{rel_readme}: `{command}`"
            start = time.monotonic()
            result = subprocess.run(["bash", "-c", command], cwd=kit, env=env, capture_output=True, text=True,
                                    timeout=1800)
            ran += 1
            output = result.stdout + result.stderr
            print(f"$ {command}   [{rel_readme}] -> exit {result.returncode} ({time.monotonic() - start:.0f} s)")
            if not check(not NOT_FOUND.search(output), f"{where} names something the kit lacks:\n{output[-1500:]}"):
                continue
            words = command.split()
            polite = "not implemented yet" in output
            if words[0] == "ctest":
                # The stubs fail every public test, politely.
                check(result.returncode == 8 and polite and re.search(r"(^|\s)0% tests passed", output),
                      f"{where}: expected every test to fail with 'not implemented yet' "
                      f"(exit {result.returncode}):\n{output[-1500:]}")
            elif os.path.basename(words[0]) == "imgcmp":
                check(result.returncode in (0, 1) and "difference image" in output,
                      f"{where}: exit {result.returncode}:\n{output[-1500:]}")
            elif words[0].startswith("build/"):
                check(result.returncode == 3 and polite,
                      f"{where}: expected the stub's exit status 3, 'not implemented yet', got exit "
                      f"{result.returncode}:\n{output[-1500:]}")
            else:
                check(result.returncode == 0, f"{where} failed (exit {result.returncode}):\n{output[-1500:]}")
                if words[0].endswith("grader/grade") and "--out" in words:
                    check_preview(os.path.join(kit, words[words.index("--out") + 1]), where)
    check(ran > 0, "no command found in the kit's READMEs")


# --- Semantic leak check: nothing in the kit computes an answer --------------------------------

def _chapters(build):
    chapters = []
    for path in sorted(glob.glob(os.path.join(build, "rt_chapters", "ch*.json"))):
        with open(path) as f:
            chapters.append(json.load(f))
    return chapters


def semantic_check(kit, work):
    """With every chapter a stub: every chapter program stops with status 3, no public test
    passes, and no other program of the kit draws a picture that matches a reference."""
    build = os.path.join(kit, "build", "student")
    chapters = _chapters(build)
    check(len(chapters) >= 7, f"the kit's build describes {len(chapters)} chapters")
    out = os.path.join(work, "kit-semantic")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    references = sorted(glob.glob(os.path.join(kit, "chapters", "*", "*.png")))
    imgcmp = os.path.join(build, "bin", "imgcmp")
    for ch in chapters:
        png = os.path.join(out, ch["id"] + ".png")
        r = subprocess.run([ch["program"], "--out", png], capture_output=True, text=True, timeout=120)
        check(r.returncode == 3 and "not implemented yet" in r.stdout + r.stderr,
              f"{ch['id']}'s program with the stubs: exit {r.returncode}, not 3:\n{(r.stdout + r.stderr)[-800:]}")
        r = subprocess.run([ch["public_tests"]], capture_output=True, text=True, timeout=300)
        m = re.search(r"test cases:\s*(\d+)\s*\|\s*(\d+) passed", r.stdout)
        if check(m is not None, f"{ch['id']}'s public tests printed no summary:\n{r.stdout[-800:]}"):
            check(int(m.group(1)) > 0 and m.group(2) == "0",
                  f"{ch['id']}: {m.group(2)} of {m.group(1)} public test cases pass with the stubs")
    programs = {os.path.realpath(ch["program"]) for ch in chapters}
    others = [p for p in sorted(glob.glob(os.path.join(build, "bin", "*")))
              if os.access(p, os.X_OK) and os.path.realpath(p) not in programs]
    check(any(os.path.basename(p) == "imgcmp" for p in others), "the kit builds no imgcmp")
    problems = pictures_drawn(others, kit, out, imgcmp, references)
    check(problems == [], "programs of the kit draw a reference picture with the stubs:\n" + "\n".join(problems))
    print(f"semantic check: {len(chapters)} chapter programs and public tests, and "
          f"{', '.join(os.path.basename(p) for p in others)} on {len(references)} reference pictures")
    # The check itself must catch a program that draws a chapter's picture.
    fake = os.path.join(out, "rt-fake-render")
    with open(fake, "w") as f:
        f.write("#!/bin/sh\n# draws chapter 03's picture whatever it is asked\n"
                'while [ $# -gt 0 ]; do [ "$1" = --out ] && cp "%s" "$2"; shift; done\n'
                % os.path.join(kit, "chapters", "03-scene-loop", "reference.png"))
    os.chmod(fake, 0o755)
    check(pictures_drawn([fake], kit, out, imgcmp, references) != [], "the semantic check misses a fake renderer")


def pictures_drawn(programs, kit, out, imgcmp, references):
    """Runs each program the ways a renderer is run (scene file as argument or with --scene,
    or nothing) and compares whatever picture it writes with every reference picture."""
    scenes = sorted(glob.glob(os.path.join(kit, "scenes", "*.json")))
    problems = []
    for program in programs:
        name = os.path.basename(program)
        ways = [[]] + [[scene] for scene in scenes] + [["--scene", scene] for scene in scenes]
        for i, way in enumerate(ways):
            png = os.path.join(out, f"{name}-{i}.png")
            try:
                subprocess.run([program] + way + ["--out", png], capture_output=True, timeout=60, cwd=out)
            except subprocess.TimeoutExpired:
                problems.append(f"{name} {' '.join(way)}: still running after 60 s")
                continue
            if not os.path.exists(png):
                continue
            for reference in references:
                r = subprocess.run([imgcmp, png, reference], capture_output=True, text=True)
                if r.returncode == 0:
                    problems.append(f"{name} {' '.join(way)} draws {os.path.relpath(reference, kit)}")
    return problems


def check_preview(path, where):
    """A preview of the untouched kit: zero points, only public tests, every one failing politely."""
    if not check(os.path.isfile(path), f"{where} wrote no {path}"):
        return
    with open(path) as f:
        data = json.load(f)
    check(data["score"] == 0, f"{where}: the untouched kit scored {data['score']}")
    check(all(".hidden." not in t["name"] for t in data["tests"]), f"{where}: the kit graded hidden tests")
    def kind(t):
        tags = t.get("tags") or []
        return tags[1] if len(tags) > 1 else None

    public = [t for t in data["tests"] if kind(t) == "public"]
    check(len(public) > 0, f"{where}: the kit has no public test")
    for t in public + [t for t in data["tests"] if kind(t) == "render"]:
        check("not implemented yet" in t["output"], f"{where}: {t['name']} does not fail politely: {t['output'][:200]}")


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
    args.work = os.path.abspath(args.work)
    os.makedirs(args.work, exist_ok=True)
    {"kit": test_kit, "gradescope": test_gradescope}[args.what](args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
