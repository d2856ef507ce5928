#!/usr/bin/env python3
"""Tests of the grader's sandbox (ctest label 'grader'; tests/tools/CMakeLists.txt).

  sandbox_tests.py fixture NAME --work DIR --build-dir TREE   one hostile submission, in every isolation mode
  sandbox_tests.py outputs --work DIR --build-dir TREE        root never writes through a planted link
  sandbox_tests.py imgcmp --imgcmp PATH --work DIR            a PNG claiming 8192x8192 pixels is never decoded
  sandbox_tests.py private-clone --work DIR                   a repository in a 0700 folder grades, both modes

A fixture (tests/fixtures/adversarial/sandbox-*/) is graded twice: with the
isolation this machine allows (namespaces with bubblewrap where possible) and
with the fallback forced (RT_GRADER_ISOLATION=fallback). sandbox.json says
what must hold (see tests/fixtures/adversarial/README.md).
"""

import argparse
import fnmatch
import glob
import json
import os
import shutil
import stat
import struct
import subprocess
import sys
import time
import zlib

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GRADE = os.path.join(REPO, "tools", "grader", "grade")
FIXTURES = os.path.join(REPO, "tests", "fixtures", "adversarial")
LIMITS = ["--timeout", "3", "--render-timeout", "10"]
ROOT = os.geteuid() == 0
sys.path.insert(0, os.path.join(REPO, "tools", "grader"))
sys.dont_write_bytecode = True
from rtgrader import isolation  # noqa: E402

failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)
    return ok


def machine_mode():
    """The mode the grader will pick here when not forced."""
    os.environ.pop("RT_GRADER_ISOLATION", None)
    return isolation.detect().mode


def modes():
    """(label, environment) pairs to grade in: the machine's best, and the forced fallback."""
    best = machine_mode()
    out = [(best, {})]
    if best == isolation.NAMESPACES:
        out.append(("fallback", {"RT_GRADER_ISOLATION": "fallback"}))
    return out


def solution_folder(chapter="01"):
    return glob.glob(os.path.join(REPO, "solutions", f"{chapter}-*"))[0]


def grade(submission, out, build_dir, env_extra, chapters="01", repo_grade=GRADE, timeout=400):
    env = dict(os.environ)
    env.pop("RT_GRADER_ISOLATION", None)
    env.update(env_extra)
    cmd = [sys.executable, repo_grade, submission, "--out", out, "--chapters", chapters, *LIMITS]
    if build_dir:
        cmd += ["--build-dir", build_dir]
    start = time.monotonic()
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    seconds = time.monotonic() - start
    print(result.stdout[-2500:])
    print(result.stderr[-2500:], file=sys.stderr)
    check(result.returncode == 0, f"grade exited with {result.returncode}")
    data = None
    try:
        with open(out) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        check(False, f"{out}: no valid results.json ({e})")
    if data is not None:
        check(abs(sum(t["score"] for t in data["tests"]) - data["score"]) < 1e-9, "score is not the sum of the tests")
    return data, result, seconds


def expect_statuses(name, data, spec):
    """must_fail fails; everything else not in may_differ passes (as for the solutions)."""
    for t in data["tests"]:
        n = t["name"]
        if any(fnmatch.fnmatchcase(n, p) for p in spec.get("must_fail", [])):
            check(t["status"] == "failed", f"{name}: {n} passed, but this submission must fail it")
        elif not any(fnmatch.fnmatchcase(n, p) for p in spec.get("may_differ", [])):
            check(t["status"] == "passed", f"{name}: {n} failed, but passes for the solutions: {t['output'][:300]}")


def processes_named(comm):
    """Live processes called comm. A zombie (state Z) is left out: it is dead, runs no code and
    holds nothing but its exit status until init reaps it, which some inits (this VM's among
    them) do only after a while."""
    found = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                with open(f"/proc/{pid}/comm") as f:
                    name = f.read().strip()
                with open(f"/proc/{pid}/stat") as f:
                    state = f.read().rsplit(")", 1)[1].split()[0]
                if name == comm and state != "Z":
                    found.append(int(pid))
            except (OSError, IndexError):
                pass
    return found


def leftovers(prefix):
    found = []
    for folder in ("/tmp", "/var/tmp", "/dev/shm"):
        for dirpath, dirnames, filenames in os.walk(folder):
            found += [os.path.join(dirpath, n) for n in dirnames + filenames if n.startswith(prefix)]
    return found


def sysv_segments_of_sandbox_users():
    import pwd
    uids = {str(p.pw_uid) for p in pwd.getpwall() if p.pw_name.startswith("rt-grader-")}
    try:
        with open("/proc/sysvipc/shm") as f:
            return [line for line in f.readlines()[1:] if line.split()[7] in uids]
    except OSError:
        return []


def make_submission(name, spec, work, build_dir):
    sub = os.path.join(work, "sub", name)
    shutil.rmtree(sub, ignore_errors=True)
    target = os.path.join(sub, "chapters", os.path.basename(solution_folder()))
    os.makedirs(target)
    for path in glob.glob(os.path.join(FIXTURES, name, "*.cpp")):
        with open(path) as f:
            text = f.read()
        if spec.get("substitute"):
            text = (text.replace("@REPO@", REPO).replace("@TREE@", os.path.abspath(build_dir))
                    .replace("@RESULTS@", os.path.abspath(os.path.join(work, "..", "grader-tests"))))
        with open(os.path.join(target, os.path.basename(path)), "w") as f:
            f.write(text)
    for d in (sub, os.path.join(sub, "chapters"), target):
        os.chmod(d, 0o755)
    return sub


def run_fixture(args):
    name = args.name
    with open(os.path.join(FIXTURES, name, "sandbox.json")) as f:
        spec = json.load(f)
    if spec.get("make") == "links":
        return run_links(args)
    sub = make_submission(name, spec, args.work, args.build_dir)
    for label, env in modes():
        fallback = label != isolation.NAMESPACES
        out = os.path.join(args.work, "out", name, label, "results.json")
        data, result, seconds = grade(sub, out, args.build_dir, env, spec["chapters"])
        print(f"{name} [{label}]: graded in {seconds:.1f} s, score {data and data['score']}")
        if data is None:
            continue
        check(("FALLBACK" in result.stderr) == fallback, f"{name} [{label}]: the grader did not say its mode")
        if fallback:
            check("WITHOUT the namespace sandbox" in data["output"],
                  f"{name} [{label}]: results.json does not warn that namespaces were off")
        if fallback and not ROOT:
            print(f"NOTE: {name} [{label}]: no namespaces and not root: only the validity of results.json was checked")
            continue
        expect_statuses(f"{name} [{label}]", data, spec)
        with open(out) as f:
            text = f.read()
        forbidden = spec.get("forbidden_in_results", []) + \
            ([] if fallback else spec.get("forbidden_in_results_namespaces", []))
        for word in forbidden:
            check(word not in text, f"{name} [{label}]: '{word}' appears in results.json")
        for pattern, words in spec.get("output_contains", {}).items():
            chosen = [t for t in data["tests"] if fnmatch.fnmatchcase(t["name"], pattern)]
            check(chosen, f"{name} [{label}]: no test matches {pattern}")
            for t in chosen:
                check(words in t["output"], f"{name} [{label}]: {t['name']} does not say '{words}': {t['output'][:300]}")
        if "max_seconds" in spec:
            check(seconds < spec["max_seconds"], f"{name} [{label}]: grading took {seconds:.0f} s")
        if "no_leftovers" in spec:
            left = leftovers(spec["no_leftovers"])
            check(not left, f"{name} [{label}]: left behind: {left[:5]}")
            check(not sysv_segments_of_sandbox_users(), f"{name} [{label}]: System V segments left behind")
        if spec.get("no_escape_in_summary"):
            check("\x1b" not in result.stdout and "\x07" not in result.stdout,
                  f"{name} [{label}]: raw escape codes reached the grader's terminal summary")
            check("\\x1b" in result.stdout, f"{name} [{label}]: the summary does not show the escaped text")
        if name == "sandbox-fork-orphan":
            time.sleep(0.2)
            check(not processes_named("rt-orphan"), f"{name} [{label}]: a test process outlived grading")
        if name == "sandbox-reads-secrets":
            check("words to look at" in result.stderr, f"{name} [{label}]: the instructor note is missing from the log")


def run_links(args):
    """Links of both kinds in a submission are refused, the solution never taken."""
    solution = os.path.join(solution_folder(), "unit_sphere.cpp")
    cases = {}
    base = os.path.join(args.work, "sub", "links")
    shutil.rmtree(base, ignore_errors=True)
    for kind in ("symlink", "hardlink", "linked-folder"):
        sub = os.path.join(base, kind)
        chapters = os.path.join(sub, "chapters")
        os.makedirs(chapters)
        target = os.path.join(chapters, os.path.basename(solution_folder()))
        if kind == "linked-folder":
            os.symlink(solution_folder(), target)
        else:
            os.makedirs(target)
            link = os.path.join(target, "unit_sphere.cpp")
            os.symlink(solution, link) if kind == "symlink" else os.link(solution, link)
        cases[kind] = sub
    for label, env in modes():
        for kind, sub in cases.items():
            out = os.path.join(args.work, "out", "links", label, kind, "results.json")
            data, _, _ = grade(sub, out, args.build_dir, env)
            if data is None:
                continue
            check(data["score"] == 0, f"links [{label}] {kind}: scored {data['score']} with the instructor's file")
            entry = [t for t in data["tests"] if t["name"] == "ch01 compilation"]
            check(entry and "link" in entry[0]["output"], f"links [{label}] {kind}: no compilation entry naming the link")


def run_outputs(args):
    """Links planted in the output folder are replaced, never written through;
    a world-writable output folder is closed; the lock is the grader's alone."""
    sub = os.path.join(args.work, "sub", "outputs")
    shutil.rmtree(sub, ignore_errors=True)
    shutil.copytree(solution_folder(), os.path.join(sub, "chapters", os.path.basename(solution_folder())))
    out_dir = os.path.join(args.work, "out", "outputs")
    shutil.rmtree(out_dir, ignore_errors=True)
    os.makedirs(os.path.join(out_dir, "renders"))
    victim = os.path.join(args.work, "victim.txt")
    with open(victim, "w") as f:
        f.write("untouched\n")
    for rel in ("renders/ch01.png", "renders/ch01.diff.png", "results.json.tmp", "results.json"):
        os.symlink(victim, os.path.join(out_dir, rel))
    os.chmod(out_dir, 0o777)
    os.chmod(os.path.join(out_dir, "renders"), 0o777)
    data, _, _ = grade(sub, os.path.join(out_dir, "results.json"), args.build_dir, {})
    with open(victim) as f:
        check(f.read() == "untouched\n", "the grader wrote through a link planted in the output folder")
    if data:
        check(data["score"] == sum(t["max_score"] for t in data["tests"]), f"the solution scored {data['score']}")
    for rel in ("renders/ch01.png", "results.json"):
        info = os.lstat(os.path.join(out_dir, rel))
        check(stat.S_ISREG(info.st_mode), f"{rel} is not a regular file the grader wrote")
    if ROOT:
        check(os.stat(out_dir).st_mode & 0o022 == 0, "the output folder is still writable by others")
    lock = os.path.join(args.build_dir, "grader.lock")
    check(stat.S_IMODE(os.stat(lock).st_mode) == 0o600, f"{lock} can be opened by others")


def png(width, height, raw_rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw_rows, 9)) + chunk(b"IEND", b"")


def run_imgcmp(args):
    """A real decompression bomb (8192 x 8192 zeros in 200 KB): imgcmp reads
    its header and never decodes it, under a 256 MiB address-space limit."""
    os.makedirs(args.work, exist_ok=True)
    bomb = os.path.join(args.work, "bomb.png")
    small = os.path.join(args.work, "small.png")
    with open(bomb, "wb") as f:
        f.write(png(8192, 8192, bytes(8192 * (8192 * 3 + 1))))
    with open(small, "wb") as f:
        f.write(png(4, 4, bytes(4 * 13)))
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (256 << 20, 256 << 20))
    for pair, status, words in (((bomb, small), 1, "differ in size"), ((bomb, bomb), 2, "claims 8192x8192"),
                                ((small, small), 0, "match")):
        start = time.monotonic()
        r = subprocess.run([args.imgcmp, *pair], capture_output=True, text=True, preexec_fn=limit, timeout=60)
        said = r.stdout + r.stderr
        print(f"imgcmp {os.path.basename(pair[0])} {os.path.basename(pair[1])}: {r.returncode} "
              f"in {time.monotonic() - start:.2f} s: {said.strip()}")
        check(r.returncode == status and words in said, f"imgcmp on {pair}: status {r.returncode}, said {said!r}")


def run_private_clone(args):
    """The repository copied into a 0700 folder (like root's home) grades a
    correct chapter 01 fully, with namespaces and in the fallback."""
    private = os.path.join(args.work, "private")
    shutil.rmtree(private, ignore_errors=True)
    os.makedirs(private)
    os.chmod(private, 0o700)
    clone = os.path.join(private, "repo")
    ignore = shutil.ignore_patterns("build", "build-*", ".git", "__pycache__")
    shutil.copytree(REPO, clone, ignore=ignore)
    sub = os.path.join(args.work, "sub", "private-clone")
    shutil.rmtree(sub, ignore_errors=True)
    shutil.copytree(solution_folder(), os.path.join(sub, "chapters", os.path.basename(solution_folder())))
    for label, env in modes():
        out = os.path.join(args.work, "out", "private-clone", label, "results.json")
        data, result, seconds = grade(sub, out, None, env, repo_grade=os.path.join(clone, "tools", "grader", "grade"),
                                      timeout=900)
        print(f"private clone [{label}]: {seconds:.1f} s")
        if data:
            total = sum(t["max_score"] for t in data["tests"])
            check(total > 0 and data["score"] == total, f"private clone [{label}]: scored {data['score']} of {total}: "
                  + "; ".join(t["output"][:200] for t in data["tests"] if t["status"] != "passed")[:1500])


def main():
    p = argparse.ArgumentParser()
    p.add_argument("what", choices=["fixture", "outputs", "imgcmp", "private-clone"])
    p.add_argument("name", nargs="?")
    p.add_argument("--work", required=True)
    p.add_argument("--build-dir")
    p.add_argument("--imgcmp")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    {"fixture": run_fixture, "outputs": run_outputs, "imgcmp": run_imgcmp,
     "private-clone": run_private_clone}[args.what](args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
