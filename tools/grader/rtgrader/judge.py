"""One test case: the judge (the course's tests, no student code) calls the
runner (the student's code, in the sandbox) over a socket, and decides.

    judge  chNN_{public,hidden}_judge --test-case=NAME   run by the grader, trusted
    runner chNN_runner                                   run_limited(), as the sandbox user

The verdict is the judge's own report (cases, failed cases, asserts, failed
asserts) written on a pipe only the judge holds, and the feedback is the
judge's own output. The runner's output, exit status and files are never read
for a verdict: when it dies, the judge sees the channel close and fails the
test; the way it ended is only added to the message.
"""

import os
import socket
import subprocess
import threading
from dataclasses import dataclass

from . import sandbox

JUDGE_OUTPUT_CAP = 256 * 1024
JUDGE_GRACE_SECONDS = 10     # the judge itself is trusted: it only needs time beyond the runner's limit


@dataclass
class CaseOutcome:
    passed: bool
    reason: str          # why it failed when the judge could not say (empty otherwise)
    judge_output: str    # doctest's report, written by the judge
    runner: object       # sandbox.Outcome of the runner (for the message only)
    timed_out: bool = False


def escape_filter(case):
    # doctest reads ',' as "or" in a filter: escape it.
    return case.replace("\\", "\\\\").replace(",", "\\,")


def probe(run_runner, runner, limits):
    """'' if the runner starts (its static initialisers end), else why not.
    run_runner(argv) runs it in the sandbox and returns a sandbox.Outcome."""
    outcome = run_runner([runner, "--probe"])
    if outcome.returncode == 0 and not outcome.timed_out:
        return ""
    how = sandbox.describe_ending(outcome, limits) or f"exited with status {outcome.returncode}"
    return (f"your code did not start: it {how} before any test ran "
            "(look at your file's global variables and static initialisers)")


def run_case(judge, runner, case, limits, cwd, run_runner):
    """Runs one doctest case of `judge` against a fresh runner; returns a CaseOutcome.
    run_runner(argv, env_extra, pass_fds) runs the runner in the sandbox (blocking)."""
    judge_end, runner_end = socket.socketpair()
    report_read, report_write = os.pipe()
    found = {}

    def run_it():
        try:
            found["runner"] = run_runner([runner], {"RT_RPC_FD": str(runner_end.fileno())}, (runner_end.fileno(),))
        finally:
            # Only once the runner and everything it started are gone does the judge see the channel
            # close: a crash, an exit or a limit then fails the call that was outstanding.
            runner_end.close()

    thread = threading.Thread(target=run_it)
    thread.start()
    judge_timed_out = False
    try:
        proc = subprocess.Popen(
            [judge, f"--test-case={escape_filter(case)}", "--no-version", "--no-colors"],
            cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
            env={"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "RT_RPC_FD": str(judge_end.fileno()),
                 "RT_JUDGE_REPORT_FD": str(report_write)},
            pass_fds=(judge_end.fileno(), report_write))
        judge_end.close()
        os.close(report_write)
        report_write = None
        try:
            output, _ = proc.communicate(timeout=limits.wall_seconds + JUDGE_GRACE_SECONDS)
        except subprocess.TimeoutExpired:
            proc.kill()
            output, _ = proc.communicate()
            judge_timed_out = True
        with os.fdopen(report_read, "rb") as f:
            report_read = None
            report = f.read(4096).decode("ascii", errors="replace")
    finally:
        judge_end.close()
        for fd in (report_read, report_write):
            if fd is not None:
                os.close(fd)
        thread.join()
    text = output[:JUDGE_OUTPUT_CAP].decode("utf-8", errors="replace")
    passed, reason = _decide(report, proc.returncode, judge_timed_out)
    return CaseOutcome(passed, reason, text, found.get("runner"), judge_timed_out)


def _decide(report, returncode, timed_out):
    """Pass or fail, from the judge's report only."""
    if timed_out:
        return False, "The test did not finish in time."
    fields = report.split()
    if len(fields) != 4 or not all(f.isdigit() for f in fields):
        return False, f"Grader problem: the judge gave no verdict (exit status {returncode}); tell your instructor."
    cases, failed, _, asserts_failed = (int(f) for f in fields)
    if cases != 1:
        return False, f"Grader problem: {cases} test cases matched this name (tell your instructor)."
    return failed == 0 and asserts_failed == 0 and returncode == 0, ""


def runner_ending(outcome, limits):
    """How the runner ended, when that explains a failure ('' when it just finished)."""
    if outcome is None:
        return ""
    how = sandbox.describe_ending(outcome, limits)
    if how:
        return f"Your code {how}."
    return ""
