"""Time `myrabot-desc convert --to sdf` on the bundled MYRAbot against `ign sdf -p` on the same URDF.

Both are whole processes, started cold, output to a file; the median of N runs is reported.
`ign sdf -p` gets the already-built URDF (it cannot read xacro), so our time includes the
xacro build that ign's does not. Also reported: our in-process time (build + load + SDF) and
the MJCF conversion.

    .venv/bin/python bench/bench_convert.py [--repeat N]
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def timed(cmd, **kw) -> float:
    t = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kw)
    if r.returncode != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}")
    return time.perf_counter() - t


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    me = [sys.executable, "-m", "myrabot_desc"]
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        subprocess.run([*me, "build", "-o", str(d / "myrabot.urdf")], check=True, stderr=subprocess.DEVNULL)
        ours = [timed([*me, "convert", "-o", str(d / "ours.sdf"), "-q"]) for _ in range(args.repeat)]
        print(f"myrabot-desc convert --to sdf (xacro build included): median {statistics.median(ours):.3f} s "
              f"(min {min(ours):.3f})")
        from myrabot_desc.convert.sdf import to_sdf
        from myrabot_desc.model.loader import load_robot

        lib = []
        for _ in range(args.repeat):
            t = time.perf_counter()
            to_sdf(load_robot(None))
            lib.append(time.perf_counter() - t)
        print(f"  in process (build + load + SDF): median {statistics.median(lib):.3f} s")
        robot = load_robot(None)
        conv = []
        for _ in range(args.repeat):
            t = time.perf_counter()
            to_sdf(robot)
            conv.append(time.perf_counter() - t)
        print(f"  in process (SDF from a loaded model): median {statistics.median(conv) * 1000:.1f} ms")
        mj = [timed([*me, "convert", "--to", "mjcf", "-o", str(d / "mj" / "myrabot.xml"), "-q"])
              for _ in range(args.repeat)]
        print(f"myrabot-desc convert --to mjcf: median {statistics.median(mj):.3f} s")
        if shutil.which("ign"):
            ign = [timed(["ign", "sdf", "-p", str(d / "myrabot.urdf")]) for _ in range(args.repeat)]
            print(f"ign sdf -p (URDF already built): median {statistics.median(ign):.3f} s (min {min(ign):.3f})")
        else:
            print("ign sdf -p: not installed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
