"""`python -m benchmarks --against REF`: every benchmark's figures on this tree and on REF, in one run.

Each benchmark compares a command with a reference of its own (the page's loop, scipy), which
catches no loss against the project's own last release: the resonance command lost 1.7× of its
CPU between two releases without any of them moving (issue 38). This mode compares the tree the
benchmarks run from (with any changes not yet committed) with REF, any commit, branch or tag:

* REF is checked out into a temporary git worktree, in the system's temporary folder (never inside
  the project), and removed afterwards, whatever happens: `git status` stays as it was.
* Each figure is one job: a user's command as a process (`python main.py ...`, start-up and output
  included), or a job of benchmarks/probe.py, which this tree's copy runs inside either tree (the
  engine called in-process, its own CPU time only). Jobs are the ones the benchmarks time.
* The two trees take turns: REF then this tree, then this tree then REF, and so on, `repeats`
  times each, so a busy spell of the machine falls on both. A figure is the CPU time of the job
  (user + system of the child), or the memory it touched for the first time (minor page faults ×
  the page size), which do not depend on the load as wall time does.
* For each pair the ratio this tree / REF; the table gives the median ratio and its spread (the
  lowest and highest pair) and marks WORSE each figure more than 10 % worse (median ratio > 1.10).

A job REF cannot run (a scene or flag it does not have yet) is reported as such and skipped.
"""
from __future__ import annotations

import contextlib
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

from .common import ROOT, load_average, resource, table

WORSE = 1.10          # a median ratio above this is marked
PROBE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "probe.py")


class AgainstError(RuntimeError):
    """The comparison cannot be made (not a git checkout, an unknown REF): one line for the user."""


@dataclass(frozen=True)
class Job:
    """One figure: `arguments` of `python` run from a tree ({tmp} is a scratch folder of the run);
    `measure` "cpu" (s) or "memory" (bytes touched: minor page faults × page size); `probe`: the
    arguments go to benchmarks/probe.py, whose own CPU time of the job is the figure."""

    label: str
    arguments: tuple[str, ...]
    measure: str = "cpu"
    probe: bool = False


@dataclass
class Figure:
    benchmark: str
    job: Job
    ref: list[float] = field(default_factory=list)
    ours: list[float] = field(default_factory=list)
    failed: str = ""

    @property
    def ratios(self) -> list[float]:
        return [a / b for a, b in zip(self.ours, self.ref) if b > 0]


def jobs(settings) -> dict[str, list[Job]]:
    """The jobs of each benchmark (the keys of benchmarks/__main__.py's BENCHMARKS), quick or full."""
    steps = settings.pick(1_000_000, 100_000)
    until = f"{steps * 1e-4:g}"
    vertical = ("main.py", "vertical", "--headless")
    resonance = ("main.py", "resonance", "--headless", "--json", "--set", "curves=1")
    big = settings.pick(10_000, 2_000)
    return {
        "single-mass": [
            Job(f"main.py vertical --json, {steps:,} steps", vertical + ("--json", "--set", "dt=0.0001", "--until", until)),
            Job(f"main.py vertical --csv FILE, {steps:,} rows",
                vertical + ("--csv", "{tmp}/vertical.csv", "--overwrite", "--set", "dt=0.0001", "--until", until))],
        "batches": [
            Job("10⁴ masses in 3-D, 300 steps (internal API)", ("batch", "10000", "3", "300"), probe=True),
            Job("10⁵ masses in 1-D, 100 steps (internal API)", ("batch", "100000", "1", "100"), probe=True)],
        "resonance": [Job("main.py resonance --json, count=1000", resonance + ("--set", "count=1000"))],
        "accuracy": [Job("main.py integrators --json", ("main.py", "integrators", "--headless", "--json"))],
        "startup": [Job("main.py vertical --headless", vertical)],
        "csv-batch": [
            Job(f"main.py resonance --json, count={big}", resonance + ("--set", f"count={big}")),
            Job(f"the resonance batch of {big:,} masses stepped, 300 steps (internal API)",
                ("stepping", str(big), "300"), probe=True)],
        "fit": [Job("main.py damped --data FILE --fit k,b, 1,000 points",
                    ("main.py", "damped", "--data", "{tmp}/measured-1000.csv", "--fit", "k,b", "--set", "m=0.5",
                     "--json"))],
        "friction": [Job(f"main.py friction --headless, {steps:,} steps",
                         ("main.py", "friction", "--headless", "--until", f"{steps * 0.01:g}"))],
        "allocation": [
            Job(f"memory main.py resonance --json touches, count={big}", resonance + ("--set", f"count={big}"),
                measure="memory"),
            Job(f"memory the resonance batch loop holds at once, {big:,} masses, 500 steps",
                ("allocation", str(big), "500"), measure="held", probe=True)],
    }


def git(*arguments: str) -> str:
    done = subprocess.run(["git", "-C", ROOT, *arguments], capture_output=True, text=True)
    if done.returncode != 0:
        raise AgainstError(f"git {' '.join(arguments)}: {done.stderr.strip() or 'failed'}")
    return done.stdout.strip()


@contextlib.contextmanager
def checked_out(ref: str):
    """(folder, commit, subject) of REF checked out into a temporary worktree, removed on leaving."""
    if shutil.which("git") is None:
        raise AgainstError("--against needs git on the PATH")
    try:
        commit = git("rev-parse", "--verify", "--quiet", f"{ref}^{{commit}}")
    except AgainstError:
        raise AgainstError(f"--against {ref}: no such commit, branch or tag in {ROOT}") from None
    parent = tempfile.mkdtemp(prefix="bench-against-")
    if os.path.commonpath([os.path.realpath(parent), os.path.realpath(ROOT)]) == os.path.realpath(ROOT):
        shutil.rmtree(parent, ignore_errors=True)
        raise AgainstError(f"the temporary folder {parent} is inside the project; set TMPDIR to a folder outside it")
    folder = os.path.join(parent, "ref")
    try:
        git("worktree", "add", "--detach", "--quiet", folder, commit)
        yield folder, commit, git("log", "-1", "--format=%h %s", commit)
    finally:
        try:
            git("worktree", "remove", "--force", folder)
        except AgainstError:          # half made, or its folder gone: forget it once it is removed
            shutil.rmtree(folder, ignore_errors=True)
            with contextlib.suppress(AgainstError):
                git("worktree", "prune")
        shutil.rmtree(parent, ignore_errors=True)


def run_job(job: Job, tree: str, scratch: str) -> float:
    """The job's figure in `tree`: CPU s, or bytes of memory touched. Raises RuntimeError if it fails."""
    arguments = [argument.replace("{tmp}", scratch) for argument in job.arguments]
    if job.probe:
        arguments = [PROBE, *arguments]
    before = resource.getrusage(resource.RUSAGE_CHILDREN) if resource is not None else None
    start = time.perf_counter()
    done = subprocess.run([sys.executable, *arguments], cwd=tree, capture_output=True, text=True, timeout=1800)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["no message"])[-1]
        raise RuntimeError(f"exit {done.returncode}: {last}")
    if job.probe:
        import json

        answer = json.loads(done.stdout.strip().splitlines()[-1])
        return float(answer["value"] if job.measure == "held" else answer["cpu"])
    if before is None:                  # Windows: no resource module, the wall time stands in
        return wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if job.measure == "memory":
        return float(after.ru_minflt - before.ru_minflt) * resource.getpagesize()
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def shown(value: float, measure: str) -> str:
    if measure == "cpu":
        return f"{value:.3g} s"
    return f"{value / 1e6:.3g} MB"


def compare(chosen: list[str], settings, ref: str, *, repeats: int) -> list[Figure]:
    """Run every job of the chosen benchmarks on both trees in turn; print the table; the figures."""
    every = jobs(settings)
    figures = [Figure(name, job) for name in chosen for job in every.get(name, [])]
    skipped = [name for name in chosen if name not in every]
    with checked_out(ref) as (other, commit, subject), tempfile.TemporaryDirectory(prefix="bench-data-") as scratch:
        mine = git("log", "-1", "--format=%h", "HEAD")
        dirty = " with changes not committed" if git("status", "--porcelain", "--untracked-files=no") else ""
        print(f"against {ref}: REF = {subject}; this tree = {ROOT} at {mine}{dirty}")
        print(f"{repeats} runs of each job on each tree, in turn; load average at start: {load_average(every=True)}")
        if any("{tmp}/measured-1000.csv" in job.arguments for job in every.get("fit", [])) and "fit" in chosen:
            from .fit import write_data

            write_data(scratch, 1_000, 50.0)
        for figure in figures:
            for turn in range(repeats):
                order = [(other, figure.ref), (ROOT, figure.ours)]
                for tree, values in (order if turn % 2 == 0 else order[::-1]):
                    try:
                        values.append(run_job(figure.job, tree, scratch))
                    except (RuntimeError, subprocess.SubprocessError) as problem:
                        figure.failed = f"{'REF' if tree == other else 'this tree'}: {problem}"
                        break
                if figure.failed:
                    break
            print(f"  {figure.benchmark}: {figure.job.label}: "
                  + (f"failed on {figure.failed}" if figure.failed else
                     f"{statistics.median(figure.ratios):.2f}×"), flush=True)
    print(f"load average at the end: {load_average(every=True)}\n")
    print(report(figures, repeats=repeats, skipped=skipped))
    return figures


def report(figures: list[Figure], *, repeats: int, skipped=()) -> str:
    """The table: each figure on REF and on this tree (medians), the ratio and its spread, marked."""
    rows, marked = [], 0
    for figure in figures:
        if figure.failed:
            rows.append([figure.benchmark, figure.job.label, "-", "-", f"not compared: fails on {figure.failed}", ""])
            continue
        ratios = figure.ratios
        ratio = statistics.median(ratios)
        worse = ratio > WORSE
        marked += worse
        rows.append([figure.benchmark, figure.job.label, shown(statistics.median(figure.ref), figure.job.measure),
                     shown(statistics.median(figure.ours), figure.job.measure),
                     f"{ratio:.2f} ({min(ratios):.2f}–{max(ratios):.2f})", "WORSE" if worse else ""])
    lines = [table(["benchmark", "figure (CPU s, or memory)", "REF", "this tree",
                    f"this/REF, median of {repeats} (spread)", f"> {WORSE:.2f}"], rows)]
    for name in skipped:
        lines.append(f"{name}: no figure to compare (its figures are statistics of the fit, not costs); run it alone")
    lines.append(f"{marked} figure{'' if marked == 1 else 's'} more than {WORSE - 1:.0%} worse than REF"
                 if marked else f"no figure more than {WORSE - 1:.0%} worse than REF")
    return "\n".join(lines)
