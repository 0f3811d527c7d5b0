"""Shared helpers for the bench_*.py scripts: best-of-N timing of commands, machine facts, tables.

Every command is timed as a fresh process (wall clock with perf_counter, and the
child's user+sys CPU from wait4), best of N, with the peers interleaved with our
commands so that load from other processes hits both alike.
"""

from __future__ import annotations

import json
import os
import platform
import shutil
import subprocess
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
OUT = ROOT / "out" / "bench"


def bench_env() -> dict:
    """The environment for timed children: bytecode caches on, as after ``pip install``.

    This machine exports PYTHONDONTWRITEBYTECODE=1, which makes every run recompile our
    modules from source (an editable install has no .pyc files); the caches go to
    out/bench/pycache so the source tree stays clean.
    """
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = str(OUT / "pycache")
    return env


def run_once(cmd, *, cwd=None, env=None, stdin=None) -> tuple[float, float, int, bytes]:
    """(wall s, child cpu s, returncode, stderr) of one run of ``cmd``."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=cwd, env=env or bench_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         stdin=stdin)
    err = p.stderr.read()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return wall, ru.ru_utime + ru.ru_stime, p.returncode, err


def best_of(cmds: dict, n: int, *, cwd=None, env=None, ok=(0,), warmup=1) -> dict:
    """Time every command of ``cmds`` (name -> argv) n times, interleaved; best wall and cpu per name."""
    res = {k: {"wall": [], "cpu": []} for k in cmds}
    for _ in range(warmup):
        for name, cmd in cmds.items():
            w, c, rc, err = run_once(cmd, cwd=cwd, env=env)
            if rc not in ok:
                raise SystemExit(f"{name}: {' '.join(map(str, cmd))} exited {rc}: {err.decode(errors='replace')[-400:]}")
    for _ in range(n):
        for name, cmd in cmds.items():
            w, c, rc, err = run_once(cmd, cwd=cwd, env=env)
            if rc not in ok:
                raise SystemExit(f"{name}: {' '.join(map(str, cmd))} exited {rc}: {err.decode(errors='replace')[-400:]}")
            res[name]["wall"].append(w)
            res[name]["cpu"].append(c)
    return {k: {"wall": min(v["wall"]), "cpu": min(v["cpu"]), "n": n} for k, v in res.items()}


def baseline(n: int = 5) -> dict:
    """This machine's floor in the same run: ``python -c pass`` and ``python -c "import numpy"`` (one
    BLAS thread, as the CLI runs it), best of ``n``: figures from another machine compare through them."""
    py = str(BIN / "python")
    return best_of({"python -c pass": [py, "-c", "pass"], "import numpy": [py, "-c", "import numpy"]}, n,
                   env=dict(bench_env(), OPENBLAS_NUM_THREADS="1"))


def baseline_text(base: dict) -> str:
    p, n = base["python -c pass"], base["import numpy"]
    return (f"`python -c pass` {fmt_s(p['cpu'])} CPU ({fmt_s(p['wall'])} wall), `python -c \"import numpy\"` "
            f"{fmt_s(n['cpu'])} CPU ({fmt_s(n['wall'])} wall, one BLAS thread)")


def have(tool: str) -> bool:
    return shutil.which(tool) is not None


def machine() -> dict:
    model = "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cores": os.cpu_count(), "cpu": model, "python": platform.python_version(),
            "date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "load": os.getloadavg()[0]}


def save(name: str, data: dict) -> Path:
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / f"{name}.json"
    data = {"machine": machine(), **data}
    path.write_text(json.dumps(data, indent=2) + "\n")
    return path


def fmt_s(x) -> str:
    if x is None:
        return "—"
    return f"{x * 1000:.0f} ms" if x < 1 else f"{x:.2f} s"


def table(rows, header) -> str:
    """Plain-text table (also valid Markdown)."""
    rows = [[str(c) for c in r] for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(header)]
    line = lambda cells: "| " + " | ".join(c.ljust(w) for c, w in zip(cells, widths)) + " |"  # noqa: E731
    return "\n".join([line(header), "|" + "|".join("-" * (w + 2) for w in widths) + "|"] + [line(r) for r in rows])
