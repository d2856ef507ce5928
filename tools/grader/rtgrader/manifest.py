"""The grading manifest: points and visibility of every test, keyed by name.

tests/manifest.json looks like

  {
    "tests": {
      "ch01.public.a tangent ray touches the sphere once<float>": {"points": 1, "visibility": "visible"},
      "ch01.hidden.<name>":  {"points": 2, "visibility": "after_published"},
      "ch01.render":         {"points": 4, "visibility": "visible"}
    }
  }

Names are the ctest names: chNN.public.<doctest case>, chNN.hidden.<doctest
case>, and chNN.render for the picture. The grader refuses to run when a
test found in the tree has no entry, or an entry names no test, so a renamed
test can never silently lose or give away points.
"""

import json
import os

VISIBILITIES = ("visible", "after_published", "after_due_date", "hidden")
DEFAULT_POINTS = {"public": 1, "hidden": 2, "render": 4}
DEFAULT_VISIBILITY = {"public": "visible", "hidden": "after_published", "render": "visible"}


def test_names(chapters, chapter_ids, public_only):
    """Every gradable test of the chapters, in grading order: (name, kind, chapter id, case)."""
    names = []
    for cid in chapter_ids:
        ch = chapters[cid]
        for kind in ("public", "hidden"):
            if kind == "hidden" and public_only:
                continue
            for case in ch.get("tests", {}).get(kind, []):
                names.append((f"{cid}.{kind}.{case}", kind, cid, case))
        if ch.get("reference"):
            names.append((f"{cid}.render", "render", cid, None))
    return names


def load(path):
    with open(path) as f:
        data = json.load(f)
    entries = data.get("tests")
    if not isinstance(entries, dict):
        raise ValueError(f"{path}: expected an object with a 'tests' object")
    for name, e in entries.items():
        if not isinstance(e, dict) or not isinstance(e.get("points"), (int, float)) or e["points"] < 0:
            raise ValueError(f"{path}: entry '{name}' needs a non-negative number 'points'")
        if e.get("visibility", "visible") not in VISIBILITIES:
            raise ValueError(f"{path}: entry '{name}' has visibility '{e.get('visibility')}', "
                             f"expected one of {', '.join(VISIBILITIES)}")
    return entries


def check(entries, names, chapter_ids, public_only):
    """Problems as sentences: tests without entry, entries without test (in the chapters graded)."""
    found = {n for n, *_ in names}
    problems = [f"test '{n}' has no entry in the manifest" for n, *_ in names if n not in entries]
    for name in entries:
        chapter = name.split(".", 1)[0]
        if chapter not in chapter_ids or (public_only and ".hidden." in name):
            continue
        if name not in found:
            problems.append(f"manifest entry '{name}' names no test")
    return problems


def missing_entries(entries, names):
    """JSON lines to paste into the manifest for tests that have no entry yet."""
    lines = []
    for name, kind, _, _ in names:
        if name not in entries:
            entry = {"points": DEFAULT_POINTS[kind], "visibility": DEFAULT_VISIBILITY[kind]}
            lines.append(f"    {json.dumps(name)}: {json.dumps(entry)},")
    return lines


def update(path, entries, names, chapter_ids, public_only):
    """Rewrites the manifest: entries of the graded chapters in test order
    (new tests get the default points), other chapters' entries kept."""
    found = {n for n, *_ in names}
    kept = {}
    for name, kind, _, _ in names:
        kept[name] = entries.get(name, {"points": DEFAULT_POINTS[kind], "visibility": DEFAULT_VISIBILITY[kind]})
    dropped = []
    for name, e in entries.items():
        if name in kept:
            continue
        mine = name.split(".", 1)[0] in chapter_ids and not (public_only and ".hidden." in name)
        if mine and name not in found:
            dropped.append(name)
        else:
            kept[name] = e
    ordered = dict(sorted(kept.items(), key=lambda item: (item[0].split(".", 1)[0], 0)))
    lines = ["{", '  "comment": "Points and visibility of every graded test, keyed by its ctest name '
             '(tools/grader/README.md). tools/grader/grade --update-manifest adds entries for new tests.",',
             '  "tests": {']
    items = [f"    {json.dumps(n)}: {json.dumps(e)}" for n, e in ordered.items()]
    lines.append(",\n".join(items))
    lines += ["  }", "}"]
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)
    added = len([n for n in found if n not in entries])
    return f"{path}: {added} entries added, {len(dropped)} dropped" + "".join(f"\n  dropped {d}" for d in dropped)
