"""report.html: what one grading (or a kit's preview) gives the student, as a page.

Built only from the results data written to results.json and the pictures in the renders/
folder beside it, so the page can never show more than results.json's visible part: tests
whose visibility is not "visible" (the hidden ones, after_published) are left out entirely,
scores included, as Gradescope shows them before publication.

One self-contained file: every picture is inlined as a data: URI, and the page's template
(common/picture_page.html, shared with the chapter programs' --compare) forbids loading
anything else. Without JavaScript everything is readable; the script only moves the slider
between the reference and the student's render.
"""

import base64
import html
import os
import re

from . import fsutil

TEMPLATE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "common",
                        "picture_page.html")
PICTURE_BYTES = 16 * 1024 * 1024        # a picture larger than this is not inlined
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
_COMPILER_ERROR = re.compile(r"^(\S+?):(\d+):(?:(\d+):)? (?:fatal )?error: .*$", re.M)
WITHHELD = "(figures not shown:"        # grading.py's words when a render's figures are withheld
_PLACEHOLDER = re.compile(r"\{\{(\w+)\}\}")


def template(path=TEMPLATE):
    """(page, picture block) of the shared template: the page without the block, and the block."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    start, end = "<!-- picture -->\n", "<!-- /picture -->\n"
    a, b = text.index(start), text.index(end)
    return text[:a] + text[b + len(end):], text[a + len(start):b]


def fill(text, values, raw=()):
    """text with each {{name}} replaced by values[name], HTML-escaped unless name is in raw."""
    def one(m):
        value = str(values.get(m.group(1), ""))
        return value if m.group(1) in raw else html.escape(value)
    return _PLACEHOLDER.sub(one, text)


def png_data_uri(data):
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def missing_picture_uri(why):
    """A grey box saying why a picture is missing (an SVG data: URI)."""
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><rect width="400" height="300" '
           f'fill="#ddd"/><text x="200" y="150" text-anchor="middle" font-size="16">{html.escape(why)}</text></svg>')
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode("ascii")


def _read_png(path):
    """The bytes of a PNG file the grader wrote (or the course's reference), or None."""
    try:
        data = fsutil.read_regular(path, PICTURE_BYTES)
    except (OSError, fsutil.Refused):
        return None
    return data if data.startswith(PNG_MAGIC) else None


def picture_block(block, cid, caption, reference, render, diff):
    """The template's picture block for one picture (each image: PNG bytes, or None when absent)."""
    return fill(block, {
        "id": cid, "caption": caption,
        "reference": png_data_uri(reference) if reference else missing_picture_uri("no reference picture"),
        "render": png_data_uri(render) if render else missing_picture_uri("no render"),
        "diff": png_data_uri(diff) if diff else missing_picture_uri("no difference image"),
        "diff_label": "difference (red: past tolerance)" if diff else "difference: none"})


def visible(tests):
    """The tests a student sees before publication."""
    return [t for t in tests if t.get("visibility", "visible") == "visible"]


def _chapter_number(test):
    number = str(test.get("number", "")).split(".")[0]
    return number.zfill(2) if number.isdigit() else ""


def _points(tests):
    return sum(t["score"] for t in tests), sum(t["max_score"] for t in tests)


def _fmt(x):
    return f"{x:g}"


def first_compiler_error(message):
    """The compiler's first error line ("file:line:col: error: ...") of a compilation entry, or ''."""
    m = _COMPILER_ERROR.search(message)
    return m.group(0) if m else ""


def _pre(text):
    return f"<pre>{html.escape(text)}</pre>"


def _chapter_section(cid, title, tests, renders, references, block):
    score, total = _points(tests)
    out = [f'<section class="chapter" id="{html.escape(cid)}">',
           f"<h2>{html.escape(cid)} {html.escape(title)}: {_fmt(score)} / {_fmt(total)}</h2>"]
    compilation = [t for t in tests if t["tags"][1:2] == ["compilation"]]
    for t in compilation:
        out.append('<p class="fail">This chapter did not build, so none of its tests ran.</p>')
        line = first_compiler_error(t["output"])
        if line:
            out.append(f'<div class="error-line">{html.escape(line)}</div>')
        out.append(_pre(t["output"]))
    others = [t for t in tests if t not in compilation]
    failed = [t for t in others if t["status"] != "passed"]
    passed = [t for t in others if t["status"] == "passed"]
    render = renders_of(cid, renders)
    render_test = [t for t in others if t["tags"][1:2] == ["render"]]
    withheld = render_test and WITHHELD in render_test[0]["output"]
    if withheld:
        # The grading's policy, read from what it wrote: a program that also held the course's own code
        # (earlier chapters from the solutions) had its figures withheld; its picture could carry more.
        out.append('<p class="note">Your render is not shown here: this chapter\'s program also held the course\'s '
                   "own code of earlier chapters. Compare your picture in your kit (--compare).</p>")
    elif render_test and render:
        lines = render_test[0]["output"].strip().splitlines()
        caption = lines[0] if lines else ""
        reference = _read_png(os.path.join(renders, f"{cid}.reference.png")) or \
            (_read_png(references[cid]) if references.get(cid) else None)
        out.append(picture_block(block, cid, caption, reference, render,
                                 _read_png(os.path.join(renders, f"{cid}.diff.png"))))
    if compilation and failed:
        out.append(f'<p class="note">{len(failed)} tests were not graded because the chapter did not build.</p>')
    else:
        for t in failed:
            kind = t["tags"][1] if len(t["tags"]) > 1 else ""
            points = _fmt(t["max_score"]) + (" point" if t["max_score"] == 1 else " points")
            out.append(f'<h3 class="fail">failed: {html.escape(t["name"])} '
                       f'<span class="note">({html.escape(kind)}, {points})</span></h3>')
            out.append(_pre(t["output"]))
    if passed:
        out.append(f"<details><summary>{len(passed)} passed</summary><ul>"
                   + "".join(f'<li class="pass">{html.escape(t["name"])}</li>' for t in passed) + "</ul></details>")
    out.append("</section>")
    return "\n".join(out)


def renders_of(cid, renders):
    """The student's render of a chapter, from the renders folder, or None."""
    return _read_png(os.path.join(renders, f"{cid}.png")) if renders else None


def build(data, renders=None, titles=None, references=None, title="Your results"):
    """The page for one results.json (its data) and the renders folder beside it.
    titles: {chapter id: title}; references: {chapter id: reference.png} (the course's own
    pictures, used where the renders folder holds no chNN.reference.png)."""
    page, block = template()
    titles, references = titles or {}, references or {}
    tests = visible(data.get("tests", []))
    chapters = {}
    for t in tests:
        chapters.setdefault(t["tags"][0] if t.get("tags") else "grader", []).append(t)
    score, total = _points(tests)
    head = [f"<p><b>Score {_fmt(score)} / {_fmt(total)}</b> "
            f'<span class="note">(the tests you can see now; hidden tests are shown after grades are '
            f"published)</span></p>"]
    rows = []
    for cid, mine in chapters.items():
        s, m = _points(mine)
        built = not any(t["tags"][1:2] == ["compilation"] for t in mine)
        public = [t for t in mine if t["tags"][1:2] == ["public"]]
        render = [t for t in mine if t["tags"][1:2] == ["render"]]
        status = (f"{sum(t['status'] == 'passed' for t in public)}/{len(public)} passed" if built else
                  '<span class="fail">did not build</span>')
        picture = ("" if not render or not built else '<span class="pass">matches</span>'
                   if render[0]["status"] == "passed" else '<span class="fail">differs</span>')
        name = titles.get(cid, "")
        rows.append(f'<tr><td><a href="#{html.escape(cid)}">{html.escape(cid)}</a> {html.escape(name)}</td>'
                    f'<td class="num">{_fmt(s)} / {_fmt(m)}</td><td>{status}</td><td>{picture}</td></tr>')
    head.append("<table><tr><th>chapter</th><th>score</th><th>tests</th><th>picture</th></tr>"
                + "".join(rows) + "</table>")
    if data.get("output"):
        head.append("<details><summary>notes from the grader</summary>" + _pre(data["output"]) + "</details>")
    sections = [_chapter_section(cid, titles.get(cid, ""), mine, renders, references, block)
                for cid, mine in chapters.items()]
    return fill(page, {"title": title, "content": "\n".join(head + sections)}, raw=("content",))


def write(data, results_path, chapters=None, title="Your results"):
    """Writes report.html beside results_path (from data, the results written there, and the renders
    folder beside it); returns its path. chapters: the tree's chapter descriptions (titles and
    the course's reference pictures only)."""
    folder = os.path.dirname(os.path.abspath(results_path))
    chapters = chapters or {}
    titles = {cid: ch.get("title", "") for cid, ch in chapters.items()}
    references = {cid: ch["reference"] for cid, ch in chapters.items() if ch.get("reference")}
    try:
        text = build(data, os.path.join(folder, "renders"), titles, references, title)
    except Exception as e:   # the page must never cost the grade: results.json is already written
        text = (f"<!DOCTYPE html><meta charset=utf-8><title>{html.escape(title)}</title>"
                + _pre(f"The report page could not be made ({type(e).__name__}: {e}); see results.json."))
    path = os.path.join(folder, "report.html")
    fsutil.write_atomic(path, text.encode("utf-8"), 0o600 if os.geteuid() == 0 else 0o644)
    return path


# --- Gradescope's formatted output ----------------------------------------------------------------------
_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]#+!|~])")


def md_text(text):
    """text as Markdown shows it literally (HTML's three characters as entities, the rest escaped)."""
    text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return _MD_SPECIAL.sub(r"\\\1", text)


def markdown_tables(data):
    """Markdown for results.json's top-level output: per chapter a table of its visible tests (hidden ones
    are never in the top-level output, which a student sees at once)."""
    chapters = {}
    for t in visible(data.get("tests", [])):
        chapters.setdefault(t["tags"][0] if t.get("tags") else "grader", []).append(t)
    out = []
    for cid, tests in chapters.items():
        score, total = _points(tests)
        out += ["", f"**{md_text(cid)}: {_fmt(score)} / {_fmt(total)}**", "",
                "| test | result | points |", "|---|---|---:|"]
        for t in tests:
            result = "passed" if t["status"] == "passed" else "**failed**"
            out.append(f"| {md_text(t['name'])} | {result} | {_fmt(t['score'])} / {_fmt(t['max_score'])} |")
    return "\n".join(out)


def gradescope_formatted(data):
    """results.json as written for Gradescope: the top-level output as Markdown ("output_format": "md":
    the grader's lines, then each chapter's tests as a table); each test's output stays plain text
    ("test_output_format": "text": Gradescope shows it as written, the teaching messages' layout kept)."""
    head = "  \n".join(md_text(line) for line in str(data.get("output", "")).splitlines())
    return {**data, "output": head + "\n" + markdown_tables(data), "output_format": "md",
            "test_output_format": "text", "test_name_format": "text"}
