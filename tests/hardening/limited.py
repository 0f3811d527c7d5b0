"""Run the command line as a real process under watch: its CPU time and peak memory measured from
the kernel's accounting (wait4), a CPU limit and a wall-clock timeout for a run that blocks.

The figures are CPU time, so a loaded machine does not fail a test; ``BUDGET_CPU`` and
``BUDGET_RSS`` are the issue's bounds for any hostile run (10 s of CPU, 1 GB).
"""

from __future__ import annotations

import os
import resource
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


def run(argv, cwd=None, env=None, timeout: float = 60.0, stdin=None) -> Run:
    """``myrabot-desc ARGV`` in a child process, reaped with os.wait4: its own CPU seconds and peak
    resident memory. A CPU limit of twice the budget stops a runaway; ``timeout`` (wall) one that
    blocks."""
    import tempfile

    full_env = {**os.environ, "MUJOCO_GL": "disable", **(env or {})}
    full_env.pop("MYRABOT_DESC_DEBUG", None)

    def limits():
        resource.setrlimit(resource.RLIMIT_CPU, (int(2 * BUDGET_CPU) + 1, int(2 * BUDGET_CPU) + 2))

    t0 = time.monotonic()
    with tempfile.TemporaryFile() as fo, tempfile.TemporaryFile() as fe:
        p = subprocess.Popen(CLI + [str(a) for a in argv], cwd=cwd, env=full_env,
                             stdin=stdin if stdin is not None else subprocess.DEVNULL,
                             stdout=fo, stderr=fe, preexec_fn=limits)
        deadline = time.monotonic() + timeout
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                p.kill()
                _pid, status, usage = os.wait4(p.pid, 0)
                status = None
                break
            time.sleep(0.02)
        p.returncode = -1             # reaped here: Popen must not wait for it again
        fo.seek(0)
        fe.seek(0)
        out, err = fo.read().decode(errors="replace"), fe.read().decode(errors="replace")
    code = os.WEXITSTATUS(status) if status is not None and os.WIFEXITED(status) else None
    return Run(code, out, err, usage.ru_utime + usage.ru_stime, usage.ru_maxrss * 1024, time.monotonic() - t0)


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
