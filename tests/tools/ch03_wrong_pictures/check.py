#!/usr/bin/env python3
"""Checks chapter 03's README statements about wrong pictures against the fixtures.

    check.py --readme README.md --scene SCENE.json --fixtures DIR --work DIR BUG=DESCRIBE,PROGRAM,STATUS ...

Each item of the README's list of wrong pictures ends with a statement in an
HTML comment (invisible on the rendered page), one per fixture of
tests/fixtures/wrong/ch03/:

    - **blue painted over red** ... <!-- wrong-picture first_hit: blue over red -->
    - **an error** ... `the quoted text` ... <!-- wrong-picture no_object_index: error -->
    - ... <!-- wrong-picture no_shrink: same picture -->

"X over Y, ..." must be exactly the pairs the fixture's describer finds
(however few pixels they cover), and the item's visible text must name
every colour of those pairs and no other colour of the scene; "error"
means the chapter program linked with the fixture exits non-zero and prints
the item's back-quoted text; "same picture" means not one pixel differs.
An item may hold several statements. Every fixture needs a statement, and
every statement a fixture.
"""
import argparse
import json
import os
import re
import subprocess
import sys

MIN_PIXELS = 1  # every pair the picture shows must be stated (both sides trace in double: no rounding noise)
STATEMENT = re.compile(r"<!--\s*wrong-picture\s+([\w-]+)\s*:\s*(.*?)\s*-->")


def list_items(text):
    """The Markdown list items of text that hold a wrong-picture statement, as whole strings."""
    items, current = [], None
    for line in text.splitlines():
        if line.startswith("- "):
            current = [line]
            items.append(current)
        elif current is not None and line.startswith("  ") and line.strip():
            current.append(line)
        else:
            current = None
    return [" ".join(s.strip() for s in item) for item in items if STATEMENT.search(" ".join(item))]


def describe(program, scene):
    out = subprocess.run([program, scene], capture_output=True, text=True, timeout=60)
    if out.returncode != 0:
        raise SystemExit(f"{program} failed ({out.returncode}): {out.stderr}")
    pairs, bad, differing = {}, {}, None
    for line in out.stdout.splitlines():
        words = line.split()
        if words[0] == "over":
            pairs[(words[1], words[2])] = int(words[3])
        elif words[0] == "bad-object-index":
            bad[int(words[1])] = int(words[2])
        elif words[0] == "differing":
            differing = int(words[1])
    return pairs, bad, differing


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--readme", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--fixtures", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("tools", nargs="*", help="BUG=DESCRIBER,PROGRAM,PATCH_STATUS")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    tools = {}
    for t in args.tools:
        bug, paths = t.split("=", 1)
        tools[bug] = paths.split(",")
    with open(args.scene) as f:
        text = f.read()
    colours = set(re.findall(r'"name"\s*:\s*"(\w+)"', text))
    with open(args.readme) as f:
        items = list_items(f.read())

    problems = []
    stated = {}
    for item in items:
        visible = STATEMENT.sub("", item)
        for bug, claim in STATEMENT.findall(item):
            if bug in stated:
                problems.append(f"{bug}: stated twice")
            stated[bug] = (claim, visible)
    fixtures = sorted(d for d in os.listdir(args.fixtures) if os.path.exists(os.path.join(args.fixtures, d, "bug.patch")))
    for bug in fixtures:
        if bug not in stated:
            problems.append(f"{bug}: the fixture has no <!-- wrong-picture {bug}: ... --> statement in the README")
    for bug in stated:
        if bug not in fixtures:
            problems.append(f"{bug}: the README states a wrong picture for a fixture that does not exist")

    for bug in fixtures:
        if bug not in stated or bug not in tools:
            if bug not in tools:
                problems.append(f"{bug}: not built (re-run cmake)")
            continue
        claim, visible = stated[bug]
        describer, program, status = tools[bug]
        missing = [path for path in (status, describer, program) if not os.path.exists(path)]
        if missing:     # ctest -R ch03.wrong_pictures alone, before the build made these
            problems.append(f"{bug}: not built yet: {', '.join(missing)} (build the whole tree first, or the "
                            f"targets ch03_describe_{re.sub(r'[^A-Za-z0-9_]', '_', bug)} and "
                            f"ch03_program_{re.sub(r'[^A-Za-z0-9_]', '_', bug)})")
            continue
        with open(status) as f:
            status_text = f.read().strip()
        if status_text != "ok":
            problems.append(f"{bug}: {status_text}")
            continue
        pairs, bad, differing = describe(describer, args.scene)
        found = {pair for pair, n in pairs.items() if n >= MIN_PIXELS}
        print(f"{bug}: {differing} pixels differ; " +
              (", ".join(f"{a} over {b} ({n})" for (a, b), n in sorted(pairs.items(), key=lambda x: -x[1])) or "no pair") +
              ("; hits with object index " + ", ".join(f"{i} ({n})" for i, n in bad.items()) if bad else ""))
        if claim == "same picture":
            if differing or bad:
                problems.append(f"{bug}: the README says the picture is the same, but {differing} pixels differ"
                                + (f" and {sum(bad.values())} hits have no object" if bad else ""))
        elif claim == "error":
            quoted = re.findall(r"`([^`]+)`", visible)
            out = subprocess.run([program, "--out", os.path.join(args.work, bug + ".png")],
                                 capture_output=True, text=True, timeout=60)
            printed = out.stdout + out.stderr
            print(f"{bug}: the program exits with status {out.returncode} and prints: {printed.strip()}")
            if out.returncode == 0:
                problems.append(f"{bug}: the README says the program stops with an error, but it exits with status 0")
            if not quoted:
                problems.append(f"{bug}: the README item quotes no error text (in back quotes)")
            for q in quoted:
                if q not in printed:
                    problems.append(f"{bug}: the README quotes `{q}`, but the program prints: {printed.strip()}")
        else:
            claimed = set()
            for part in claim.split(","):
                m = re.fullmatch(r"\s*(\w+) over (\w+)\s*", part)
                if not m:
                    problems.append(f"{bug}: cannot read '{part.strip()}' (expected 'COLOUR over COLOUR')")
                    continue
                claimed.add((m.group(1), m.group(2)))
            for a, b in sorted(claimed - found):
                problems.append(f"{bug}: the README says {a} over {b}, but the picture shows that on "
                                f"{pairs.get((a, b), 0)} pixels")
            for a, b in sorted(found - claimed):
                problems.append(f"{bug}: the picture shows {a} over {b} on {pairs[(a, b)]} pixels, "
                                "and the README does not say so")
            named = {c for c in colours | {"background"} if re.search(rf"\b{c}\b", visible)}
            wanted = {c for pair in claimed for c in pair}
            for c in sorted(wanted - named):
                problems.append(f"{bug}: the item's text does not name {c}, which its statement does")
            for c in sorted((named & colours) - wanted):
                problems.append(f"{bug}: the item's text names {c}, which the picture does not involve")
    if problems:
        print("ch03.wrong_pictures: the README and the wrong pictures disagree:\n  " + "\n  ".join(problems))
        return 1
    print(f"ch03.wrong_pictures: the README's {len(stated)} statements match the {len(fixtures)} fixtures")
    return 0


if __name__ == "__main__":
    sys.exit(main())
