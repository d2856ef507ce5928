#!/usr/bin/env python3
"""Tests of the exporters (ctest label 'grader'; see tests/tools/CMakeLists.txt).

  export_tests.py --work DIR KitFiles KitBuilt
      KitFiles exports the student kit and checks its files: every file is on
      the list of what may ship, nothing private by path or content (and the
      checks do catch a pasted solution, a hidden test's name, the renderer's
      fast path, a helper next to an exercise), only the student preset, no
      README names a path the kit lacks. KitBuilt then runs every command of
      every README of the kit, in the kit (builds with the student preset;
      programs and tests stop politely with the stubs; the score preview is 0,
      which prepares the kit's grading tree in build/grader), builds the rest,
      and checks semantically that nothing computes an answer: every chapter
      program exits with status 3, no public test case passes, and no other
      program draws a reference picture. The kit stays in DIR/kit for
      grader.kit-compile-error.
  export_tests.py --work DIR --build-dir TREE Gradescope
      writes the Gradescope zip, unpacks it into a folder laid out like
      /autograder/, runs setup.sh and run_autograder there on the solutions
      and on the stubs, and checks results/results.json.
"""

import glob
import json
import os
import re
import shutil
import subprocess
import sys
import time

from tooltest import REPO, ToolTest, compiler_cache, config, main, total_score

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(REPO, "tools", "export"))
import rtexport  # noqa: E402


def run(cmd, **kwargs):
    print("$", " ".join(cmd))
    result = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    print(result.stdout[-4000:])
    print(result.stderr[-4000:], file=sys.stderr)
    return result


_exported = {}


def exported_kit():
    """(the kit's folder, the exporter's run): exported once per run of this file, shared by its classes."""
    if not _exported:
        kit = os.path.join(config.work, "kit")
        shutil.rmtree(kit, ignore_errors=True)
        _exported["kit"] = kit, run([sys.executable, os.path.join(REPO, "tools", "export", "kit"), kit])
    return _exported["kit"]


class KitTest(ToolTest):
    @classmethod
    def setUpClass(cls):
        cls.kit, cls.export = exported_kit()

    def setUp(self):
        self.assertEqual(self.export.returncode, 0, "tools/export/kit failed")


class KitFiles(KitTest):
    """The exported kit's files, before anything is built in it."""

    def test_nothing_private_or_instructor_only(self):
        for rel in ("solutions", "tests/hidden", "tests/fixtures", "tests/tools", "tests/fuzz", "tests/numerics",
                    "tools/export", "tools/render", "tools/bench", "tools/study", "tools/diagrams", "tools/test-all",
                    "tools/render-all", "tests/scenes/scene_plan_test.cpp"):
            self.assertFalse(os.path.exists(os.path.join(self.kit, rel)), f"the kit contains {rel}")

    def test_every_file_is_on_the_list_of_what_may_ship(self):
        self.assertEqual(rtexport.ship_check(self.kit), [])

    def test_the_leak_check_finds_nothing(self):
        self.assertEqual(rtexport.leak_check(self.kit), [])

    def test_only_the_student_preset(self):
        with open(os.path.join(self.kit, "CMakePresets.json")) as f:
            presets = json.load(f)
        for kind in ("configurePresets", "buildPresets", "testPresets"):
            visible = [p["name"] for p in presets[kind] if not p.get("hidden")]
            self.assertEqual(visible, ["student"], f"the kit's {kind}")

    def test_gitignore_keeps_the_students_outputs_out(self):
        with open(os.path.join(self.kit, ".gitignore")) as f:
            ignored = f.read().split()
        for name in ("build/", "out/", "renders/", "preview.json"):
            self.assertIn(name, ignored, "the kit's .gitignore")

    def test_readmes_name_only_what_the_kit_holds(self):
        self.assertEqual(readme_path_problems(self.kit, after_build=False), [])

    def spoiled_copy(self):
        spoiled = os.path.join(config.work, "kit-spoiled")
        shutil.rmtree(spoiled, ignore_errors=True)
        shutil.copytree(self.kit, spoiled, ignore=lambda folder, names: [
            n for n in names if folder == self.kit and n in ("build", "out", "renders")])
        self.addCleanup(shutil.rmtree, spoiled, True)
        return spoiled

    def test_the_leak_check_catches_a_pasted_solution(self):
        for solution in sorted(glob.glob(os.path.join(REPO, "solutions", "*", "*.cpp")))[:2]:
            spoiled = self.spoiled_copy()
            with open(solution) as f_in, open(os.path.join(spoiled, "common", "math.hpp"), "a") as f_out:
                f_out.write(f_in.read())
            self.assertNotEqual(rtexport.leak_check(spoiled), [], f"the leak check misses {solution} pasted into common/")

    def test_the_leak_check_catches_a_copied_hidden_test(self):
        hidden = sorted(glob.glob(os.path.join(REPO, "tests", "hidden", "*.cpp")))[0]
        spoiled = self.spoiled_copy()
        shutil.copy(hidden, os.path.join(spoiled, "tests", "public", "extra_test.cpp"))
        self.assertNotEqual(rtexport.leak_check(spoiled), [], f"the leak check misses a copy of {hidden}")

    def test_the_answer_check_finds_nothing(self):
        self.assertEqual(rtexport.answer_check(self.kit), [])

    def test_the_answer_check_catches_an_answer_written_again(self):
        # The two kinds once shipped: a public test helper whose brute force was chapter 03's loop,
        # and a study program whose offset rule was shadow_ray_origin's formula, with other names.
        brute_force = """
template <class T>
std::optional<hit_record<T>> brute_force(const objects<T>& scene, const ray<T>& r, interval<T> range) {
    std::optional<hit_record<T>> best;
    for (int i = 0; i < scene.count(); ++i)
        if (auto hit = scene.test(i, r, range)) {
            hit->object = i;
            range.max = hit->t;
            best = hit;
        }
    return best;
}
"""
        offset_rule = """
template <class T>
vec3<T> apply(const vec3<T>& p, const vec3<T>& unit_normal, T amount) {
    const T magnitude = std::max({T(1), std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return p + amount * std::numeric_limits<T>::epsilon() * magnitude * unit_normal;
}
"""
        for rel, code in (("tests/public/ch08_scenes.hpp", brute_force), ("chapters/06-shading/acne_study.cpp", offset_rule)):
            spoiled = self.spoiled_copy()
            with open(os.path.join(spoiled, rel), "a") as f:
                f.write(code)
            problems = rtexport.answer_check(spoiled)
            self.assertTrue(any(p.startswith(rel) for p in problems), f"the answer check misses an answer in {rel}: {problems}")

    def test_the_ship_check_names_a_file_not_on_the_list(self):
        # The renderer's fast path, or a helper next to a chapter's exercise.
        chapter = sorted(glob.glob(os.path.join(self.kit, "chapters", "[0-9][0-9]-*")))[-1]
        for rel in (os.path.join("tools", "render", "fast_path.cpp"),
                    os.path.relpath(os.path.join(chapter, "answer_helper.cpp"), self.kit)):
            spoiled = self.spoiled_copy()
            os.makedirs(os.path.dirname(os.path.join(spoiled, rel)), exist_ok=True)
            with open(os.path.join(spoiled, rel), "w") as f:
                f.write("// anything\n")
            problems = rtexport.ship_check(spoiled)
            self.assertTrue(any(rel in p for p in problems), f"the ship check misses {rel}: {problems}")


class KitFullMarks(ToolTest):
    """A kit whose exercise files are all correct scores full marks in its own preview (issue 19): a kit
    exported afresh, the solutions' exercise files copied into its chapters, then the preview exactly as
    the kit's README says, once for every chapter together (which prepares the kit's grading tree) and
    then for each chapter alone (the same tree, reused). Chapter 06's and 08's tests call earlier
    chapters (02's sphere, 05's triangle), which in a kit come from the student's own files."""

    @classmethod
    def setUpClass(cls):
        cls.kit = os.path.join(config.work, "kit-correct")
        shutil.rmtree(cls.kit, ignore_errors=True)
        cls.export = run([sys.executable, os.path.join(REPO, "tools", "export", "kit"), cls.kit])
        cls.previews = {}
        if cls.export.returncode != 0:
            return
        for folder in sorted(glob.glob(os.path.join(REPO, "solutions", "[0-9][0-9]-*"))):
            for exercise in glob.glob(os.path.join(folder, "*.cpp")):
                shutil.copy(exercise, os.path.join(cls.kit, "chapters", os.path.basename(folder)))
        with open(os.path.join(cls.kit, "tests", "manifest.json")) as f:
            cls.manifest = json.load(f)["tests"]
        cls.chapters = sorted(os.path.basename(c)[:2] for c in glob.glob(os.path.join(cls.kit, "chapters", "[0-9][0-9]-*")))
        env = dict(os.environ, **compiler_cache(cls.kit))
        env.pop("RT_GRADER_ISOLATION", None)
        for chapters in [None] + cls.chapters:
            cmd = ["tools/grader/grade", ".", "--out", "preview.json"] + (["--chapters", chapters] if chapters else [])
            started = time.monotonic()
            result = run(cmd, cwd=cls.kit, env=env, timeout=1500 if chapters is None else 600)
            data = None
            if os.path.isfile(os.path.join(cls.kit, "preview.json")):
                with open(os.path.join(cls.kit, "preview.json")) as f:
                    data = json.load(f)
                os.remove(os.path.join(cls.kit, "preview.json"))
            print(f"{' '.join(cmd)}: {time.monotonic() - started:.1f} s")
            cls.previews[chapters] = result, data

    def setUp(self):
        self.assertEqual(self.export.returncode, 0, "tools/export/kit failed")

    def check(self, chapters):
        result, data = self.previews[chapters]
        where = "the preview" + (f" --chapters {chapters}" if chapters else "")
        self.assertEqual(result.returncode, 0, f"{where} failed:\n{result.stderr[-2000:]}")
        self.assertIsNotNone(data, f"{where} wrote no preview.json")
        wanted = sorted(n for n in self.manifest if chapters is None or n.startswith(f"ch{chapters}."))
        self.assertTrue(wanted, f"the kit's manifest has no test of {where}")
        self.assertEqual(sorted(t["name"] for t in data["tests"]), wanted, f"{where}: not every test was graded")
        failed = [f"{t['name']}: {t['output'][:300]}" for t in data["tests"] if t["status"] != "passed"]
        self.assertEqual(failed, [], f"{where}: correct exercise files lost points")
        total = sum(self.manifest[n]["points"] for n in wanted)
        self.assertEqual(data.get("score"), total, f"{where}: {data.get('score')} of {total}")

    def test_every_chapter_together_scores_full_marks(self):
        self.check(None)

    def test_each_chapter_alone_scores_full_marks(self):
        for chapter in self.chapters:
            with self.subTest(chapter=chapter):
                self.check(chapter)


class KitBuilt(KitTest):
    """The kit's READMEs' commands, run in the kit in order; then the whole kit built, and nothing in it
    computing an answer. One build of the kit (build/student) serves every check: the READMEs'
    commands build their chapters (and preview the score with the kit's own grader), then the rest is built."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        if cls.export.returncode != 0:
            return
        env = dict(os.environ, **compiler_cache(cls.kit))
        cls.commands = run_readme_commands(cls.kit, env)
        cls.build = run(["cmake", "--build", "--preset", "student"], cwd=cls.kit, env=env, timeout=1800)

    def test_every_readme_command_works_in_the_kit(self):
        self.assertTrue(self.commands, "no command found in the kit's READMEs")
        for where, command, result in self.commands:
            with self.subTest(command=where):
                self.check_command(where, command, result)

    def check_command(self, where, command, result):
        """Each command must work, or stop politely because the chapters are still stubs."""
        output = result.stdout + result.stderr
        self.assertIsNone(NOT_FOUND.search(output), f"{where} names something the kit lacks:\n{output[-1500:]}")
        words = command.split()
        polite = "not implemented yet" in output
        if words[0] in ("ctest", "tools/check"):  # tools/check NN builds chapter NN, then runs its ctest
            # The stubs fail every public test, politely.
            self.assertTrue(result.returncode == 8 and polite and re.search(r"(^|\s)0% tests passed", output),
                            f"{where}: expected every test to fail with 'not implemented yet' "
                            f"(exit {result.returncode}):\n{output[-1500:]}")
        elif os.path.basename(words[0]) == "imgcmp":
            self.assertTrue(result.returncode in (0, 1) and "difference image" in output,
                            f"{where}: exit {result.returncode}:\n{output[-1500:]}")
        elif words[0].startswith("build/"):
            self.assertTrue(result.returncode == 3 and polite,
                            f"{where}: expected the stub's exit status 3, 'not implemented yet', got exit "
                            f"{result.returncode}:\n{output[-1500:]}")
        else:
            self.assertEqual(result.returncode, 0, f"{where} failed:\n{output[-1500:]}")
            if words[0].endswith("grader/grade") and "--out" in words:
                self.check_preview(os.path.join(self.kit, words[words.index("--out") + 1]), where)

    def check_preview(self, path, where):
        """A preview of the untouched kit: zero points, only public tests, every one failing politely."""
        self.assertTrue(os.path.isfile(path), f"{where} wrote no {path}")
        with open(path) as f:
            data = json.load(f)
        self.assertEqual(total_score(data), 0, f"{where}: the untouched kit scored points")
        self.assertEqual([t["name"] for t in data["tests"] if ".hidden." in t["name"]], [],
                         f"{where}: the kit graded hidden tests")

        def kind(t):
            tags = t.get("tags") or []
            return tags[1] if len(tags) > 1 else None

        public = [t for t in data["tests"] if kind(t) == "public"]
        self.assertTrue(public, f"{where}: the kit has no public test")
        for t in public + [t for t in data["tests"] if kind(t) == "render"]:
            self.assertIn("not implemented yet", t["output"], f"{where}: {t['name']} does not fail politely")

    def test_check_stops_at_a_build_error(self):
        """tools/check NN does not run the last build's tests when chapter NN no longer compiles."""
        self.test_the_kit_builds_with_the_student_preset()
        exercise = os.path.join(self.kit, "chapters", "01-unit-sphere", "unit_sphere.cpp")
        with open(exercise) as f:
            original = f.read()
        try:
            with open(exercise, "a") as f:
                f.write("\nthis line does not compile;\n")
            result = run(["tools/check", "01"], cwd=self.kit, env=dict(os.environ, **compiler_cache(self.kit)),
                         timeout=600)
        finally:
            with open(exercise, "w") as f:
                f.write(original)
        output = result.stdout + result.stderr
        self.assertEqual(result.returncode, 1, f"tools/check 01 with a compile error:\n{output[-1500:]}")
        self.assertIn("chapter 01 does not build, so its tests were not run", output)
        self.assertNotIn("tests passed", output, "tools/check ran the tests of the last build that worked")

    def test_the_kit_builds_with_the_student_preset(self):
        self.assertEqual(self.build.returncode, 0, "the kit does not build with the student preset")

    def test_readmes_name_only_what_the_built_kit_holds(self):
        self.test_the_kit_builds_with_the_student_preset()
        self.assertEqual(readme_path_problems(self.kit, after_build=True), [])

    # --- Semantic leak check: nothing in the kit computes an answer ---------------------------------
    def chapters(self):
        self.test_the_kit_builds_with_the_student_preset()
        chapters = []
        for path in sorted(glob.glob(os.path.join(self.kit, "build", "student", "rt_chapters", "ch*.json"))):
            with open(path) as f:
                chapters.append(json.load(f))
        self.assertGreaterEqual(len(chapters), 7, "the kit's build describes too few chapters")
        return chapters

    def scratch(self, name):
        out = os.path.join(config.work, name)
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        return out

    def test_every_chapter_program_stops_politely(self):
        out = self.scratch("kit-programs")
        for ch in self.chapters():
            with self.subTest(chapter=ch["id"]):
                r = subprocess.run([ch["program"], "--out", os.path.join(out, ch["id"] + ".png")],
                                   capture_output=True, text=True, timeout=120)
                self.assertTrue(r.returncode == 3 and "not implemented yet" in r.stdout + r.stderr,
                                f"{ch['id']}'s program with the stubs: exit {r.returncode}, not 3:\n"
                                f"{(r.stdout + r.stderr)[-800:]}")

    def test_no_public_test_passes_with_the_stubs(self):
        for ch in self.chapters():
            with self.subTest(chapter=ch["id"]):
                r = subprocess.run([ch["public_tests"]], capture_output=True, text=True, timeout=300)
                m = re.search(r"test cases:\s*(\d+)\s*\|\s*(\d+) passed", r.stdout)
                self.assertIsNotNone(m, f"{ch['id']}'s public tests printed no summary:\n{r.stdout[-800:]}")
                self.assertTrue(int(m.group(1)) > 0 and m.group(2) == "0",
                                f"{ch['id']}: {m.group(2)} of {m.group(1)} public test cases pass with the stubs")

    def references(self):
        return sorted(glob.glob(os.path.join(self.kit, "chapters", "*", "*.png")))

    def imgcmp(self):
        return os.path.join(self.kit, "build", "student", "bin", "imgcmp")

    def test_no_other_program_draws_a_reference_picture(self):
        programs = {os.path.realpath(ch["program"]) for ch in self.chapters()}
        build = os.path.join(self.kit, "build", "student")
        others = [p for p in sorted(glob.glob(os.path.join(build, "bin", "*")))
                  if os.access(p, os.X_OK) and os.path.realpath(p) not in programs]
        self.assertIn("imgcmp", [os.path.basename(p) for p in others], "the kit builds no imgcmp")
        problems = pictures_drawn(others, self.kit, self.scratch("kit-semantic"), self.imgcmp(), self.references())
        self.assertEqual(problems, [], "programs of the kit draw a reference picture with the stubs")
        print(f"semantic check: {', '.join(os.path.basename(p) for p in others)} "
              f"on {len(self.references())} reference pictures")

    def test_the_semantic_check_catches_a_fake_renderer(self):
        self.test_the_kit_builds_with_the_student_preset()
        out = self.scratch("kit-fake")
        fake = os.path.join(out, "rt-fake-render")
        with open(fake, "w") as f:
            f.write("#!/bin/sh\n# draws chapter 03's picture whatever it is asked\n"
                    'while [ $# -gt 0 ]; do [ "$1" = --out ] && cp "%s" "$2"; shift; done\n'
                    % os.path.join(self.kit, "chapters", "03-scene-loop", "reference.png"))
        os.chmod(fake, 0o755)
        self.assertNotEqual(pictures_drawn([fake], self.kit, out, self.imgcmp(), self.references()), [],
                            "the semantic check misses a fake renderer")


# --- The READMEs of the kit ---------------------------------------------------------------------

KIT_TOP_FOLDERS = ("chapters", "common", "tests", "tools", "scenes", "cmake", "solutions", "build")


def kit_readmes(kit):
    found = []
    for dirpath, dirnames, filenames in os.walk(kit):
        dirnames[:] = sorted(d for d in dirnames if not (dirpath == kit and d in ("build", "out", "renders")))
        found += [os.path.join(dirpath, n) for n in sorted(filenames) if n.endswith(".md")]
    return found


def readme_path_problems(kit, after_build):
    """Every repository path a kit README names (in `code` or as a link) exists in the kit;
    build/ paths are checked once the kit is built. Returns the problems found."""
    problems = []
    for readme in kit_readmes(kit):
        rel_readme = os.path.relpath(readme, kit)
        with open(readme) as f:
            text = f.read()
        if not after_build:
            problems += [f"{rel_readme} still holds the marker {marker}" for marker in rtexport.INSTRUCTOR_ONLY
                         if marker in text]
            for target in re.findall(r"\]\(([^)\s#]+)(?:#[^)]*)?\)", text):
                if "://" in target or target.startswith("mailto:"):
                    continue
                if not os.path.exists(os.path.normpath(os.path.join(os.path.dirname(readme), target))):
                    problems.append(f"{rel_readme} links to {target}, which is not in the kit")
        names = set()
        for span in re.findall(r"`([^`\n]+)`", re.sub(r"```.*?```", "", text, flags=re.S)):
            for word in re.findall(r"(?<![\w./-])((?:%s)/[\w./-]*)" % "|".join(KIT_TOP_FOLDERS), span):
                names.add(word.rstrip("."))
        for name in sorted(names):
            if re.search(r"NN|XX", name) or (name.startswith("build/") != after_build):
                continue
            if not os.path.exists(os.path.join(kit, name)):
                problems.append(f"{rel_readme} names {name}, which is not in the kit")
    return problems


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


def run_readme_commands(kit, env):
    """Runs every command of every kit README, in the kit, in order; returns (where, command, result)."""
    ran = []
    for readme in kit_readmes(kit):
        rel_readme = os.path.relpath(readme, kit)
        for command in sh_commands(readme):
            start = time.monotonic()
            result = subprocess.run(["bash", "-c", command], cwd=kit, env=env, capture_output=True, text=True,
                                    timeout=1800)
            print(f"$ {command}   [{rel_readme}] -> exit {result.returncode} ({time.monotonic() - start:.0f} s)")
            ran.append((f"{rel_readme}: `{command}`", command, result))
    return ran


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


class Gradescope(ToolTest):
    """The Gradescope bundle, unpacked into a folder laid out like /autograder/: setup.sh, then
    run_autograder on the solutions and on the stubs of chapter 01 (a flat upload of the exercise file)."""

    @classmethod
    def setUpClass(cls):
        zip_path = os.path.join(config.work, "gradescope", "autograder.zip")
        cls.export = run([sys.executable, os.path.join(REPO, "tools", "export", "gradescope"), zip_path])
        root = os.path.join(config.work, "gradescope", "autograder")
        shutil.rmtree(root, ignore_errors=True)
        cls.source = source = os.path.join(root, "source")
        os.makedirs(source)
        if cls.export.returncode != 0:
            return
        rtexport.unpack_bundle(zip_path, source)
        shutil.copy(os.path.join(source, "run_autograder"), os.path.join(root, "run_autograder"))
        env = dict(os.environ, AUTOGRADER_ROOT=root, RT_SKIP_APT="1", RT_GRADER_BUILD_DIR=config.build_dir,
                   RT_GRADER_CHAPTERS="01")
        cls.setup = run(["bash", os.path.join(source, "setup.sh")], cwd=source, env=env, timeout=900)
        cls.runs = {}
        cases = {"solutions": os.path.join(REPO, "solutions", "01-unit-sphere", "unit_sphere.cpp"),
                 "stubs": os.path.join(REPO, "chapters", "01-unit-sphere", "unit_sphere.cpp")}
        for who, exercise in cases.items():
            submission = os.path.join(root, "submission")
            shutil.rmtree(submission, ignore_errors=True)
            os.makedirs(submission)
            shutil.copy(exercise, submission)
            results = os.path.join(root, "results", "results.json")
            if os.path.exists(results):
                os.remove(results)
            run_ = run([os.path.join(root, "run_autograder")], cwd=root, env=env, timeout=900)
            data = None
            if os.path.isfile(results):
                with open(results) as f:
                    data = json.load(f)
            cls.runs[who] = run_, data

    def setUp(self):
        self.assertEqual(self.export.returncode, 0, "tools/export/gradescope failed")

    def test_the_bundle_holds_the_grader_and_the_private_tests(self):
        for name in ("setup.sh", "run_autograder", "tools/grader/grade", "solutions", "tests/hidden"):
            self.assertTrue(os.path.exists(os.path.join(self.source, name)), f"the bundle lacks {name}")

    def test_setup_sh_prepares_the_tree(self):
        self.assertEqual(self.setup.returncode, 0, "setup.sh failed")

    def graded(self, who):
        run_, data = self.runs[who]
        self.assertEqual(run_.returncode, 0, f"run_autograder failed on the {who}")
        self.assertIsNotNone(data, f"no results.json for the {who}")
        return data

    def test_the_solutions_score_full_marks(self):
        data = self.graded("solutions")
        total = sum(t["max_score"] for t in data["tests"])
        self.assertTrue(total > 0 and total_score(data) == total, f"the solutions scored {total_score(data)} of {total}")

    def test_the_stubs_score_zero(self):
        self.assertEqual(total_score(self.graded("stubs")), 0, "the stubs scored points")


if __name__ == "__main__":
    main()
