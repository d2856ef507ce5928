"""Command lines of tools/grader/grade and tools/grader/grade-batch (see README.md)."""

import argparse
import csv
import io
import os
import sys
import time
import traceback
from concurrent.futures import ThreadPoolExecutor

from . import dashboard, fsutil, grading, manifest, report, results, tree
from .sandbox import Limits


KIT_TIMEOUT = 30.0     # seconds per test case in a kit's preview (README, "Student kit and preview")


def _common_arguments(p):
    p.add_argument("--build-dir", help="grading folder holding the prebuilt instructor tree "
                                       "(default: build/grader in the repository)")
    p.add_argument("--repo", help="the instructor repository (default: the one this grader is in)")
    p.add_argument("--chapters", help="chapters to grade, e.g. 01,02 (default: all)")
    p.add_argument("--public-only", action="store_true",
                   help="public tests and renders only (a student's preview; the only choice in a kit)")
    p.add_argument("--manifest", help="points and visibility (default: tests/manifest.json)")
    p.add_argument("--timeout", type=float, default=None,
                   help="wall-clock seconds per test case (default 10; 30 in a student kit's preview)")
    p.add_argument("--render-timeout", type=float, default=60.0, help="seconds for a chapter's render (default 60)")
    p.add_argument("--memory-mb", type=int, default=1024, help="address-space limit per test in MiB (default 1024)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="parallel compiles / submissions")


def _setup(args, log):
    repo = os.path.abspath(args.repo or tree.repository_root())
    folder = args.build_dir or os.path.join(repo, "build", "grader")
    t = tree.Tree(folder, repo)
    wanted = None
    if args.chapters:
        wanted = [c.strip().zfill(2) for c in args.chapters.split(",") if c.strip()]
    t.prepare(args.jobs, wanted, log=log)
    public_only = args.public_only or not t.state["has_solutions"]
    # In a kit the judge has no solutions: what a test's own helpers ask of earlier chapters (chapter 08's
    # brute force, its served objects) goes to the student's runner too, a round trip each, and the
    # preview runs on the student's own machine, whatever else it is doing. Its cases get more time.
    if args.timeout is None:
        args.timeout = 10.0 if t.state["has_solutions"] else KIT_TIMEOUT
    limits = Limits(wall_seconds=args.timeout, cpu_seconds=int(args.timeout) + 1,
                    memory_bytes=args.memory_mb * 1024 * 1024)
    ids = [f"ch{n}" for n in wanted] if wanted else None
    options = grading.Options(chapters=ids, public_only=public_only, limits=limits,
                              render_seconds=args.render_timeout, jobs=args.jobs)
    manifest_path = args.manifest or os.path.join(t.source, "tests", "manifest.json")
    entries = manifest.load(manifest_path) if os.path.exists(manifest_path) else {}
    grader = grading.Grader(t, entries, options, log=log)
    problems = manifest.check(entries, grader.names, grader.chapter_ids, public_only)
    return t, grader, entries, problems, manifest_path


def _manifest_report(grader, entries, problems, manifest_path):
    lines = [f"{manifest_path}: {len(problems)} problem(s)"] + [f"  {p}" for p in problems]
    missing = manifest.missing_entries(entries, grader.names)
    if missing:
        lines += ["Entries to add to \"tests\" (default points; adjust them):"] + missing
    return "\n".join(lines)


def _check_manifest_from_build(args):
    """--check-manifest on an ordinary build (all chapters, no grading tree)."""
    import glob
    import json
    chapters = {}
    for path in sorted(glob.glob(os.path.join(args.from_build, "rt_chapters", "ch*.json"))):
        with open(path) as f:
            ch = json.load(f)
        chapters[ch["id"]] = ch
    ids = sorted(chapters)
    if args.chapters:
        ids = [f"ch{c.strip().zfill(2)}" for c in args.chapters.split(",")]
    for cid in ids:
        ch = chapters[cid]
        ch["tests"] = {kind: tree.list_test_cases(ch[f"{kind}_tests"])
                       for kind in ("public", "hidden") if ch.get(f"{kind}_tests")}
    repo = os.path.abspath(args.repo or tree.repository_root())
    path = args.manifest or os.path.join(repo, "tests", "manifest.json")
    entries = manifest.load(path)
    names = manifest.test_names(chapters, ids, args.public_only)
    problems = manifest.check(entries, names, ids, args.public_only)
    if problems:
        print(f"{path}: {len(problems)} problem(s)\n" + "\n".join("  " + p for p in problems))
        missing = manifest.missing_entries(entries, names)
        if missing:
            print("Entries to add (or run tools/grader/grade --update-manifest):\n" + "\n".join(missing))
        return 1
    print(f"{path}: every test of {', '.join(ids)} has an entry, every entry a test ({len(names)} tests)")
    return 0


def grade_main(argv=None):
    p = argparse.ArgumentParser(prog="grade", description="Grade one submission and write results.json.")
    p.add_argument("submission", nargs="?", help="a student's kit, or a folder with just their exercise files")
    p.add_argument("--out", default="results.json", help="where to write results.json")
    p.add_argument("--prepare-only", action="store_true",
                   help="only build the instructor tree in --build-dir (Gradescope's setup.sh)")
    p.add_argument("--check-manifest", action="store_true",
                   help="only check that every test has a manifest entry and every entry a test")
    p.add_argument("--missing-manifest", action="store_true",
                   help="print the manifest entries missing for new tests, and exit")
    p.add_argument("--from-build", metavar="BUILD_DIR",
                   help="with --check-manifest: take the test names from an existing build of the repository "
                        "(its rt_chapters/*.json and test executables) instead of the grading tree")
    p.add_argument("--update-manifest", action="store_true",
                   help="add entries (default points) for new tests to the repository's tests/manifest.json "
                        "and drop entries that name no test, then exit")
    _common_arguments(p)
    args = p.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr)
    start = time.monotonic()
    if args.prepare_only:
        t, grader, entries, problems, path = _setup(args, log)
        print(f"grader: the instructor tree in {t.folder} is ready ({', '.join(grader.chapter_ids)})")
        if problems:
            print(_manifest_report(grader, entries, problems, path))
        return 1 if problems else 0
    if args.check_manifest and args.from_build:
        return _check_manifest_from_build(args)
    if args.check_manifest or args.missing_manifest or args.update_manifest:
        t, grader, entries, problems, path = _setup(args, log)
        if args.update_manifest:
            target = args.manifest or os.path.join(t.repo, "tests", "manifest.json")
            print(manifest.update(target, entries, grader.names, grader.chapter_ids, grader.options.public_only))
            return 0
        if args.missing_manifest:
            print("\n".join(manifest.missing_entries(entries, grader.names)))
            return 0
        print(_manifest_report(grader, entries, problems, path) if problems else
              f"{path}: every test of {', '.join(grader.chapter_ids)} has an entry, every entry a test "
              f"({len(grader.names)} tests)")
        return 1 if problems else 0
    if not args.submission:
        p.error("give a submission folder (or --check-manifest)")
    out = os.path.abspath(args.out)
    try:
        t, grader, entries, problems, path = _setup(args, log)
        if problems:
            message = "The grader refuses to run: the manifest does not match the tests.\n" + \
                      _manifest_report(grader, entries, problems, path)
            results.write(results.failure(message, time.monotonic() - start), out)
            print(message, file=sys.stderr)
            return 2
        prepared = time.monotonic() - start
        found, notes, visible = grader.grade(args.submission, os.path.dirname(out))
        # Preparing the tree (when it had to be built) counts too; the hidden phase does not (results.py).
        data = results.gradescope(found, notes, prepared + visible, t.chapters())
        results.write(data, out)
        page = report.write(data, out, t.chapters())
        print(results.summary(data, t.chapters(), out) + f"\nThe page with your pictures: {page}")
        return 0
    except BaseException as e:  # the file must exist and be valid whatever happened
        message = f"The grader itself failed ({type(e).__name__}): {e}"
        if not isinstance(e, SystemExit):
            message += "\n" + traceback.format_exc()[-3000:]
        results.write(results.failure(message, time.monotonic() - start), out)
        print(message, file=sys.stderr)
        return 1


def batch_main(argv=None):
    p = argparse.ArgumentParser(prog="grade-batch",
                                description="Grade every submission folder inside FOLDER, in parallel.")
    p.add_argument("folder", help="one sub-folder per submission")
    p.add_argument("--out", required=True, help="folder for <submission>/results.json and scores.csv")
    _common_arguments(p)
    args = p.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr)
    start = time.monotonic()
    t, grader, entries, problems, path = _setup(args, log)
    if problems:
        print("The grader refuses to run:\n" + _manifest_report(grader, entries, problems, path), file=sys.stderr)
        return 2
    names = sorted(d for d in os.listdir(args.folder)
                   if os.path.isdir(os.path.join(args.folder, d)) and not os.path.islink(os.path.join(args.folder, d)))
    grader.options.jobs = 1           # parallel over submissions instead
    out_dir = fsutil.own_folder(args.out)

    def one(name):
        out = os.path.join(os.path.abspath(args.out), name, "results.json")
        try:
            found, notes, elapsed = grader.grade(os.path.join(args.folder, name), os.path.dirname(out))
            data = results.gradescope(found, notes, elapsed, t.chapters())
        except Exception as e:
            data = results.failure(f"The grader failed on this submission: {e}")
        results.write(data, out)
        report.write(data, out, t.chapters())
        print(f"{results.terminal_safe(name)}: {results.total_score(data):g} ({data['execution_time']} s)",
              file=sys.stderr)
        return name, data

    # While they are graded, the submissions are closed to every other user: in the fallback by user
    # a student's compile could otherwise #include a classmate's answer by its path.
    with fsutil.closed_to_others(args.folder), ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        seconds = {}
        graded = list(pool.map(dashboard.timed(one, seconds), names))
    chapter_ids = grader.chapter_ids
    table = io.StringIO()
    w = csv.writer(table)
    w.writerow(["submission", "score", "max_score"] + chapter_ids)
    for name, data in graded:
        per = [sum(x["score"] for x in data["tests"] if x["tags"][0] == c) for c in chapter_ids]
        w.writerow([name, results.total_score(data), sum(x["max_score"] for x in data["tests"])] + per)
    fsutil.write_atomic(os.path.join(out_dir, "scores.csv"), table.getvalue().encode())
    page = dashboard.for_batch(out_dir, graded, seconds, args.folder, t, chapter_ids)
    print(f"graded {len(graded)} submissions in {time.monotonic() - start:.1f} s -> "
          f"{os.path.join(args.out, 'scores.csv')}, the class at a glance: {page}")
    return 0
