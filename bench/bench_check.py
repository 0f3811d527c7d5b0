"""Time `myrabot-desc check` on all 69 example-robot-data URDFs in one call, with and without --inertia.

Target (issue 4): without --inertia, all 69 in under 10 s (one process, imports included).

    .venv/bin/python bench/bench_check.py [--repeat N]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import sysconfig
import time
from pathlib import Path

ROBOTS = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"


def run(files, extra) -> tuple[float, int]:
    # --no-cache: the work itself (the result cache would answer every run after the first)
    cmd = [sys.executable, "-m", "myrabot_desc", "check", "--no-cache", "--format", "json", "-o", "/dev/null", *extra,
           *files]
    t = time.perf_counter()
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    return time.perf_counter() - t, rc


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3, help="runs per mode; the best is reported")
    args = ap.parse_args()
    files = [str(p) for p in sorted(ROBOTS.rglob("*.urdf"))]
    print(f"{len(files)} URDF files under {ROBOTS}")
    ok = True
    for label, extra, target in (("check", [], 10.0), ("check --inertia", ["--inertia"], None)):
        times = []
        for _ in range(args.repeat):
            dt, rc = run(files, extra)
            if rc not in (0, 1):
                print(f"{label}: exit code {rc}")
                return 2
            times.append(dt)
        best = min(times)
        verdict = "" if target is None else (" (target < %.0f s: %s)" % (target, "ok" if best < target else "MISSED"))
        ok &= target is None or best < target
        print(f"{label:<16} best {best:6.2f} s  runs {' '.join(f'{t:.2f}' for t in times)}{verdict}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
