"""The timings README.md quotes, measured as a user measures them.

    .venv/bin/python bench/bench_docs.py [--repeat 3] [--write]

Every README command whose output shows a timing (``0.22 s wall``, ``, 1.52 s)``) runs ``--repeat``
times as a fresh process, as the README writes it (tests/docblocks.py runs the blocks; ``out/`` is a
scratch folder). Printed: the median of the timing the command prints and of the whole command's
wall time, and the load average. ``--write`` puts the medians into README.md: the timing inside
each block, and the whole-command times between ``<!-- bench:NAME -->`` and ``<!-- /bench -->``
(NAME: ``sim-vuelta``, ``sim-vuelta-no-collisions``, ``render-all``...).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from docblocks import TIMING, blocks  # noqa: E402

README = ROOT / "README.md"
# extra whole-command figures the README quotes in its text (name -> command line)
EXTRA = {"sim-vuelta-no-collisions": "myrabot-desc sim vuelta --no-collisions"}


def _name(line: str) -> str:
    words = [w for w in line.split() if not w.startswith("-") and "/" not in w and "." not in w]
    return "-".join(words[1:3]) if len(words) > 2 else words[-1]


def run_once(line: str, scratch: Path) -> tuple[float, str]:
    cmd = re.sub(r"(?<![\w/.])out/", str(scratch) + "/", line)
    env = dict(os.environ, PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", ""),
               MYRABOT_DESC_CACHE_DIR=str(scratch / ".cache"))
    t0 = time.perf_counter()
    r = subprocess.run(["bash", "-c", cmd + " 2>&1"], cwd=ROOT, env=env, capture_output=True, text=True)
    return time.perf_counter() - t0, r.stdout


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--write", action="store_true", help="Put the medians into README.md.")
    a = ap.parse_args()
    timed = [c for b in blocks(README) for c in b.commands if any(TIMING.search(ln) for ln in c.expected)]
    jobs = {_name(c.line): (c.line, c) for c in timed}
    jobs.update({k: (v, None) for k, v in EXTRA.items()})
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        scratch = Path(tmp) / "out"
        scratch.mkdir()
        for name, (line, _) in jobs.items():
            walls, printed = [], []
            for _ in range(a.repeat):
                wall, out = run_once(line, scratch)
                walls.append(wall)
                m = TIMING.search(out)
                if m:
                    printed.append(float(re.match(r"[\d.]+", m.group(0)).group(0)))
            results[name] = (statistics.median(walls), statistics.median(printed) if printed else None)
            shown = f", prints {results[name][1]:.2f} s" if printed else ""
            print(f"{name:28s} whole command {results[name][0]:.2f} s (median of {a.repeat}){shown}   $ {line}")
    load = os.getloadavg()[0]
    print(f"load average: {load:.1f} on {os.cpu_count()} cores")
    if not a.write:
        return
    text = README.read_text(encoding="utf-8")
    for name, (line, cmd) in jobs.items():
        wall, printed = results[name]
        text = re.sub(rf"(<!-- bench:{re.escape(name)} -->)[^<]*(<!-- /bench -->)", rf"\g<1>{wall:.1f} s\g<2>", text)
        if cmd is None or printed is None:
            continue
        for old in cmd.expected:
            m = TIMING.search(old)
            if m:
                new = old[:m.start()] + re.sub(r"[\d.]+", f"{printed:.2f}", m.group(0), count=1) + old[m.end():]
                text = text.replace(old, new)
    # the load the figures were measured under, beside them (a hand-written one would drift)
    text = re.sub(r"(<!-- bench:load -->)[^<]*(<!-- /bench -->)", rf"\g<1>{load:.1f}\g<2>", text)
    README.write_text(text, encoding="utf-8")
    print(f"wrote {README.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
