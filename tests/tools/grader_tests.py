#!/usr/bin/env python3
"""Tests of the autograder itself (ctest label 'grader'; see tests/tools/CMakeLists.txt).

  grader_tests.py --work DIR --build-dir TREE Baseline      solutions score full marks, stubs zero (politely)
  grader_tests.py --work DIR --build-dir TREE Adversarial.test_NAME
                                                            one adversarial submission behaves as expected
  grader_tests.py --work DIR --build-dir TREE Batch         a folder of submissions, one results file each + CSV
  grader_tests.py --work DIR --kit KIT KitPreview           a kit's preview with chapter 03 broken: the others count

Every grading runs the real command line (tools/grader/grade) on chapter 01
(and 02 where a fixture needs a second chapter) against one instructor tree,
prepared by Baseline, so the other tests are quick. KitPreview grades a copy of
the kit that grader.export.kit exported, with that kit's own grading tree.
"""

import glob
import json
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "grader"))
sys.dont_write_bytecode = True
from tooltest import FIXTURES, add_fixture_tests, fixture_files, fixture_source, GRADE, REPO, ROOT, ToolTest, config, grade, main, make_submission, matches, solution_folder, total_score

PREPARE_TIME_LIMIT = 850          # seconds: the first build of the grading tree (ctest gives 900)
# A correct test case ends in milliseconds, but on a machine shared with builds (load 20-40) the
# hidden test with a thousand calls took over 3 s: the grader's own default, 10 s, costs nothing
# to a test that passes.
TEST_LIMITS = ["--timeout", "10", "--render-timeout", "20"]
# The fixtures whose hostile part hangs until a limit stops it wait that limit in every test
# case it fires in (and in the render when the program hangs too): they are graded with
# shorter limits. Their tests that must pass are chapter 01's public ones (a few calls each)
# and its render (20 ms on a quiet machine); the hidden ones may differ.
HANGING = {"infinite-loop", "static-init-loop", "fork-bomb", "slow-on-one-concept"}
HANG_LIMITS = ["--timeout", "3", "--render-timeout", "8"]


def baseline_path():
    """The solutions' results, written by Baseline; the fixtures are compared with them."""
    return os.path.join(config.work, "baseline.json")


class Baseline(ToolTest):
    """Prepares the grading tree; the solutions score full marks; the stubs score zero and say why, politely."""

    @classmethod
    def setUpClass(cls):
        # Preparing the tree first, with its own time limit: on a busy machine the first build takes minutes.
        cls.prepared = subprocess.run([sys.executable, GRADE, "--prepare-only", "--build-dir", config.build_dir,
                                       "--chapters", "01,02"], capture_output=True, text=True,
                                      timeout=PREPARE_TIME_LIMIT)
        print(cls.prepared.stdout[-2000:], cls.prepared.stderr[-3000:])
        sub = make_submission(os.path.join(config.work, "solutions"), solutions=["01", "02"])
        cls.solutions = grade(sub, os.path.join(config.work, "solutions-results", "results.json"), "01,02",
                              config.build_dir, TEST_LIMITS)
        if cls.solutions.data:
            shutil.copy(cls.solutions.path, baseline_path())
        stub = make_submission(os.path.join(config.work, "stubs"),
                               sources=[os.path.join(REPO, "chapters", "01-unit-sphere", "unit_sphere.cpp")])
        cls.stubs = grade(stub, os.path.join(config.work, "stub-results", "results.json"), "01",
                          config.build_dir, TEST_LIMITS)

    def test_tree_prepares_showing_progress(self):
        self.assertEqual(self.prepared.returncode, 0, "preparing the grading tree failed")
        self.assertTrue("build steps done" in self.prepared.stderr or "preparing" not in self.prepared.stderr,
                        "preparing the tree shows no progress (build steps done of total)")

    def test_solutions_score_full_marks(self):
        self.assertFullMarks(self.assertGraded(self.solutions), "the solutions")

    def test_stubs_score_zero_politely(self):
        data = self.assertGraded(self.stubs)
        self.assertEqual(total_score(data), 0, "the stubs scored points")
        self.assertTrue(data["tests"], "no test graded")
        for t in data["tests"]:
            with self.subTest(test=t["name"]):
                self.assertIn("not implemented yet", t["output"], "a stub's test does not say why it fails")

    def test_hidden_feedback_shows_only_the_concept(self):
        data = self.assertGraded(self.stubs)
        hidden = [t for t in data["tests"] if t["tags"][1] == "hidden"]
        self.assertTrue(hidden, "no hidden test graded")
        for t in hidden:
            with self.subTest(test=t["name"]):
                self.assertNotIn("logged", t["output"], "a hidden test shows more than the concept")
                self.assertNotIn("values:", t["output"], "a hidden test shows the values it compared")


class Adversarial(ToolTest):
    """One test per tests/fixtures/adversarial/NAME/ with an expect.json (test_NAME, '-' read as '_'):
    the submission is graded and checked against its expect.json (see the README there)."""

    def check_fixture(self, name):
        folder = os.path.join(FIXTURES, name)
        with open(os.path.join(folder, "expect.json")) as f:
            expect = json.load(f)
        source = fixture_source(name)
        sub = make_submission(os.path.join(config.work, "fixtures", name), sources=fixture_files(name),
                              solutions=expect.get("add_solutions", []),
                              files={"unit_sphere.cpp": source} if source is not None else {})
        out = os.path.join(config.work, "fixtures-results", name, "results.json")
        # "gradings": N grades the same submission N times in a row (a channel from one grading into the
        # next); the checks read the last.
        for _ in range(expect.get("gradings", 1)):
            graded = grade(sub, out, expect["chapters"], config.build_dir,
                           HANG_LIMITS if name in HANGING else TEST_LIMITS)
        data = self.assertGraded(graded)
        if expect.get("root_only") and not ROOT:
            self.skipTest(f"'{name}' needs user isolation, which is off when the grader is not run as root: "
                          "only the validity of results.json was checked")
        self.assertTrue(os.path.isfile(baseline_path()), "no solutions' results: grader.baseline must run first")
        with open(baseline_path()) as f:
            chapters = {f"ch{c}" for c in expect["chapters"].split(",")}
            base = {t["name"]: t["status"] for t in json.load(f)["tests"] if t["name"].split(".", 1)[0] in chapters}
        self.assertTrue(base, f"the solutions' results hold no test of {expect['chapters']}")
        self.assertStatuses(name, data, expect["must_fail"], expect["may_differ"], base)
        for chapter, words in expect.get("compilation", {}).items():
            entry = [t for t in data["tests"] if t["name"] == f"{chapter} compilation"]
            self.assertTrue(entry, f"no '{chapter} compilation' entry")
            self.assertIn(words, entry[0]["output"])
            self.assertEqual(entry[0]["visibility"], "visible")
        forbidden = expect.get("forbidden_in_results")
        if forbidden:
            with open(out) as f:
                self.assertNotIn(forbidden, f.read(), "results.json shows what it must not")
        hidden_forbidden = expect.get("forbidden_in_hidden")
        public_forbidden = expect.get("forbidden_in_public_tests")
        if hidden_forbidden:
            for t in data["tests"]:
                if t["tags"][1] == "hidden":
                    self.assertNotIn(hidden_forbidden, t["output"], f"hidden test {t['name']} shows it")
            if not public_forbidden:
                self.assertTrue(any(hidden_forbidden in t["output"] for t in data["tests"] if t["tags"][1] == "public"),
                                "the public feedback should still show the exception's own message")
        shown = expect.get("shown_in_public")     # the attack ran and its channel works (the test is not vacuous)
        if shown:
            self.assertTrue(any(shown in t["output"] for t in data["tests"] if t["tags"][1] == "public"),
                            f"no public test shows '{shown}'")
        if public_forbidden:
            for t in data["tests"]:
                if t["tags"][1] == "public":
                    self.assertNotIn(public_forbidden, t["output"], f"public test {t['name']} shows it")


add_fixture_tests(Adversarial, "*/expect.json")


class InstructorNote(ToolTest):
    """The "words to look at" note (grading.suspicious_words) matches identifiers whole: the
    chapter 08 solutions' widen_exit is no _exit, and the solutions are not flagged for it."""

    def test_identifiers_match_whole(self):
        from rtgrader import grading
        self.assertEqual(grading.suspicious_words("return entry <= widen_exit(exit) ? t : u;"), [])
        self.assertEqual(grading.suspicious_words("if (x) _exit(0); if (y) std::_Exit(1);"), ["_exit", "_Exit"])
        self.assertEqual(grading.suspicious_words("pid_t p = vfork(); // forking"), ["vfork"])
        self.assertEqual(grading.suspicious_words('#include "/dev/zero"\nsystem("ls");'),
                         ["system(", '#include "/'])
        # a closest_hit that reads the served callback's table instead of calling it
        self.assertEqual(grading.suspicious_words("f.target<rt::test::served_table<T>>()"),
                         ["rt::test", "served_table"])

    def test_no_solution_is_flagged_for_part_of_a_name(self):
        from rtgrader import grading
        for path in sorted(glob.glob(os.path.join(REPO, "solutions", "*", "*.cpp"))):
            with open(path) as f:
                words = grading.suspicious_words(f.read())
            with self.subTest(solution=os.path.relpath(path, REPO)):
                self.assertNotIn("_exit", words)
                self.assertNotIn("asm", words)


class ProgramOutput(ToolTest):
    """A chapter program that links earlier chapters from the solutions (grading with the
    solutions) holds the course's own code: its output, which the student's code writes, is not
    shown (it could print that code's bytes); a chapter that builds on nothing shows it."""

    def said(self, depends, has_solutions):
        from types import SimpleNamespace
        from rtgrader import grading
        grader = grading.Grader.__new__(grading.Grader)
        grader.tree = SimpleNamespace(has_solutions=has_solutions)
        return grader._program_said({"depends": depends}, "SOLUTION-BYTES 554889e5\n")

    def test_output_hidden_when_the_program_holds_solutions(self):
        self.assertNotIn("SOLUTION-BYTES", self.said(["02", "03"], True))
        self.assertIn("not shown", self.said(["02", "03"], True))

    def test_output_shown_otherwise(self):
        self.assertIn("SOLUTION-BYTES", self.said([], True))
        self.assertIn("SOLUTION-BYTES", self.said(["02", "03"], False))     # a kit: the student's own code

    def figures(self, depends, has_solutions):
        from types import SimpleNamespace
        from rtgrader import grading
        grader = grading.Grader.__new__(grading.Grader)
        grader.tree = SimpleNamespace(has_solutions=has_solutions)
        return grader._figures_shown({"depends": depends}, "MISMATCH: 28659 of 120000 pixels differ")

    def test_imgcmp_figures_hidden_when_the_program_holds_solutions(self):
        self.assertNotIn("28659", self.figures(["02"], True))
        self.assertIn("28659", self.figures([], True))
        self.assertIn("28659", self.figures(["02"], False))


class LinkRule(ToolTest):
    """What a submission object may define (rtgrader/symbols.py, README "Linking"): its exercise's
    functions; another strong definition is refused, naming the symbol demangled and the rule; a weak
    copy of anything else (an inline function of common/ with another body) becomes the object's own:
    linked after an instructor object carrying the same inline function, each keeps its own copy."""

    EXERCISE = "_Z8exercisei"          # int exercise(int)
    INLINE = """
        namespace rt { struct options { int n = 0; ~options(); }; }
        __attribute__((noinline)) inline int shared_inline(int x) { return x * 2; }   // an inline function of "common/"
    """

    def compile(self, name, text):
        folder = os.path.join(config.work, "link-rule")
        os.makedirs(folder, exist_ok=True)
        src, obj = os.path.join(folder, name + ".cpp"), os.path.join(folder, name + ".o")
        with open(src, "w") as f:
            f.write(text)
        subprocess.run(["c++", "-O2", "-c", src, "-o", obj], check=True)
        with open(obj, "rb") as f:
            return f.read(), obj

    def confine(self, text):
        from rtgrader import symbols
        data, _ = self.compile("student", text)
        return symbols.confine(data, {self.EXERCISE}, "unit_sphere.cpp")

    def test_a_strong_helper_is_refused_by_name(self):
        out, why = self.confine("int helper(int x) { return x; }\nint exercise(int x) { return helper(x); }\n")
        self.assertIsNone(out)
        self.assertIn("helper(int) (_Z6helperi)", why)
        self.assertIn("internal linkage", why)
        self.assertNotIn("exercise(int)", why)

    def test_a_defined_front_end_is_refused(self):
        out, why = self.confine("namespace rt { struct chapter_program; int run_chapter_program(int, char**, "
                                "const chapter_program&) { return 0; } }\nint exercise(int x) { return x; }\n")
        self.assertIsNone(out)
        self.assertIn("rt::run_chapter_program(int, char**, rt::chapter_program const&)", why)

    def test_an_old_style_comdat_section_is_refused(self):
        out, why = self.confine('asm(".section .gnu.linkonce.t.foo,\\"ax\\",@progbits\\n.byte 0xc3\\n.previous");\n'
                                "int exercise(int x) { return x; }\n")
        self.assertIsNone(out)
        self.assertIn(".gnu.linkonce", why)

    # The red team's link-time tricks (C++ or asm in the exercise file): each is refused, or its object,
    # once confined, defines nothing global but the exercise (what any other object could bind to).
    TRICKS = {
        "strong alias": 'extern "C" void png_alias() __attribute__((alias("_Z8exercisei")));',
        "weak alias named like libc's memcpy": 'asm(".weak memcpy\\n.set memcpy, _Z8exercisei");',
        "symbol version of libc's malloc": 'asm(".symver _Z8exercisei, malloc@@GLIBC_2.2.5");',
        "ifunc resolver": 'static int impl(int x) { return x; }\nextern "C" void* pick() { return (void*)impl; }\n'
                          'int other(int) __attribute__((ifunc("pick")));',
        "global operator new": "#include <cstdlib>\n#include <new>\n"
                               "void* operator new(std::size_t n) { return std::malloc(n); }",
        "weak operator new": "#include <cstdlib>\n#include <new>\n"
                             "__attribute__((weak)) void* operator new(std::size_t n) { return std::malloc(n); }",
        "main": "int main() { return 0; }",
        "_start": 'extern "C" void _start() {}',
        "a TLS variable": "thread_local int counter = 0;",
        "a weak TLS variable": "__attribute__((weak)) thread_local int counter = 0;",
        "another chapter's exercise": "namespace rt::ch02 { int intersect_sphere(int x) { return x; } }",
        "an explicit specialisation of a library template":
            "namespace std { template <class T> struct hash; template <> struct hash<int> {"
            " unsigned long operator()(int) const noexcept { return 0; } }; }\n"
            "unsigned long use(int x) { return std::hash<int>{}(x); }",
        "a common symbol": 'asm(".comm shared_buffer,64,8");',
        "an absolute symbol": 'asm(".globl abs_sym\\n.set abs_sym, 0x1234");',
        "a weak rt::write_png in asm": 'asm(".weak _ZN2rt9write_pngEv\\n_ZN2rt9write_pngEv: ret");',
        "a COMDAT group signed by rt::run_chapter_program":
            'asm(".section .text.g,\\"axG\\",@progbits,_ZN2rt18run_chapter_programEv,comdat\\n'
            '.weak _ZN2rt18run_chapter_programEv\\n_ZN2rt18run_chapter_programEv: ret\\n.text");',
    }

    def test_link_tricks_gain_nothing(self):
        from rtgrader import symbols
        for k, (what, trick) in enumerate(self.TRICKS.items()):
            with self.subTest(trick=what):
                data, _ = self.compile(f"trick{k}", trick + "\nint exercise(int x) { return x + 1; }\n")
                out, why = symbols.confine(data, {self.EXERCISE}, "unit_sphere.cpp")
                if out is None:
                    self.assertIn("The rule:", why)
                    continue
                confined = os.path.join(config.work, "link-rule", f"trick{k}.confined.o")
                with open(confined, "wb") as f:
                    f.write(out)
                listed = subprocess.run(["nm", "-g", "--defined-only", confined], capture_output=True, text=True,
                                        check=True).stdout
                names = [line.split()[-1] for line in listed.splitlines() if line.strip()]
                self.assertEqual(names, [self.EXERCISE], f"{what}: still global after confining")

    def test_static_helpers_and_the_exercise_pass_unchanged(self):
        from rtgrader import symbols
        text = "static int helper(int x) { return x; }\nnamespace { int other(int x) { return -x; } }\n" \
               "int exercise(int x) { return helper(x) + other(x); }\n"
        data, _ = self.compile("plain", text)
        out, why = symbols.confine(data, {self.EXERCISE}, "unit_sphere.cpp")
        self.assertEqual(why, "")
        self.assertEqual(out, data)

    def test_a_weak_copy_with_another_body_stays_the_submissions_own(self):
        from rtgrader import symbols
        student = self.INLINE.replace("x * 2", "x * 1000") + \
            "__attribute__((noinline)) int call(int x) { return shared_inline(x); }\n" \
            "int exercise(int x) { return shared_inline(x); }\n"
        out, why = self.confine(student.replace("__attribute__((noinline)) int call", "static int call"))
        self.assertEqual(why, "")
        defined, _, signatures = symbols.read_symbols(out)
        self.assertEqual(set(defined), {self.EXERCISE}, "the rewritten object defines more than its exercise")
        self.assertFalse({s for s in signatures if "shared_inline" in s}, "a COMDAT group kept its signature")
        # Linked first, before the instructor's object that carries the same inline function: the
        # instructor's call still gets the instructor's body, and the student's its own.
        folder = os.path.join(config.work, "link-rule")
        with open(os.path.join(folder, "student-confined.o"), "wb") as f:
            f.write(out)
        _, teacher = self.compile("teacher", self.INLINE + """
            #include <cstdio>
            int exercise(int);
            __attribute__((noinline)) int instructor(int x) { return shared_inline(x); }
            int main() { std::printf("%d %d\\n", instructor(3), exercise(3)); }
        """)
        program = os.path.join(folder, "linked")
        for student_object, expected in ((os.path.join(folder, "student-confined.o"), "6 3000"),):
            subprocess.run(["c++", student_object, teacher, "-o", program], check=True)
            self.assertEqual(subprocess.run([program], capture_output=True, text=True).stdout.strip(), expected)

    def test_the_unconfined_weak_copy_would_replace_the_instructors(self):
        """The mistake the rule prevents: the same objects linked as they are, the student's first."""
        student = self.INLINE.replace("x * 2", "x * 1000") + "int exercise(int x) { return shared_inline(x); }\n"
        _, raw = self.compile("student-raw", student)
        _, teacher = self.compile("teacher-raw", self.INLINE + """
            #include <cstdio>
            int exercise(int);
            __attribute__((noinline)) int instructor(int x) { return shared_inline(x); }
            int main() { std::printf("%d %d\\n", instructor(3), exercise(3)); }
        """)
        program = os.path.join(config.work, "link-rule", "linked-raw")
        subprocess.run(["c++", raw, teacher, "-o", program], check=True)
        self.assertEqual(subprocess.run([program], capture_output=True, text=True).stdout.strip(), "3000 3000")


class PictureView(ToolTest):
    """The graded picture's view (rtgrader/picture.py): drawn from a fresh secret at every grading,
    different for every chapter, within the documented turn, never the chapter's own view."""

    def test_views_come_from_the_secret(self):
        from rtgrader import picture
        seen = set()
        for _ in range(200):
            secret = picture.draw_secret()
            for cid in ("ch01", "ch02"):
                yaw, pitch = picture.view_for(secret, cid)
                self.assertTrue(picture.YAW_DEGREES[0] <= abs(yaw) <= picture.YAW_DEGREES[1], yaw)
                self.assertTrue(picture.PITCH_DEGREES[0] <= pitch <= picture.PITCH_DEGREES[1], pitch)
                seen.add((yaw, pitch))
            self.assertEqual(picture.view_for(secret, "ch01"), picture.view_for(secret, "ch01"))
        self.assertGreater(len(seen), 395, "views repeat across gradings")
        self.assertTrue(any(y < 0 for y, _ in seen) and any(y > 0 for y, _ in seen))

    def test_graded_size_is_half_the_reference(self):
        from rtgrader import picture
        reference = os.path.join(REPO, "chapters", "01-unit-sphere", "reference.png")
        self.assertEqual(picture.png_size(reference), (400, 300))
        self.assertEqual(picture.graded_size(reference), (200, 150))


class JudgeLimits(ToolTest):
    """The judge runs as the grader's user (root) outside the sandbox and decodes what the student's
    runner sends: it is started with an address-space limit (judge.JUDGE_MEMORY_BYTES)."""

    def test_a_judge_process_has_a_memory_limit(self):
        from rtgrader import judge
        said = subprocess.run([sys.executable, "-c", "import resource; print(resource.getrlimit(resource.RLIMIT_AS)[0])"],
                              capture_output=True, text=True, preexec_fn=judge._judge_limits, check=True).stdout
        self.assertEqual(int(said), judge.JUDGE_MEMORY_BYTES)
        self.assertLessEqual(judge.JUDGE_MEMORY_BYTES, 4096 << 20)


class CallbackTables(ToolTest):
    """Chapter 03's intersector is answered by the judge, call by call: a closest_hit that reads the
    callback's data instead of calling it (tests/fixtures/callbacks/reads-served-table.cpp, which scored
    86/90 while the answers were a table in the runner) finds nothing to read and scores what a
    closest_hit that always misses scores."""

    USE_TESTS = ["ch03.hidden.each object is tested with tmax shrunk to the closest hit so far",
                 "ch03.public.each hit shrinks tmax for the objects after it",
                 "ch03.hidden.random scenes of walls give the nearest hit",
                 "ch03.hidden.random scenes of spheres agree with testing every sphere"]

    def test_reading_the_callback_instead_of_calling_it_gains_nothing(self):
        folder = os.path.join(config.work, "reads-served-table")
        shutil.rmtree(folder, ignore_errors=True)
        with open(os.path.join(REPO, "tests", "fixtures", "callbacks", "reads-served-table.cpp")) as f:
            make_submission(folder, files={"scene_loop.cpp": f.read()})
        out = os.path.join(config.work, "reads-served-table.json")
        graded = grade(folder, out, "03", config.build_dir, TEST_LIMITS)
        results = self.assertValidResults(out)
        status = {t["name"]: t["status"] for t in results["tests"]}
        for name in self.USE_TESTS:
            for scalar in ("float", "double"):
                self.assertEqual(status.get(f"{name}<{scalar}>"), "failed", f"{name}<{scalar}>: {graded.stdout[-500:]}")
        total = sum(t.get("max_score", 0) for t in results["tests"])
        self.assertLess(total_score(results), total / 4, "more than a closest_hit that always misses would score")

    def test_catching_the_occlusion_tests_error_gains_nothing(self):
        """Chapter 06: the solution's shade() patched to ask about lights below the surface too and to
        swallow the error such a question raises (tests/fixtures/callbacks/catches-occlusion-error.patch).
        The judge notes the question and throws after the call, where the student's code cannot catch it."""
        work = os.path.join(config.work, "catches-occlusion-error")
        shutil.rmtree(work, ignore_errors=True)
        shutil.copytree(os.path.join(REPO, "solutions", "06-shading"), os.path.join(work, "src", "solutions", "06-shading"))
        with open(os.path.join(REPO, "tests", "fixtures", "callbacks", "catches-occlusion-error.patch")) as patch:
            subprocess.run(["patch", "-s", "-p1", "-d", os.path.join(work, "src")], stdin=patch, check=True)
        with open(os.path.join(work, "src", "solutions", "06-shading", "shading.cpp")) as f:
            folder = make_submission(os.path.join(work, "sub"), files={"shading.cpp": f.read()})
        out = os.path.join(work, "results.json")
        graded = grade(folder, out, "06", config.build_dir, TEST_LIMITS)
        status = {t["name"]: t["status"] for t in self.assertValidResults(out)["tests"]}
        for scalar in ("float", "double"):
            name = f"ch06.hidden.hidden: a light below the surface sends no shadow ray<{scalar}>"
            self.assertEqual(status.get(name), "failed", f"{name}: {graded.stdout[-500:]}")


CALLBACK_FIXTURES = os.path.join(REPO, "tests", "fixtures", "callbacks")


class CallbackRules(ToolTest):
    """One test per tests/fixtures/callbacks/NAME/ with an expect.json (test_NAME, '-' read as '_'): a
    wrong answer with a trick against the callbacks' rules, stored as attack.patch over the solution
    file named in expect.json. The trick's lines sit in `#ifndef RT_HONEST`: with RT_HONEST defined
    the same file is the honest wrong answer. Both are graded; the attack must gain nothing over the
    honest one (no test it passes that the honest one fails), and fail every test `must_fail` names."""

    def check_fixture(self, name):
        folder = os.path.join(CALLBACK_FIXTURES, name)
        with open(os.path.join(folder, "expect.json")) as f:
            expect = json.load(f)
        work = os.path.join(config.work, "callback-rules", name)
        shutil.rmtree(work, ignore_errors=True)
        solution = solution_folder(expect["chapter"])
        patched = os.path.join(work, "src", os.path.relpath(solution, REPO))
        shutil.copytree(solution, patched)
        with open(os.path.join(folder, "attack.patch")) as patch:
            subprocess.run(["patch", "-s", "-p1", "-d", os.path.join(work, "src")], stdin=patch, check=True)
        files = {}
        for path in sorted(glob.glob(os.path.join(patched, "*.cpp"))):
            with open(path) as f:
                files[os.path.basename(path)] = f.read()
        attacked = os.path.basename(expect["solution_file"])
        honest = dict(files)
        honest[attacked] = f"#define {expect['honest_define']} 1\n" + files[attacked]
        statuses, scores = {}, {}
        for who, sources in (("attack", files), ("honest", honest)):
            sub = make_submission(os.path.join(work, who), files=sources)
            out = os.path.join(work, who + "-results", "results.json")
            data = self.assertGraded(grade(sub, out, expect["chapter"], config.build_dir, TEST_LIMITS))
            statuses[who] = {t["name"]: t["status"] for t in data["tests"]}
            scores[who] = total_score(data)
            total = sum(t["max_score"] for t in data["tests"])
        self.assertLess(scores["honest"], total, "the honest wrong answer scored full marks: nothing to compare")
        gained = [n for n, s in statuses["attack"].items() if s == "passed" and statuses["honest"].get(n) != "passed"]
        self.assertEqual(gained, [], f"{name}: the trick passes tests the honest wrong answer fails")
        self.assertLessEqual(scores["attack"], scores["honest"], f"{name}: the trick gains points")
        for pattern in expect["must_fail"]:
            named = [n for n in statuses["attack"] if matches(n, [pattern])]
            self.assertTrue(named, f"no test matches {pattern}")
            for n in named:
                self.assertEqual(statuses["attack"][n], "failed", f"{name}: {n} passed")


for _path in sorted(glob.glob(os.path.join(CALLBACK_FIXTURES, "*", "expect.json"))):
    def _test(self, name=os.path.basename(os.path.dirname(_path))):
        self.check_fixture(name)
    setattr(CallbackRules, "test_" + os.path.basename(os.path.dirname(_path)).replace("-", "_"), _test)


class Batch(ToolTest):
    def test_batch_grades_each_submission_and_writes_the_scores(self):
        """Each submission gets its results and a row of scores.csv; mallory's file includes alice's
        answer by its path and gains nothing: with namespaces it does not exist for her compiler,
        and in the fallback by user (root) the submissions are closed to the sandbox users."""
        folder = os.path.join(config.work, "batch-in")
        shutil.rmtree(folder, ignore_errors=True)
        alice = make_submission(os.path.join(folder, "alice"), solutions=["01"])
        make_submission(os.path.join(folder, "bob"), files={"unit_sphere.cpp": fixture_source("segfault")})
        make_submission(os.path.join(folder, "carol"))
        answer = os.path.join(alice, "chapters", os.path.basename(solution_folder("01")), "unit_sphere.cpp")
        make_submission(os.path.join(folder, "mallory"), files={"unit_sphere.cpp": f'#include "{answer}"\n'})
        for mode, env in (("machine's best", {}), ("fallback", {"RT_GRADER_ISOLATION": "fallback"})):
            with self.subTest(mode=mode):
                self.check_batch(folder, mode, env)

    def check_batch(self, folder, mode, env):
        out = os.path.join(config.work, "batch-out")
        shutil.rmtree(out, ignore_errors=True)
        cmd = [sys.executable, os.path.join(REPO, "tools", "grader", "grade-batch"), folder, "--out", out,
               "--build-dir", config.build_dir, "--chapters", "01", "--jobs", "2", *TEST_LIMITS]
        before = os.stat(folder).st_mode
        result = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=dict(os.environ, **env))
        print(result.stdout, result.stderr)
        self.assertEqual(result.returncode, 0, "grade-batch failed")
        self.assertEqual(os.stat(folder).st_mode, before, "the submissions' folder keeps its mode")
        scores = {who: total_score(self.assertValidResults(os.path.join(out, who, "results.json")))
                  for who in ("alice", "bob", "carol", "mallory")}
        with open(os.path.join(out, "scores.csv")) as f:
            rows = f.read().splitlines()
        self.assertTrue(rows[0].startswith("submission,score,max_score,ch01"), rows)
        self.assertEqual(len(rows), 5, rows)
        self.assertGreater(scores["alice"], 0, scores)
        self.assertEqual(scores["carol"], 0, scores)
        self.assertTrue(0 < scores["bob"] < scores["alice"], f"implausible batch scores {scores}")
        if ROOT or "FALLBACK" not in result.stderr:
            self.assertEqual(scores["mallory"], 0, f"{mode}: a classmate's answer was compiled in")


class KitPreview(ToolTest):
    """In a student kit a chapter whose file does not compile costs that chapter only (issue 9).
    A copy of the exported kit, with the solutions of 01, 02 and 04, a broken 03 and a notes
    file of the student's, is previewed with the kit's own grader and grading tree: the new
    file makes the grader prepare that tree again, now from a kit whose chapter 03 does not compile."""

    def test_a_compile_error_costs_only_its_chapter(self):
        tree = os.path.join(config.kit, "build", "grader")
        self.assertTrue(os.path.isfile(os.path.join(tree, "state.json")),
                        f"no prepared grading tree in {tree}: grader.export.kit must run first")
        kit = os.path.join(config.work, "kit-broken")
        shutil.rmtree(kit, ignore_errors=True)
        shutil.copytree(config.kit, kit, ignore=lambda folder, names: [
            n for n in names if folder == config.kit and n in ("build", "out", "renders", "preview.json")])
        for chapter in ("01", "02", "03", "04"):
            folder = solution_folder(chapter)
            shutil.copytree(folder, os.path.join(kit, "chapters", os.path.basename(folder)), dirs_exist_ok=True)
        broken = glob.glob(os.path.join(kit, "chapters", "03-*", "scene_loop.cpp"))[0]
        with open(broken, "a") as f:
            f.write("\nthis line is not C++\n")
        with open(os.path.join(kit, "notes.txt"), "w") as f:    # new each time: the tree must be prepared again
            f.write(f"my notes of {time.time_ns()}\n")
        graded = grade(kit, os.path.join(kit, "preview.json"), "01,02,03,04", tree, TEST_LIMITS,
                       grade_cmd=os.path.join(kit, "tools", "grader", "grade"), timeout=PREPARE_TIME_LIMIT)
        self.assertIn("preparing the instructor tree", graded.stderr, "the kit's tree was not prepared again")
        data = self.assertGraded(graded)
        self.assertNotIn("does not build", data["output"], "the whole preview failed")
        for t in data["tests"]:
            chapter, kind = t["tags"]
            with self.subTest(test=t["name"]):
                if chapter in ("ch01", "ch02") or (chapter == "ch04" and kind == "public"):
                    self.assertEqual(t["status"], "passed", f"failed although its chapter is correct: {t['output'][:300]}")
                elif chapter == "ch03":
                    self.assertEqual(t["status"], "failed", "passed although chapter 03 does not compile")
        entry = [t for t in data["tests"] if t["name"] == "ch03 compilation"]
        self.assertTrue(entry, "no 'ch03 compilation' entry")
        self.assertIn("error", entry[0]["output"], "the 'ch03 compilation' entry lacks the compiler's message")
        with open(os.path.join(kit, "report.html"), encoding="utf-8") as f:     # the preview's page, beside it
            page = f.read()
        self.assertIn("The page with your pictures: " + os.path.join(kit, "report.html"), graded.stdout)
        for cid in ("ch01", "ch02", "ch03", "ch04"):
            self.assertIn(f'<section class="chapter" id="{cid}">', page)
        self.assertRegex(page, r'<div class="error-line">chapters/03-scene-loop/scene_loop\.cpp:\d+:\d+: error: ',
                         "the page does not show the compiler's first error line")
        self.assertIn('id="picture-ch01"', page, "chapter 01's picture is not on the page")
        # Every message the broken chapter causes in a later one names it (chapter 04's picture is drawn
        # with chapter 03's loop), and the terminal shows the compiler's first error line.
        caused = [t for t in data["tests"] if t["tags"][0] == "ch04" and t["status"] != "passed"]
        self.assertTrue(caused, "chapter 04 lost nothing although its program calls chapter 03's loop")
        for t in caused:
            with self.subTest(test=t["name"]):
                self.assertIn("chapter 03", t["output"], "a failure caused by chapter 03 does not name it")
        first = next(line.strip() for line in entry[0]["output"].splitlines() if " error" in line or "error:" in line)
        self.assertIn(first[:100], graded.stdout, "the terminal summary lacks the compiler's first error line")


if __name__ == "__main__":
    main()
