"""Run the command line as a real process under watch: its CPU time and peak memory measured from
the kernel's accounting (wait4), a CPU limit and a wall-clock timeout for a run that blocks.

The figures are CPU time, so a loaded machine does not fail a test; ``BUDGET_CPU`` and
``BUDGET_RSS`` are the issue's bounds for any hostile run (10 s of CPU, 1 GB).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path
from typing import NamedTuple

BUDGET_CPU = 10.0                 # seconds of CPU a hostile run may take
BUDGET_RSS = 1 << 30              # bytes of resident memory it may reach
CLI = [sys.executable, "-m", "myrabot_desc"]


class Run(NamedTuple):
    code: int | None              # None: killed (the CPU limit) or timed out (blocked)
    stdout: str
    stderr: str
    cpu: float                    # user + system seconds
    rss: int                      # peak resident bytes
    wall: float


# Runs the command in a grandchild and reports its rusage. Linux carries a process's peak RSS across
# exec, so a child forked straight from a pytest worker that has grown (models, MuJoCo) would report
# the worker's peak as its own; a process forked from this small launcher starts its count afresh.
_LAUNCHER = """
import os, resource, sys
lim = int(sys.argv[1])
pid = os.fork()
if pid == 0:
    resource.setrlimit(resource.RLIMIT_CPU, (lim, lim + 1))
    os.execv(sys.argv[2], sys.argv[2:])
_, status, u = os.wait4(pid, 0)
with open(os.environ["_LIMITED_USAGE"], "w") as f:
    f.write(f"{u.ru_utime + u.ru_stime} {u.ru_maxrss} {status}")
"""


def run(argv, cwd=None, env=None, timeout: float = 60.0, stdin=None) -> Run:
    """``myrabot-desc ARGV`` in a child process, reaped with os.wait4: its own CPU seconds and peak
    resident memory. A CPU limit of twice the budget stops a runaway; ``timeout`` (wall) one that
    blocks."""
    import signal
    import tempfile

    full_env = {**os.environ, "MUJOCO_GL": "disable", **(env or {})}
    full_env.pop("MYRABOT_DESC_DEBUG", None)
    t0 = time.monotonic()
    with tempfile.TemporaryFile() as fo, tempfile.TemporaryFile() as fe, \
            tempfile.TemporaryDirectory() as scratch:
        usage_file = Path(scratch) / "usage"
        full_env["_LIMITED_USAGE"] = str(usage_file)
        p = subprocess.Popen([sys.executable, "-S", "-c", _LAUNCHER, str(int(2 * BUDGET_CPU) + 1), *CLI,
                              *[str(a) for a in argv]], cwd=cwd, env=full_env,
                             stdin=stdin if stdin is not None else subprocess.DEVNULL,
                             stdout=fo, stderr=fe, start_new_session=True)
        try:
            p.wait(timeout=timeout)
            killed = False
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
            killed = True
        fo.seek(0)
        fe.seek(0)
        out, err = fo.read().decode(errors="replace"), fe.read().decode(errors="replace")
        cpu, rss, status = (usage_file.read_text().split() if usage_file.exists() else ("0", "0", None))
    status = None if killed or status is None else int(status)
    code = os.WEXITSTATUS(status) if status is not None and os.WIFEXITED(status) else None
    return Run(code, out, err, float(cpu), int(rss) * 1024, time.monotonic() - t0)


def within_budget(r: Run) -> list[str]:
    """What is wrong with a hostile run's cost (empty: nothing)."""
    bad = []
    if r.code is None:
        bad.append(f"killed or blocked after {r.wall:.1f} s")
    if r.cpu > BUDGET_CPU:
        bad.append(f"{r.cpu:.1f} s of CPU")
    if r.rss > BUDGET_RSS:
        bad.append(f"{r.rss / 2**20:.0f} MB resident")
    text = r.stdout + r.stderr
    if "Traceback" in text or "internal error" in text:
        bad.append("traceback or internal error: " + text[-500:])
    return bad


def write(path: Path, text) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return path
