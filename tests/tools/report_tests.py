#!/usr/bin/env python3
"""Tests of the pages the grader writes (ctest -L grader; see tests/tools/CMakeLists.txt).

  report_tests.py --work DIR ReportPage        report.html from made-up results: only what a student sees;
                                               results.json's Markdown tables
  report_tests.py --work DIR --program CHAPTER_PROGRAM Browser
                                               that page and a chapter program's --compare page in headless
                                               Chromium (exit 77, ctest's skip, without chromium)
  report_tests.py --work DIR --build-dir TREE Dashboard
                                               grade-batch on a class of made-up submissions: dashboard.html,
                                               its JSON and CSV
  report_tests.py --work DIR DashboardBrowser.test_dashboard_page DashboardBrowser.test_a_students_report_page
                                               the class's dashboard and one student's report in Chromium

ReportPage and Browser need no grading: they build the pages from results data made here
(results.json's schema, PNG pictures written by png() below), so every case is known.
"""

import fnmatch
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "grader"))
sys.dont_write_bytecode = True
from tooltest import REPO, ToolTest, config, main  # noqa: E402
from rtgrader import report  # noqa: E402

SECRET = "HIDDEN-SECRET-7f3a"      # appears only in hidden tests' names and text


def png(width, height, pixel):
    """A PNG file's bytes: pixel(x, y) -> (r, g, b), 8 bits each."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data +
                                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def test_entry(name, chapter, kind, passed, points, output, visibility="visible", number="1.1"):
    return {"name": name, "number": number, "score": points if passed else 0, "max_score": points,
            "status": "passed" if passed else "failed", "output": output, "tags": [chapter, kind],
            "visibility": visibility}


def sample_results(folder):
    """A results.json and renders/ as a grading of chapters 01 (one public test failing, a picture
    that differs, hidden tests), 02 (did not build) and 03 (all passed, picture matches) leaves them."""
    tests = [
        test_entry("ch01.public.the ray misses", "ch01", "public", True, 1, "passed", number="1.1"),
        test_entry("ch01.public.inside the sphere", "ch01", "public", False, 1,
                   "unit_sphere_test.cpp:40: ERROR: CHECK( hit ) is NOT correct!\n"
                   "logged: the ray starts inside the sphere: the hit in front of the origin is the far root\n"
                   "your code said <script>alert(1)</script> & more", number="1.2"),
        test_entry(f"ch01.hidden.{SECRET} far root", "ch01", "hidden", False, 2, f"{SECRET}: a concept",
                   "after_published", number="1.3"),
        test_entry("ch01.render", "ch01", "render", False, 4,
                   "the picture differs from the reference render beyond tolerance: 1200 of 120000 pixels\n"
                   "your render: renders/ch01.png", number="1.4"),
        test_entry("ch02 compilation", "ch02", "compilation", False, 0,
                   "chapters/02-sphere/sphere.cpp: In function 'f':\n"
                   "chapters/02-sphere/sphere.cpp:17:5: error: expected ';' before 'return'\n   17 |     return t\n",
                   number="2.1"),
        test_entry("ch02.public.a sphere", "ch02", "public", False, 1,
                   "not graded: chapter 02 did not build (see 'ch02 compilation')", number="2.2"),
        test_entry("ch03.public.nearest wins", "ch03", "public", True, 1, "passed", number="3.1"),
        test_entry(f"ch03.hidden.{SECRET} order", "ch03", "hidden", True, 2, "passed", "after_published",
                   number="3.2"),
        test_entry("ch03.render", "ch03", "render", True, 4, "the picture matches the reference within tolerance",
                   number="3.3"),
    ]
    data = {"score": sum(t["score"] for t in tests), "execution_time": 12, "output": "Score 6 / 20.",
            "stdout_visibility": "hidden", "tests": tests}
    shutil.rmtree(folder, ignore_errors=True)
    renders = os.path.join(folder, "renders")
    os.makedirs(renders)
    pictures = {
        "ch01.png": png(80, 60, lambda x, y: (200, 40, 40) if (x - 40) ** 2 + (y - 30) ** 2 < 400 else (0, 0, 0)),
        "ch01.reference.png": png(80, 60, lambda x, y: (40, 40, 200) if (x - 40) ** 2 + (y - 30) ** 2 < 625
                                  else (0, 0, 0)),
        "ch01.diff.png": png(80, 60, lambda x, y: (255, 0, 0) if 400 <= (x - 40) ** 2 + (y - 30) ** 2 < 625
                             else (0, 0, 0)),
        "ch03.png": png(80, 60, lambda x, y: (x * 3, y * 4, 100)),
        "ch03.reference.png": png(80, 60, lambda x, y: (x * 3, y * 4, 100)),
        "ch03.diff.png": png(80, 60, lambda x, y: (0, 0, 0)),
    }
    for name, data_ in pictures.items():
        with open(os.path.join(renders, name), "wb") as f:
            f.write(data_)
    path = os.path.join(folder, "results.json")
    with open(path, "w") as f:
        json.dump(data, f)
    return data, path


# --- In a real browser -------------------------------------------------------------------------
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  # nothing resolves: whatever would still try to leave the machine goes nowhere
                  "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
                  "--window-size=1280,800", "--hide-scrollbars"]

# Put first in <head>: records every load the page attempts (resource timing, also failed loads)
# and every load its policy refused, before anything else of the page runs.
WATCH = """<script>
window.rtSeen = []; window.rtRefused = [];
new PerformanceObserver(l => { for (const e of l.getEntries()) rtSeen.push(e.name); })
  .observe({type: 'resource', buffered: true});
document.addEventListener('securitypolicyviolation', e => rtRefused.push(e.blockedURI + ' (' + e.violatedDirective + ')'));
</script>"""

# Put last in <body>: after the load event, what a person would see, as JSON in <pre id="rt-check">.
CHECK = """<script>
window.addEventListener('load', () => setTimeout(() => {
  const r = {sections: [...document.querySelectorAll('body > section')].map(s => s.id), images: [], sliders: [],
             drawings: [...document.querySelectorAll('svg')].map(g => { const b = g.getBoundingClientRect();
                                                                       return [b.width, b.height]; })};
  for (const img of document.images) {
    const box = img.getBoundingClientRect();
    r.images.push({alt: img.alt, complete: img.complete, natural: [img.naturalWidth, img.naturalHeight],
                   shown: [box.width, box.height]});
  }
  for (const s of document.querySelectorAll('.slider')) {
    const range = s.querySelector('input'), stack = s.querySelector('.stack');
    stack.scrollIntoView({block: 'center'});
    const at = value => {
      range.value = value; range.dispatchEvent(new Event('input'));
      const b = stack.getBoundingClientRect();
      const hit = document.elementFromPoint(b.left + b.width * 0.25, b.top + b.height / 2);
      return hit ? hit.className : 'nothing';
    };
    r.sliders.push({left_at_100: at(100), left_at_0: at(0)});
  }
  window.scrollTo(0, 0);
  r.loads = rtSeen.filter(u => !u.startsWith('data:'));
  r.refused = rtRefused;
  const pre = document.createElement('pre'); pre.id = 'rt-check'; pre.textContent = JSON.stringify(r);
  document.body.appendChild(pre);
}, 0));
</script>"""


def chromium():
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    return None


def run_chromium(args, work, timeout=120):
    """Chromium headless with a new empty profile of its own; returns (stdout, stderr, exit status).
    Each run gets its own profile folder: the page tests run in parallel (ctest -j) in one work folder,
    and a profile shared between two Chromiums, or deleted under one, fails the other one at random."""
    os.makedirs(work, exist_ok=True)
    profile = tempfile.mkdtemp(prefix="chromium-profile-", dir=work)
    try:
        result = subprocess.run([chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}", *args],
                                capture_output=True, text=True, timeout=timeout)
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return result.stdout, result.stderr, result.returncode


def look_at(page, work):
    """What Chromium shows of page (a file): the checks' JSON, from a copy with WATCH and CHECK added."""
    with open(page, encoding="utf-8") as f:
        text = f.read()
    text = text.replace("<head>", "<head>\n" + WATCH, 1).replace("</body>", CHECK + "\n</body>", 1)
    # A page without scripts of its own (the dashboard) forbids them all: the copy allows inline ones,
    # for the checks; every other kind of load stays as the page's policy says.
    text = re.sub(r"(Content-Security-Policy\"\s+content=\"(?:(?!script-src)[^\"])*)\"",
                  lambda m: m.group(1) + "; script-src 'unsafe-inline'\"", text, count=1)
    copy = os.path.join(os.path.dirname(page), "checked-" + os.path.basename(page))
    with open(copy, "w", encoding="utf-8") as f:
        f.write(text)
    dom, errors, status = run_chromium(["--virtual-time-budget=5000", "--dump-dom", "file://" + copy], work)
    m = re.search(r'<pre id="rt-check">(.*?)</pre>', dom, re.S)
    if not m:
        raise AssertionError(f"Chromium (exit {status}) showed no check results for {page}:\n{dom[-2000:]}\n"
                             f"Chromium's messages:\n{errors[-2000:]}")
    import html as html_
    return json.loads(html_.unescape(m.group(1)))


def screenshot(page, path, work):
    if os.path.exists(path):
        os.remove(path)     # so a screenshot of an earlier run cannot stand in for this one
    _, errors, status = run_chromium([f"--screenshot={path}", "file://" + page], work)
    if not os.path.isfile(path):
        raise AssertionError(f"Chromium (exit {status}) wrote no screenshot {path} of {page}:\n{errors[-2000:]}")
    return path


class ReportPage(ToolTest):
    """report.html from known results: what the student sees, and nothing of the hidden tests."""

    @classmethod
    def setUpClass(cls):
        cls.data, cls.results = sample_results(os.path.join(config.work, "report-sample"))
        chapters = {"ch01": {"title": "unit sphere"}, "ch02": {"title": "sphere"}, "ch03": {"title": "scene loop"}}
        cls.path = report.write(cls.data, cls.results, chapters)
        with open(cls.path, encoding="utf-8") as f:
            cls.page = f.read()

    def test_written_beside_results(self):
        self.assertEqual(os.path.dirname(self.path), os.path.dirname(self.results))
        self.assertEqual(os.path.basename(self.path), "report.html")

    def test_every_chapter_has_its_section_and_score(self):
        for cid, title, score in (("ch01", "unit sphere", "1 / 6"), ("ch02", "sphere", "0 / 1"),
                                  ("ch03", "scene loop", "5 / 5")):
            self.assertIn(f'<section class="chapter" id="{cid}">', self.page, cid)
            self.assertIn(f"<h2>{cid} {title}: {score}</h2>", self.page, f"{cid}: visible score")
        self.assertIn("Score 6 / 12", self.page, "the total counts the visible tests only")

    def test_hidden_tests_leave_no_trace(self):
        self.assertNotIn(SECRET, self.page, "a hidden test's name or text is on the page")
        self.assertNotIn("1.3", re.sub(r"data:[^\"]+", "", self.page), "a hidden test's number is on the page")

    def test_failing_test_message_as_the_student_sees_it(self):
        self.assertIn("the ray starts inside the sphere: the hit in front of the origin is the far root", self.page)
        self.assertIn("failed: ch01.public.inside the sphere", self.page)

    def test_student_text_is_escaped(self):
        self.assertNotIn("<script>alert(1)</script>", self.page)
        self.assertIn("&lt;script&gt;alert(1)&lt;/script&gt; &amp; more", self.page)

    def test_compiler_error_line_shown(self):
        self.assertIn('<div class="error-line">chapters/02-sphere/sphere.cpp:17:5: error: expected &#x27;;&#x27; '
                      "before &#x27;return&#x27;</div>", self.page)
        self.assertIn("did not build", self.page)

    def test_pictures_inlined_and_nothing_loaded_from_outside(self):
        sources = re.findall(r'src="([^"]*)"', self.page)
        self.assertEqual(len(sources), 10, "two pictures of five images each (three side by side, two in the slider)")
        for src in sources:
            self.assertTrue(src.startswith("data:image/png;base64,"), src[:60])
        self.assertNotRegex(self.page, r"(?i)(https?:|//[a-z0-9.-]+\.[a-z]{2,}/|<link|@import|url\()",
                            "the page names an outside address")
        self.assertIn("default-src 'none'", self.page, "the page's policy forbids loading")

    def test_a_render_whose_figures_were_withheld_is_not_shown(self):
        """A chapter program that also held the solutions' code: the grading withheld its figures (a picture
        could carry the course's code out), so the page withholds the picture too."""
        data, results = sample_results(os.path.join(config.work, "report-withheld"))
        render = [t for t in data["tests"] if t["name"] == "ch01.render"][0]
        render["output"] = ("the picture differs from the reference render beyond tolerance: (figures not shown: "
                            "the program also holds the course's own code of chapter 01; compare your render in "
                            "your kit with imgcmp)")
        with open(report.write(data, results), encoding="utf-8") as f:
            page = f.read()
        self.assertIn("Your render is not shown here", page)
        self.assertEqual(len(re.findall(r'src="data:image/png', page)), 5, "only chapter 03's picture is shown")
        self.assertNotIn('id="picture-ch01"', page)

    def test_gradescope_output_is_a_table_per_chapter(self):
        """results.json's top-level output in Markdown: each chapter's visible tests as a table; no hidden test."""
        from rtgrader import results
        path = os.path.join(config.work, "formatted", "results.json")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        results.write(self.data, path)
        with open(path) as f:
            written = json.load(f)
        self.assertEqual((written["output_format"], written["test_output_format"]), ("md", "text"))
        self.assertEqual(written["tests"], self.data["tests"], "the tests themselves are written as given")
        out = written["output"]
        self.assertTrue(out.startswith("Score 6 / 20."), out[:100])
        for cid, score in (("ch01", "1 / 6"), ("ch02", "0 / 1"), ("ch03", "5 / 5")):
            self.assertIn(f"**{cid}: {score}**\n\n| test | result | points |\n|---|---|---:|\n", out)
        self.assertIn("| ch01.public.inside the sphere | **failed** | 0 / 1 |", out)
        self.assertNotIn(SECRET, out, "a hidden test in the top-level output, which a student sees at once")

    def test_a_broken_input_still_gives_a_page(self):
        os.makedirs(os.path.join(config.work, "broken"), exist_ok=True)
        path = report.write({"tests": [{"name": "x"}]}, os.path.join(config.work, "broken", "results.json"))
        with open(path) as f:
            self.assertIn("could not be made", f.read())


# --- A class for the dashboard ---------------------------------------------------------------------
CH01 = os.path.join(REPO, "solutions", "01-unit-sphere", "unit_sphere.cpp")
WRONG = os.path.join(REPO, "tests", "fixtures", "wrong", "ch01")
# A correct chapter 01 written independently of the solutions: the full quadratic instead of half b,
# both roots tried in a loop, other names and comments. It shares what the exercise forces.
INDEPENDENT = """// My intersection with the unit sphere.
#include "01-unit-sphere/unit_sphere.hpp"

#include <cmath>

namespace rt::ch01 {

template <class T>
std::optional<T> intersect_unit_sphere(const ray<T>& r, const interval<T>& range) {
    const T qa = dot(r.direction, r.direction);
    if (!(qa > T(0))) return std::nullopt;          // not a ray
    const T qb = T(2) * dot(r.origin, r.direction);
    const T qc = dot(r.origin, r.origin) - T(1);
    const T d = qb * qb - T(4) * qa * qc;
    if (d >= T(0)) {                                 // NaN fails this too
        const T s = std::sqrt(d);
        const T candidates[2] = {(-qb - s) / (T(2) * qa), (-qb + s) / (T(2) * qa)};
        for (const T t : candidates)
            if (range.surrounds(t)) return t;
    }
    return std::nullopt;
}

template std::optional<float> intersect_unit_sphere(const ray<float>&, const interval<float>&);
template std::optional<double> intersect_unit_sphere(const ray<double>&, const interval<double>&);

}  // namespace rt::ch01
"""
RENAMES = {"discriminant": "disc", "half_b": "hb", "near_t": "t_near", "far_t": "t_far", "root": "sq"}


def renamed(text, style=0):
    """A copy as a student hides one: variables renamed, comments dropped, and (style 1) spacing changed."""
    for old, new in RENAMES.items():
        text = re.sub(rf"\b{old}\b", new, text)
    text = re.sub(r"//[^\n]*", "", text)
    if style:
        text = re.sub(r" = ", "=", text).replace("    ", "  ")
    return text


def with_bug(name):
    """The solutions' chapter 01 with the wrong-implementation fixture NAME's patch applied."""
    out = os.path.join(config.work, "patched", name + ".cpp")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    subprocess.run(["patch", "-s", "-o", out, CH01, os.path.join(WRONG, name, "bug.patch")], check=True, cwd=REPO)
    with open(out) as f:
        return f.read()


def must_fail(name):
    """The hidden test cases fixture NAME fails, and no other hidden one (tests/fixtures/wrong/)."""
    with open(os.path.join(WRONG, name, "expect_fail.txt")) as f:
        return [line.strip() for line in f if line.strip() and not line.startswith("#")]


class Dashboard(ToolTest):
    """grade-batch on a class of ten: the solutions, a renamed copy of them, an independent correct answer,
    three copies of one classic mistake, two of another, one of a third, and one that does not build."""

    @classmethod
    def setUpClass(cls):
        with open(CH01) as f:
            solution = f.read()
        tmin, closed, far = with_bug("ignores-tmin"), with_bug("closed-interval"), with_bug("far-root")
        cls.bugs = {"tmin-a": "ignores-tmin", "tmin-b": "ignores-tmin", "tmin-c": "ignores-tmin",
                    "closed-a": "closed-interval", "closed-b": "closed-interval", "far": "far-root"}
        cls.files = {"solution": solution, "solution-renamed": renamed(solution), "independent": INDEPENDENT,
                     "tmin-a": tmin, "tmin-b": renamed(tmin), "tmin-c": renamed(tmin, 1),
                     "closed-a": closed, "closed-b": renamed(closed, 1), "far": far,
                     "broken": solution.replace("return std::nullopt;\n}", "return std::nullopt\n}")}
        cls.folder = os.path.join(config.work, "class")
        shutil.rmtree(cls.folder, ignore_errors=True)
        for name, text in cls.files.items():
            os.makedirs(os.path.join(cls.folder, name, "chapters", "01-unit-sphere"))
            with open(os.path.join(cls.folder, name, "chapters", "01-unit-sphere", "unit_sphere.cpp"), "w") as f:
                f.write(text)
        for dirpath, _, _ in os.walk(cls.folder):
            os.chmod(dirpath, 0o755)
        cls.out = os.path.join(config.work, "class-out")
        shutil.rmtree(cls.out, ignore_errors=True)
        cls.batch = subprocess.run([sys.executable, os.path.join(REPO, "tools", "grader", "grade-batch"), cls.folder,
                                  "--out", cls.out, "--build-dir", config.build_dir, "--chapters", "01",
                                  "--jobs", "2", "--timeout", "10", "--render-timeout", "20"],
                                 capture_output=True, text=True, timeout=900)
        print(cls.batch.stdout[-3000:], cls.batch.stderr[-3000:])
        with open(os.path.join(cls.out, "dashboard.json")) as f:
            cls.data = json.load(f)

    def test_written_beside_the_scores(self):
        self.assertEqual(self.batch.returncode, 0)
        for name in ("dashboard.html", "dashboard.json", "failures.csv", "similarity.csv", "scores.csv"):
            self.assertTrue(os.path.isfile(os.path.join(self.out, name)), name)
        self.assertIn(os.path.join(self.out, "dashboard.html"), self.batch.stdout, "the summary names the page")
        for phase in ("public tests and picture", "hidden tests"):      # progress while it grades
            self.assertEqual(self.batch.stderr.count(f"grader: ch01 {phase} done ("), 9, phase)

    def test_failed_concepts_ranked_by_how_many_failed_them(self):
        """Each hidden test is counted once per submission whose mistake fails it (exactly the fixtures'
        expect_fail.txt), and the list is sorted by that count."""
        counts = {t["test"]: t["failed"] for t in self.data["tests"]}
        hidden = [name for name in counts if name.startswith("ch01.hidden.")]
        self.assertTrue(hidden, "no hidden test in the dashboard")
        expected = {}
        for name in hidden:
            case = name[len("ch01.hidden."):]
            expected[name] = sum(any(fnmatch.fnmatchcase(case, p) for p in must_fail(bug))
                                 for bug in self.bugs.values())
            self.assertEqual(counts[name], expected[name], f"{name}: failed by {counts[name]}, "
                                                           f"expected {expected[name]}")
        ranked = [t["failed"] for t in self.data["tests"]]
        self.assertEqual(ranked, sorted(ranked, reverse=True), "not sorted by failures")
        self.assertEqual(self.data["tests"][0]["failed"], max(expected.values()), "the top concept")
        tmin_only = [t for t in self.data["tests"] if t["test"].startswith("ch01.hidden.") and t["failed"] == 3]
        self.assertTrue(tmin_only and all(set(t["submissions"]) == {"tmin-a", "tmin-b", "tmin-c"} for t in tmin_only
                                          if any(fnmatch.fnmatchcase(t["test"][12:], p)
                                                 for p in must_fail("ignores-tmin"))), tmin_only)
        for t in self.data["tests"]:
            self.assertFalse({"solution", "solution-renamed", "independent"} & set(t["submissions"]),
                             f"a correct submission failed {t['test']}")

    def test_the_broken_one_is_listed_with_its_error(self):
        broken = self.data["did_not_build"]
        self.assertEqual([b["submission"] for b in broken], ["broken"])
        self.assertRegex(broken[0]["error"], r"unit_sphere\.cpp:\d+:\d+: error: expected .;.")

    def test_grading_time_of_each(self):
        times = {t["submission"]: t["seconds"] for t in self.data["grading_seconds"]}
        self.assertEqual(set(times), set(self.files))
        self.assertTrue(all(s > 0 for s in times.values()), times)

    def test_copies_listed_and_independent_answers_not(self):
        if not shutil.which("sim_c++"):
            self.skipTest("sim_c++ is not installed (optional package similarity-tester): no similar pairs looked for")
        pairs = {(p["a"], p["b"]) for p in self.data["similar_pairs"]}
        for a, b in (("solution", "solution-renamed"), ("tmin-a", "tmin-b"), ("tmin-b", "tmin-c"),
                     ("closed-a", "closed-b")):
            self.assertIn((a, b), pairs, f"the copies {a} and {b} are not listed")
        self.assertFalse([p for p in pairs if "independent" in p], f"an independent answer listed: {pairs}")
        independent = [g for g in self.data["similar_groups"] if "independent" in g]
        self.assertEqual(independent, [], "the independent answer is in a group")
        for p in self.data["similar_pairs"]:
            self.assertTrue(p["runs"], f"{p['a']} and {p['b']}: no matching lines to show")
        with open(os.path.join(self.out, "dashboard.html")) as f:
            page = f.read()
        self.assertIn("solution and solution-renamed: ch01/unit_sphere.cpp", page)
        self.assertIn("const T disc = hb * hb - a * c;", page, "the copy's matching lines are not shown")


class Browser(ToolTest):
    """report.html (and dashboard.html, when Dashboard made one) as a person sees them in Chromium."""

    def setUp(self):
        if not chromium():
            self.skipTest("chromium is not installed (optional: tools/setup installs it): the pages were not "
                          "looked at in a browser")

    def check_page(self, page, sections):
        seen = look_at(page, config.work)
        self.assertEqual(seen["sections"], sections, "the chapters' sections")
        self.assertTrue(seen["images"] or seen["drawings"], "no image on the page")
        for size in seen["drawings"]:
            self.assertTrue(min(size) > 0, f"a drawing shown with no size: {size}")
        for img in seen["images"]:
            with self.subTest(image=img["alt"]):
                self.assertTrue(img["complete"] and min(img["natural"]) > 0, f"did not decode: {img}")
                self.assertTrue(min(img["shown"]) > 0, f"shown with no size: {img}")
        self.assertEqual(seen["loads"], [], "the page loaded something from an address")
        self.assertEqual(seen["refused"], [], "the page tried to load something from an address")
        return seen

    def test_report_page(self):
        data, results = sample_results(os.path.join(config.work, "browser-sample"))
        page = report.write(data, results, {"ch01": {"title": "unit sphere"}})
        seen = self.check_page(page, ["ch01", "ch02", "ch03"])
        self.assertEqual(len(seen["images"]), 10)
        self.assertEqual(seen["sliders"], [{"left_at_100": "over", "left_at_0": "under"}] * 2,
                         "the slider does not change which picture shows")
        shot = screenshot(page, os.path.join(config.work, "report-sample.png"), config.work)
        with open(shot, "rb") as f:
            head = f.read(24)
        self.assertEqual(struct.unpack(">II", head[16:24]), (1280, 800), "screenshot size")

    def test_compare_page_of_a_chapter_program(self):
        """--compare writes the same kind of page for one picture (common/picture_page.html)."""
        self.assertTrue(config.program, "give --program, a chapter program of this build")
        folder = os.path.join(config.work, "compare")
        shutil.rmtree(folder, ignore_errors=True)
        reference = os.path.join(REPO, "chapters", "03-scene-loop", "reference.png")
        run = subprocess.run([config.program, "--out", os.path.join(folder, "mine.png"), "--compare", reference],
                             capture_output=True, text=True, timeout=120)
        page = os.path.join(folder, "mine-compare.html")
        self.assertIn(f"comparison page (reference, render, difference): {page}", run.stdout)
        seen = self.check_page_of(page)
        self.assertEqual(len(seen["images"]), 5, "reference, render, difference, and the slider's two")
        self.assertEqual(seen["sliders"], [{"left_at_100": "over", "left_at_0": "under"}])

    def check_page_of(self, page):
        seen = look_at(page, config.work)
        for img in seen["images"]:
            self.assertTrue(img["complete"] and min(img["natural"]) > 0 and min(img["shown"]) > 0, img)
        self.assertEqual(seen["loads"] + seen["refused"], [], "the page loads from an address")
        return seen

    def test_a_page_that_loads_from_outside_is_caught(self):
        """The check itself: an image from an address, in a page without the policy, is reported."""
        folder = os.path.join(config.work, "outside")
        os.makedirs(folder, exist_ok=True)
        page = os.path.join(folder, "outside.html")
        with open(page, "w") as f:
            f.write('<!DOCTYPE html><html><head><title>x</title></head><body><section class="chapter" id="ch01">'
                    '<img alt="a" src="http://example.invalid/a.png"></section></body></html>')
        seen = look_at(page, config.work)
        self.assertTrue(seen["loads"] or seen["refused"], f"an outside image went unnoticed: {seen}")



class DashboardBrowser(Browser):
    """dashboard.html of the class Dashboard graded, as the instructor sees it in Chromium."""

    def test_dashboard_page(self):
        page = os.path.join(config.work, "class-out", "dashboard.html")
        self.assertTrue(os.path.isfile(page), f"{page} is missing: grader.dashboard makes it")
        seen = self.check_page(page, ["scores", "tests", "did-not-build", "times", "similar"])
        self.assertEqual(len(seen["drawings"]), 1, "one histogram (chapter 01)")
        screenshot(page, os.path.join(config.work, "dashboard.png"), config.work)

    def test_a_students_report_page(self):
        """The report.html grade-batch wrote for one student of the class (the far root: the picture differs)."""
        page = os.path.join(config.work, "class-out", "far", "report.html")
        seen = self.check_page(page, ["ch01"])
        self.assertEqual(len(seen["images"]), 5, "reference, render, difference and the slider's two")
        self.assertEqual(seen["sliders"], [{"left_at_100": "over", "left_at_0": "under"}])
        screenshot(page, os.path.join(config.work, "report.png"), config.work)


if __name__ == "__main__":
    if any(a.endswith("Browser") for a in sys.argv) and not chromium():
        print("SKIPPED: chromium is not installed (optional; tools/setup installs it): "
              "the pages were not looked at in a browser")
        sys.exit(77)      # ctest's SKIP_RETURN_CODE
    main()
