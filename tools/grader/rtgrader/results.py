"""results.json in Gradescope's schema, and the summary printed on the terminal.

The file is written atomically (a temporary file, then a rename), so it is
always complete, valid JSON, whatever happened while grading."""

import json
import os
import re

from . import fsutil, report


def gradescope(results, notes, elapsed, chapters):
    tests = []
    index = {}
    for r in results:
        number = chapters[r.chapter]["number"] if r.chapter in chapters else "00"
        index[r.chapter] = index.get(r.chapter, 0) + 1
        score = r.points if r.passed else 0
        tests.append({
            "name": r.name,
            "number": f"{int(number)}.{index[r.chapter]}",
            "score": score,
            "max_score": r.points,
            "status": "passed" if r.passed else "failed",
            "output": r.output,
            "tags": [r.chapter, r.kind],
            "visibility": r.visibility,
        })
    # Before publication a student sees the visible tests only, so everything at the top counts only
    # them. Gradescope takes a top-level "score" as the total, shown to the student at once: it is
    # written only when every test is visible (a preview); otherwise Gradescope adds the tests' scores
    # itself and, while some are hidden, does not show the student the total (README, "Gradescope").
    visible = [t for t in tests if t["visibility"] == "visible"]
    score = sum(t["score"] for t in visible)
    total = sum(t["max_score"] for t in visible)
    withheld = len(tests) - len(visible)
    head = f"Score {score:g} / {total:g}" + (f" on the tests shown now; {withheld} more tests are shown when "
                                             "grades are published." if withheld else ".")
    data = {
        "execution_time": shown_seconds(elapsed),
        "output": "\n".join([head] + [f"Note: {n}" for n in notes]),
        "stdout_visibility": "hidden",
        "tests": tests,
    }
    if not withheld:
        data = {"score": score, **data}
    return data


SECONDS_STEP = 5


def shown_seconds(elapsed):
    """execution_time as results.json gives it: the visible phase's time (the caller's), rounded up to
    SECONDS_STEP seconds."""
    return int(-(-max(0.0, elapsed) // SECONDS_STEP) * SECONDS_STEP)


def total_score(data):
    """The points of every test (hidden ones too): what Gradescope counts once grades are published."""
    return sum(t["score"] for t in data["tests"])


def failure(message, elapsed=0.0):
    """The results file when grading could not even start."""
    return {"score": 0, "execution_time": shown_seconds(elapsed), "output": message,
            "stdout_visibility": "hidden",
            "tests": [{"name": "grader", "number": "0.1", "score": 0, "max_score": 0, "status": "failed",
                       "output": message, "tags": ["grader"], "visibility": "visible"}]}


def write(data, path):
    """Atomically, never through a link planted in the folder (fsutil.write_atomic)."""
    data = report.gradescope_formatted(data)      # Markdown tables at the top (Gradescope's "output_format")
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    # As root, for root only: a sandbox user (fallback mode) must not read another submission's results.
    mode = 0o600 if os.geteuid() == 0 else 0o644
    fsutil.write_atomic(path, (json.dumps(data, indent=2) + "\n").encode(), mode)


def summary(data, chapters, path=None):
    """A readable summary: one line per chapter, then what failed."""
    out = []
    by_chapter = {}
    for t in data["tests"]:
        by_chapter.setdefault(t["tags"][0], []).append(t)
    for cid, tests in by_chapter.items():
        title = chapters.get(cid, {}).get("title", "")
        score = sum(t["score"] for t in tests)
        total = sum(t["max_score"] for t in tests)
        parts = []     # the instructor's terminal, or the student's own preview (no hidden tests): all of it
        for kind in ("public", "hidden", "render"):
            mine = [t for t in tests if t["tags"][1] == kind]
            if mine:
                parts.append(f"{kind} {sum(t['status'] == 'passed' for t in mine)}/{len(mine)}")
        compiled = not any(t["tags"][1] == "compilation" for t in tests)
        out.append(f"{cid} {title:<22} {score:>6g} / {total:<6g} "
                   + (", ".join(parts) if compiled else "DID NOT BUILD"))
        failed = [t for t in tests if t["status"] != "passed" and (compiled or t["tags"][1] == "compilation")]
        for t in failed[:8]:
            headline, explanation = _why(t["output"])
            if t["tags"][1] == "compilation":
                # The compiler's first error, which _why would drop as one of doctest's location lines.
                first = next((line.strip() for line in t["output"].splitlines()
                              if re.search(r"\berror\b", line)), "")
                explanation = [first] if first and first != headline else explanation[:1]
            out.append(f"    failed: {t['name']}: {headline[:150]}")
            out += [f"        {line[:200]}" for line in explanation]
        if len(failed) > 8:
            out.append(f"    ... and {len(failed) - 8} more failed (see the results file)")
    out.append(data["output"])
    if "score" not in data:     # for the instructor: what Gradescope will count once grades are published
        out.append(f"With the hidden tests: {total_score(data):g} / {sum(t['max_score'] for t in data['tests']):g}.")
    out.append(f"({data['execution_time']} s)" + (f" -> {path}" if path else ""))
    return terminal_safe("\n".join(out))


def _why(output):
    """What the terminal shows of a failed test: its first telling line, then
    the explanation results.json holds (the checks' teaching messages, the
    picture's figures and where its files are), a few lines of it."""
    lines = [line.strip() for line in output.splitlines() if line.strip()]
    telling = [line for line in lines if "ERROR:" in line or "exception" in line]
    headline = (telling or lines or [""])[0]
    rest = lines[lines.index(headline) + 1:] if headline in lines else []
    headline = headline.split("ERROR:", 1)[-1].strip()
    # doctest's own lines say where and which expression: the messages say why.
    explanation = [line.split("logged:", 1)[-1].strip() if line.startswith("logged:") else line for line in rest
                   if not line.startswith(("values:", "TEST CASE:", "CHECK", "REQUIRE")) and
                   not re.match(r"^\S+\.(cpp|hpp):\d+:", line)]
    seen = []
    for line in explanation:
        if line not in seen and line != headline:
            seen.append(line)
    return headline, seen[:4]


def terminal_safe(text):
    """A student's text as the instructor's terminal should show it: control
    characters (escape sequences could rewrite the screen or the title) as \\xNN."""
    return re.sub(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]", lambda m: f"\\x{ord(m.group()):02x}", text)
