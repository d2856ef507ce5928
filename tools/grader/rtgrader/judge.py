"""A chapter's test cases: the judge (the course's tests, no student code)
calls the runner (the student's code, in the sandbox) over a socket, and decides.

    judge  chNN_{public,hidden}_judge --test-case=A,B,...   run by the grader, trusted
    runner chNN_runner                                      sandbox.run(), as the sandbox user

One judge process runs all the cases it is given, and one runner serves them
(RunnerHost), replaced only when it broke: it crashed, exited, wrote garbage
or went past a case's time limit. The judge reports every case on a control
socket only it and the grader hold (judge_main.cpp): `B` when a case starts
(the grader answers with the runner to use, passing a fresh one's socket when
needed), `E` with the verdict and doctest's report of that case when it ends.
The grader times each case from its `B`: at the limit it kills the runner
(the judge's outstanding call then fails the case), and if the judge itself
does not end the case soon after, the judge too, and a new judge runs the
remaining cases. The runner's output, exit status and files are never read
for a verdict; the way it ended is only added to the message.
"""

import os
import socket
import struct
import subprocess
import threading
import time
from dataclasses import dataclass

from . import sandbox

JUDGE_GRACE_SECONDS = 10     # the judge is trusted: the time it may take beyond a case's limit, or to start
MAX_FRAME = 1 << 20          # a case's report is cut at 256 KiB by the judge
counts = {"judges": 0}       # judge processes started by this grader process


@dataclass
class CaseOutcome:
    passed: bool
    reason: str          # why it failed when the judge could not say (empty otherwise)
    judge_output: str    # doctest's report of this case, written by the judge
    runner: object       # sandbox.Outcome of the runner when it ended during this case (message only)
    timed_out: bool = False


# The judge is trusted code, but it decodes whatever the runner sends (the student's process) and runs
# as the grader's user (root) outside the sandbox: a list the runner claims to hold (one byte an item on
# the wire, many bytes an item once decoded) must not let it take the machine's memory. Its own needs
# are a few MiB (the largest judge, chapter 08's, peaks under 5 MiB resident).
JUDGE_MEMORY_BYTES = 2048 << 20


def _judge_limits(cpu=None):     # in the judge's process, before exec
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (JUDGE_MEMORY_BYTES, JUDGE_MEMORY_BYTES))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if cpu is not None:
        # The judge stays on this CPU and asks its runner to join it (judge.cpp, share_cpu): two
        # chapters graded at once then use one CPU each.
        try:
            os.sched_setaffinity(0, {cpu})
        except OSError:
            pass


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


class Runner:
    """One sandboxed runner process, serving calls on a socket until it is stopped."""

    def __init__(self, start):
        self.judge_end, runner_end = socket.socketpair()
        self.stopper = sandbox.Stopper()
        self.outcome = None
        self.done = threading.Event()   # set before the judge can see the channel close

        def run_it():
            try:
                self.outcome = start({"RT_RPC_FD": str(runner_end.fileno())}, (runner_end.fileno(),), self.stopper)
                self.done.set()
            finally:
                # Only once the runner and everything it started are gone does the judge see the channel
                # close: a crash, an exit or a limit then fails the call that was outstanding, and
                # self.outcome is already there to say how it ended.
                runner_end.close()

        self.thread = threading.Thread(target=run_it, daemon=True)
        self.thread.start()

    def ended(self):
        return self.done.is_set() or not self.thread.is_alive()

    def close(self):
        """Stops the runner (if it still runs) and waits until it is gone."""
        self.stopper.stop()
        self.judge_end.close()
        self.thread.join()


class RunnerHost:
    """The runner of one chapter: started when a case first needs it, kept from
    case to case (and from the public to the hidden judge), replaced after it broke.
    start(env_extra, pass_fds, stopper) runs one runner in the sandbox (blocking)."""

    def __init__(self, start):
        self._start = start
        self.runner = None
        self.starts = 0

    def fresh(self):
        if self.runner is not None:
            self.runner.close()
        self.runner = Runner(self._start)
        self.starts += 1
        return self.runner

    def close(self):
        if self.runner is not None:
            # Closing our end tells an idle runner the chapter is over; stop() ends one that lingers.
            self.runner.judge_end.close()
            self.runner.thread.join(timeout=1)
            self.runner.close()
            self.runner = None


class _Frames:
    """The judge's framed messages (32-bit length, kind byte, bytes), read with deadlines."""

    def __init__(self, sock):
        self.sock = sock
        self.buffer = b""

    def next(self, deadline):
        """(kind, bytes); None when the judge closed the socket; raises TimeoutError at the deadline."""
        while True:
            if len(self.buffer) >= 4:
                size = struct.unpack("=I", self.buffer[:4])[0]
                if size < 1 or size > MAX_FRAME:
                    raise ValueError("the judge sent a message of impossible length")
                if len(self.buffer) >= 4 + size:
                    frame, self.buffer = self.buffer[4:4 + size], self.buffer[4 + size:]
                    return chr(frame[0]), frame[1:]
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError
            self.sock.settimeout(left)
            try:
                data = self.sock.recv(1 << 16)
            except socket.timeout:
                raise TimeoutError from None
            if not data:
                return None
            self.buffer += data


def run_cases(judge, cases, host, limits, cwd, log_path, budget, cpu=None):
    """Runs `cases` (names) of `judge` against host's runner; returns {name: CaseOutcome}.
    budget.reason() says why no further case may start ('' while they may), budget.skipped(case)
    why that case is not started (another case of its concept went past its time limit, which
    budget.timed_out(case) is told). Cases not run are missing from the result (the caller says
    why). A judge that reaches a skipped case is ended and a new one runs the cases left."""
    results = {}
    remaining = [c for c in cases if not budget.skipped(c)]
    while remaining and not budget.reason():
        ran = _one_judge(judge, remaining, host, limits, cwd, log_path, budget, results, cpu)
        left = [c for c in remaining if c not in results and not budget.skipped(c)]
        if not ran or (len(left) == len(remaining) and not budget.reason()):
            for c in left:   # the judge ended without starting them: nothing more to learn by starting it again
                results[c] = CaseOutcome(False, "Grader problem: the judge did not run this test "
                                                "(tell your instructor).", "", None)
            break
        remaining = left
    return results


def _one_judge(judge, cases, host, limits, cwd, log_path, budget, results, cpu=None):
    """One judge process for `cases`, until it ends or is killed; fills results. Returns
    whether it started any case."""
    grader_end, judge_control = socket.socketpair()
    counts["judges"] += 1
    wanted = set(cases)
    ran = False
    with open(log_path, "ab") as log:
        proc = subprocess.Popen(
            [judge, "--test-case=" + ",".join(escape_filter(c) for c in cases), "--no-version", "--no-colors"],
            cwd=cwd, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
            env={"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "RT_JUDGE_CONTROL_FD": str(judge_control.fileno())},
            pass_fds=(judge_control.fileno(),), preexec_fn=lambda: _judge_limits(cpu))
    judge_control.close()
    frames = _Frames(grader_end)
    has_runner = None         # the Runner this judge process holds
    current = None            # the case running now: its name, runner, deadline, whether it timed out
    try:
        while True:
            if current is None:
                deadline = time.monotonic() + JUDGE_GRACE_SECONDS
            else:
                deadline = current["deadline"] + (JUDGE_GRACE_SECONDS if current["timed_out"] else 0)
            try:
                frame = frames.next(deadline)
            except TimeoutError:
                if current is not None and not current["timed_out"]:
                    # The case's time is up: end the runner; the judge's call fails and the case ends.
                    current["timed_out"] = True
                    current["runner"].stopper.stop()
                    continue
                break      # the judge itself does not go on: it is killed below
            except ValueError:
                break
            if frame is None:
                break
            what, data = frame
            if what == "B":
                name = data[1:].decode("utf-8", errors="replace")
                if budget.reason() or budget.skipped(name):
                    break
                runner = host.runner
                if data[:1] == b"1" or runner is None or runner.ended() or runner.stopper.stopped:
                    runner = host.fresh()
                if runner is not has_runner:
                    socket.send_fds(grader_end, [b"R"], [runner.judge_end.fileno()])
                    has_runner = runner
                else:
                    grader_end.sendall(b"G")
                ran = True
                current = {"name": name, "runner": runner, "timed_out": False,
                           "deadline": time.monotonic() + limits.wall_seconds}
            elif what == "E" and current is not None:
                if not _record(results, wanted, current, data, limits, budget):
                    # The runner broke (crash, exit, garbage, time limit): nobody gets it again, not
                    # even the next judge; the next case starts a fresh one.
                    current["runner"].stopper.stop()
                current = None
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        grader_end.close()
    if proc.returncode not in (0, 1) and has_runner is not None:
        # The judge crashed or was killed: its runner may be in the middle of a call (waiting for a
        # callback's answer), so no later judge gets it.
        has_runner.stopper.stop()
    if current is not None:
        # The judge ended (or was killed) in the middle of a case: it fails, and the runner, which may
        # be in the middle of an answer, is not given to anyone else.
        current["runner"].stopper.stop()
        if current["timed_out"]:
            budget.timed_out(current["name"])
        if current["name"] in wanted and current["name"] not in results:
            results[current["name"]] = CaseOutcome(
                False, "The test did not finish in time." if current["timed_out"] else
                "The test ended abnormally (the judge stopped during it).", "", _ending(current), current["timed_out"])
    return ran


def _record(results, wanted, current, data, limits, budget):
    """A case's E message: its verdict and report. Returns whether the runner is still fit
    to serve (it did not break during the case)."""
    head, _, report = data.partition(b"\n")
    fields = head.split()
    text = report.decode("utf-8", errors="replace")
    timed_out = current["timed_out"]
    if timed_out:
        budget.timed_out(current["name"])
    fit = False
    if len(fields) != 4 or not all(f.isdigit() for f in fields):
        outcome = CaseOutcome(False, "Grader problem: the judge gave no verdict; tell your instructor.", text, None)
    else:
        failed, _, asserts_failed, broke = (int(f) for f in fields)
        passed = failed == 0 and asserts_failed == 0 and broke == 0 and not timed_out
        reason = "The test did not finish in time." if timed_out else ""
        outcome = CaseOutcome(passed, reason, text, None if passed else _ending(current), timed_out)
        fit = broke == 0 and not timed_out
    if current["name"] in wanted and current["name"] not in results:
        results[current["name"]] = outcome
    return fit


def _ending(current):
    """The runner's Outcome when it ended during this case, else None."""
    if current["timed_out"]:
        return None       # we stopped it: the reason already says so
    runner = current["runner"]
    return runner.outcome if runner.done.is_set() else None


def runner_ending(outcome, limits):
    """How the runner ended, when that explains a failure ('' when it just finished)."""
    if outcome is None:
        return ""
    how = sandbox.describe_ending(outcome, limits)
    if how:
        return f"Your code {how}."
    return ""
