"""dashboard.html: a class's grading at a glance, for the instructor (tools/grader/grade-batch).

From every submission's results (the data written to its results.json, hidden tests included:
this page is the instructor's), the time its grading took, and its exercise files:

- the distribution of scores per chapter;
- every test sorted by how many submissions failed it, with the message they saw (the concepts
  the class is missing); a chapter that did not build is counted apart, not as failed tests;
- the submissions that did not build, with the compiler's first error;
- the grading time per submission;
- pairs of submissions whose exercise files are similar, found by Debian's similarity tester
  (sim_c++, package similarity-tester, optional), with the matching lines side by side. Lines of
  the course's own stub and header are blanked before comparing (every student starts from them),
  so two independent answers share only what the exercise forces. A list for a person to read,
  never a verdict.

The same data goes to dashboard.json, failures.csv and similarity.csv beside it.
"""

import csv
import html
import io
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import tempfile
import time

from . import fsutil
from .report import first_compiler_error

SIM = "sim_c++"
SIMILAR_PERCENT = 50          # a pair is listed when one file consists for this much of the other
PAIRS_SHOWN = 40              # on the page; the CSV and JSON hold every pair
SIM_SECONDS = 120
SIM_MEMORY = 1024 * 1024 * 1024
_SIM_PERCENT = re.compile(r"^(.+?) consists for (\d+) % of (.+?) material$")
_SIM_RUN = re.compile(r"^(.+?): line (\d+)-(\d+)\s*\|(.+?): line (\d+)-(\d+)\s*\[(\d+)\]$")


def timed(function, seconds):
    """function, recording how long each call took in seconds[its first argument]."""
    def call(key):
        start = time.monotonic()
        try:
            return function(key)
        finally:
            seconds[key] = time.monotonic() - start
    return call


# --- the exercise files ---------------------------------------------------------------------------
def exercise_files(submission, chapters, chapter_ids):
    """{"chNN/FILE": bytes} of one submission, read as the grader reads them (no link followed)."""
    from .grading import find_exercise
    files = {}
    for cid in chapter_ids:
        ch = chapters[cid]
        for ex in ch.get("exercises", []):
            data, _ = find_exercise(submission, ch, ex)
            if data is not None:
                files[f"{cid}/{ex}"] = data
    return files


def course_lines(source, chapters, chapter_ids):
    """{"chNN/FILE": set of stripped lines} every student is given: the chapter's stub and headers."""
    given = {}
    for cid in chapter_ids:
        ch = chapters[cid]
        folder = os.path.join(source, "chapters", ch["folder"])
        lines = set()
        for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            if name.endswith(".hpp") or name in ch.get("exercises", []):
                with open(os.path.join(folder, name), encoding="utf-8", errors="replace") as f:
                    lines |= {line.strip() for line in f if line.strip()}
        for ex in ch.get("exercises", []):
            given[f"{cid}/{ex}"] = lines
    return given


def _blank_given(text, given):
    """text with every line the course gave blanked (line numbers kept)."""
    return "\n".join("" if line.strip() in given else line for line in text.split("\n"))


def _limits():
    resource.setrlimit(resource.RLIMIT_CPU, (SIM_SECONDS, SIM_SECONDS))
    resource.setrlimit(resource.RLIMIT_AS, (SIM_MEMORY, SIM_MEMORY))


def _sim(args, cwd):
    """sim_c++'s output (it reads files the grader wrote: students' text, capped at 1 MiB each)."""
    run = subprocess.run([SIM, *args], cwd=cwd, capture_output=True, text=True, errors="replace",
                         timeout=SIM_SECONDS, preexec_fn=_limits)
    return run.stdout


def similar_pairs(sources, given, threshold=SIMILAR_PERCENT):
    """Pairs of submissions whose same exercise file is similar, most similar first:
    [{"file", "a", "b", "percent", "runs": [{"a_lines": [first, last], "b_lines": [...], "tokens"}]}],
    or None when sim_c++ is not installed. sources: {submission: {"chNN/FILE": bytes}}."""
    if not shutil.which(SIM):
        return None
    pairs = []
    work = tempfile.mkdtemp(prefix="rt-similar-")
    try:
        for key in sorted({k for files in sources.values() for k in files}):
            who = sorted(name for name, files in sources.items() if key in files)
            if len(who) < 2:
                continue
            folder = os.path.join(work, key.replace("/", "_"))
            os.makedirs(folder)
            names = {}
            for i, name in enumerate(who):
                text = sources[name][key].decode("utf-8", errors="replace")
                local = f"s{i}.cpp"        # sim never sees a name the student chose
                with open(os.path.join(folder, local), "w", encoding="utf-8") as f:
                    f.write(_blank_given(text, given.get(key, set())))
                names[local] = name
            best = {}
            for line in _sim(["-p", "-e", "-s", "-t1", *names], folder).splitlines():
                m = _SIM_PERCENT.match(line.strip())
                if m and m.group(1) in names and m.group(3) in names:
                    pair = tuple(sorted((names[m.group(1)], names[m.group(3)])))
                    best[pair] = max(best.get(pair, 0), int(m.group(2)))
            for (a, b), percent in best.items():
                if percent < threshold:
                    continue
                local = {v: k for k, v in names.items()}
                runs = []
                for line in _sim(["-n", "-T", "-s", local[a], local[b]], folder).splitlines():
                    m = _SIM_RUN.match(line.strip())
                    if m and {m.group(1).strip(), m.group(4).strip()} == {local[a], local[b]}:
                        first = (int(m.group(2)), int(m.group(3)))
                        second = (int(m.group(5)), int(m.group(6)))
                        if m.group(1).strip() != local[a]:
                            first, second = second, first
                        runs.append({"a_lines": list(first), "b_lines": list(second), "tokens": int(m.group(7))})
                pairs.append({"file": key, "a": a, "b": b, "percent": percent, "runs": runs})
    finally:
        shutil.rmtree(work, ignore_errors=True)
    pairs.sort(key=lambda p: (-p["percent"], p["file"], p["a"], p["b"]))
    return pairs


# --- the class's results ----------------------------------------------------------------------------
def _message(output):
    """The first telling line of what a student saw for a failed test."""
    lines = [line.strip() for line in output.splitlines() if line.strip()]
    for line in lines:
        if line.startswith("logged:"):
            return line[len("logged:"):].strip()
    for line in lines:
        if "ERROR:" in line:
            return line.split("ERROR:", 1)[1].strip()
    return lines[0] if lines else ""


def summarise(graded, seconds, chapter_ids):
    """The dashboard's data from [(submission, results data)] and {submission: grading seconds}."""
    chapters = {cid: [] for cid in chapter_ids}
    tests = {}
    broken = []
    for name, data in graded:
        per = {}
        for t in data.get("tests", []):
            per.setdefault(t["tags"][0], []).append(t)
        for cid, mine in per.items():
            total = sum(t["max_score"] for t in mine)
            if cid in chapters:
                chapters[cid].append({"submission": name, "score": sum(t["score"] for t in mine), "max": total})
            compilation = [t for t in mine if t["tags"][1:2] == ["compilation"]]
            if compilation:
                broken.append({"submission": name, "chapter": cid,
                               "error": first_compiler_error(compilation[0]["output"]) or
                               _message(compilation[0]["output"])})
                continue
            for t in mine:
                entry = tests.setdefault(t["name"], {"test": t["name"], "chapter": cid, "kind": t["tags"][1],
                                                     "visibility": t.get("visibility", ""), "failed": 0,
                                                     "graded": 0, "submissions": [], "messages": {}})
                entry["graded"] += 1
                if t["status"] != "passed":
                    entry["failed"] += 1
                    entry["submissions"].append(name)
                    message = _message(t["output"])
                    entry["messages"][message] = entry["messages"].get(message, 0) + 1
    ranked = sorted(tests.values(), key=lambda e: (-e["failed"], e["chapter"], e["test"]))
    for e in ranked:
        e["messages"] = sorted(e["messages"].items(), key=lambda kv: -kv[1])
    times = sorted(({"submission": name, "seconds": round(seconds.get(name, 0.0), 1)} for name, _ in graded),
                   key=lambda r: -r["seconds"])
    return {"submissions": len(graded), "chapters": chapters, "tests": ranked, "did_not_build": broken,
            "grading_seconds": times}


# --- the page -------------------------------------------------------------------------------------------
STYLE = """
body { font: 15px/1.45 system-ui, sans-serif; color: #1d1d1f; background: #fafafa; margin: 0 auto;
       max-width: 1220px; padding: 12px 20px 40px; }
h1 { font-size: 22px; margin: 8px 0; } h2 { font-size: 18px; margin: 26px 0 8px; border-top: 1px solid #ccc;
padding-top: 6px; }
table { border-collapse: collapse; margin: 6px 0 12px; } th, td { border: 1px solid #ccc; padding: 3px 8px;
text-align: left; vertical-align: top; } th { background: #eee; } td.num { text-align: right;
font-variant-numeric: tabular-nums; } .note { color: #555; } .bar { background: #4a78c2; height: 12px; }
pre { margin: 0; font-size: 12px; white-space: pre-wrap; word-break: break-word; }
td.code { font-family: monospace; font-size: 12px; white-space: pre-wrap; background: #fff; }
section.pair { margin-bottom: 18px; } svg text { font: 11px system-ui, sans-serif; }
"""


def _histogram(rows, bins=10):
    """An inline SVG histogram of score fractions (0 to 1) in `bins` bins, the last closed."""
    counts = [0] * bins
    for r in rows:
        f = r["score"] / r["max"] if r["max"] else 0.0
        counts[min(bins - 1, int(f * bins))] += 1
    top = max(counts) or 1
    w, h, pad = 28, 90, 16
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{bins * w + 10}" height="{h + 2 * pad}" '
             f'role="img" aria-label="scores">']
    for i, c in enumerate(counts):
        bar = round((h - 4) * c / top)
        parts.append(f'<rect x="{5 + i * w}" y="{pad + h - bar}" width="{w - 4}" height="{bar}" fill="#4a78c2"/>'
                     f'<text x="{5 + i * w + (w - 4) / 2}" y="{pad + h - bar - 3}" text-anchor="middle">'
                     f'{c or ""}</text><text x="{5 + i * w + (w - 4) / 2}" y="{pad + h + 12}" '
                     f'text-anchor="middle">{i * 100 // bins}</text>')
    parts.append("</svg>")
    return "".join(parts)


def _lines(text, first, last):
    lines = text.split("\n")
    return "\n".join(lines[first - 1:last])


def build(summary, pairs, sources, title="Class dashboard"):
    e = html.escape
    out = [f"<h1>{e(title)}</h1>", f'<p>{summary["submissions"]} submissions graded. '
           '<span class="note">The same data: dashboard.json, failures.csv, similarity.csv, scores.csv.</span></p>']
    out.append('<section id="scores"><h2>Scores per chapter</h2><table><tr><th>chapter</th><th>distribution '
               '(submissions by % of its points; the last bar: 90-100)</th><th>median</th><th>mean</th><th>full marks</th></tr>')
    for cid, rows in summary["chapters"].items():
        if not rows:
            continue
        fractions = [r["score"] / r["max"] if r["max"] else 0 for r in rows]
        full = sum(r["score"] == r["max"] for r in rows)
        out.append(f'<tr><td>{e(cid)}</td><td>{_histogram(rows)}</td><td class="num">'
                   f'{100 * statistics.median(fractions):.0f}%</td><td class="num">'
                   f'{100 * statistics.mean(fractions):.0f}%</td><td class="num">{full} of {len(rows)}</td></tr>')
    out.append("</table></section>")
    out.append('<section id="tests"><h2>Tests by how many submissions failed them</h2><p class="note">Among the '
               'submissions whose chapter built. The message is what the students saw (hidden tests: '
               'the concept).</p><table><tr><th>failed</th><th>test</th><th>kind</th><th>what they saw</th></tr>')
    for t in summary["tests"]:
        if not t["failed"]:
            continue
        said = "<br>".join(f"{e(m)} <span class=\"note\">({n})</span>" for m, n in t["messages"][:3])
        out.append(f'<tr><td class="num">{t["failed"]} of {t["graded"]}</td><td>{e(t["test"])}</td>'
                   f'<td>{e(t["kind"])}</td><td>{said}</td></tr>')
    passed = sum(1 for t in summary["tests"] if not t["failed"])
    out.append(f'</table><p class="note">{passed} tests were passed by every submission graded on them.</p>'
               "</section>")
    out.append('<section id="did-not-build"><h2>Submissions that did not build</h2>')
    if summary["did_not_build"]:
        out.append("<table><tr><th>submission</th><th>chapter</th><th>first error</th></tr>" + "".join(
            f'<tr><td>{e(b["submission"])}</td><td>{e(b["chapter"])}</td><td class="code">{e(b["error"])}</td></tr>'
            for b in summary["did_not_build"]) + "</table>")
    else:
        out.append("<p>Every chapter of every submission built.</p>")
    out.append("</section>")
    times = summary["grading_seconds"]
    longest = max([t["seconds"] for t in times] + [1e-9])
    out.append('<section id="times"><h2>Grading time per submission</h2><table><tr><th>submission</th>'
               '<th>seconds</th><th></th></tr>' + "".join(
                   f'<tr><td>{e(t["submission"])}</td><td class="num">{t["seconds"]:.1f}</td><td style="width:300px">'
                   f'<div class="bar" style="width:{100 * t["seconds"] / longest:.0f}%"></div></td></tr>'
                   for t in times) + "</table></section>")
    out.append('<section id="similar"><h2>Similar exercise files</h2>')
    if pairs is None:
        out.append("<p>Not looked for: sim_c++ (Debian package similarity-tester) is not installed.</p>")
    else:
        out.append(f'<p class="note">Pairs whose same exercise file is at least {SIMILAR_PERCENT}% the other\'s '
                   "material by Debian's similarity tester (sim_c++: tokens, so renamed variables and moved "
                   "whitespace still match), after blanking the lines of the course's stub and header. "
                   "A list for a person to read, never a verdict: short exercises leave little room to differ."
                   "</p>")
        if not pairs:
            out.append("<p>No pair above the threshold.</p>")
        else:
            out.append("<p>Groups (each member similar to at least one other): " + "; ".join(
                "{" + ", ".join(e(x) for x in g) + "}" for g in groups(pairs)) + "</p>")
        if len(pairs) > PAIRS_SHOWN:
            out.append(f'<p class="note">The {PAIRS_SHOWN} most similar pairs of {len(pairs)} are shown; '
                       "similarity.csv and dashboard.json list them all.</p>")
        for p in pairs[:PAIRS_SHOWN]:
            a_text = sources[p["a"]][p["file"]].decode("utf-8", errors="replace")
            b_text = sources[p["b"]][p["file"]].decode("utf-8", errors="replace")
            out.append(f'<section class="pair"><h3>{e(p["a"])} and {e(p["b"])}: {e(p["file"])}, {p["percent"]}%'
                       "</h3><table><tr>"
                       f'<th>{e(p["a"])}</th><th>{e(p["b"])}</th></tr>')
            for r in p["runs"][:6]:
                out.append(f'<tr><td class="code">lines {r["a_lines"][0]}-{r["a_lines"][1]}\n'
                           f'{e(_lines(a_text, *r["a_lines"]))}</td><td class="code">lines {r["b_lines"][0]}-'
                           f'{r["b_lines"][1]}\n{e(_lines(b_text, *r["b_lines"]))}</td></tr>')
            out.append("</table></section>")
    out.append("</section>")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
            "style-src 'unsafe-inline'\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{e(title)}</title><style>{STYLE}</style></head><body>\n" + "\n".join(out) + "\n</body></html>\n")


def groups(pairs):
    """The similar pairs joined into groups (connected components), largest first: [[submission, ...]]."""
    parent = {}

    def root(x):
        while parent.setdefault(x, x) != x:
            x = parent[x]
        return x
    for p in pairs or []:
        parent[root(p["a"])] = root(p["b"])
    found = {}
    for x in list(parent):
        found.setdefault(root(x), []).append(x)
    return sorted((sorted(g) for g in found.values()), key=lambda g: (-len(g), g))


def _csv(rows, header):
    table = io.StringIO()
    w = csv.writer(table)
    w.writerow(header)
    w.writerows(rows)
    return table.getvalue().encode()


def write(out_dir, graded, seconds, sources, given, chapter_ids):
    """Writes dashboard.html, dashboard.json, failures.csv and similarity.csv into out_dir; returns the page."""
    summary = summarise(graded, seconds, chapter_ids)
    try:
        pairs = similar_pairs(sources, given)
    except (OSError, subprocess.SubprocessError) as err:
        pairs, summary["similarity_error"] = None, str(err)
    mode = 0o600 if os.geteuid() == 0 else 0o644
    fsutil.write_atomic(os.path.join(out_dir, "dashboard.json"),
                        (json.dumps({**summary, "similar_pairs": pairs, "similar_groups": groups(pairs)},
                                    indent=1) + "\n").encode(), mode)
    fsutil.write_atomic(os.path.join(out_dir, "failures.csv"), _csv(
        [[t["test"], t["chapter"], t["kind"], t["failed"], t["graded"], t["messages"][0][0] if t["messages"] else "",
          " ".join(t["submissions"])] for t in summary["tests"]],
        ["test", "chapter", "kind", "failed", "graded", "message", "submissions"]), mode)
    fsutil.write_atomic(os.path.join(out_dir, "similarity.csv"), _csv(
        [[p["file"], p["a"], p["b"], p["percent"], len(p["runs"])] for p in pairs or []],
        ["file", "a", "b", "percent", "matching_runs"]), mode)
    page = os.path.join(out_dir, "dashboard.html")
    fsutil.write_atomic(page, build(summary, pairs, sources).encode("utf-8"), mode)
    return page


def for_batch(out_dir, graded, seconds, folder, tree_, chapter_ids):
    """grade-batch's dashboard: graded [(submission, data)] of the sub-folders of folder, graded with tree_."""
    chapters = tree_.chapters()
    sources = {name: exercise_files(os.path.join(folder, name), chapters, chapter_ids) for name, _ in graded}
    return write(out_dir, graded, seconds, sources, course_lines(tree_.source, chapters, chapter_ids), chapter_ids)
