"""Scale targets of issue 17: big generated trees through check and convert, as fresh processes.

Targets: check and convert of a 20,000-link star in <= 5 s each; of a 5,000-link chain in <= 3 s,
without a crash (Pinocchio used to SIGSEGV past ~4,000 joints deep). Trees from bench/gen_tree.py.
Times are wall and child CPU (best of N; the CPU figure is the one to trust on a shared machine).

    .venv/bin/python bench/bench_scale.py [--repeat N]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import BIN, bench_env, run_once  # noqa: E402
from gen_tree import tree_urdf  # noqa: E402

CASES = [("star", 20_000, 5.0), ("chain", 5_000, 3.0)]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench_scale_"))
    exe = str(BIN / "myrabot-desc")
    rows, ok = [], True
    for kind, n, target in CASES:
        src = work / f"{kind}_{n}.urdf"
        src.write_text(tree_urdf(kind, n))
        for name, argv in [("check", ["check", str(src), "-o", "/dev/null"]),
                           ("convert sdf", ["convert", "--to", "sdf", str(src), "-o", str(work / "o.sdf")]),
                           ("convert mjcf", ["convert", "--to", "mjcf", str(src), "-o", str(work / "m" / "o.xml")])]:
            runs = [run_once([exe, *argv], env=bench_env()) for _ in range(args.repeat)]
            wall = min(r[0] for r in runs)
            cpu = min(r[1] for r in runs)
            rc = runs[0][2]
            crashed = rc < 0 or rc > 2
            met = cpu <= target and not crashed
            ok &= met
            rows.append(f"| {kind} {n:,} | {name} | {wall:.2f} | {cpu:.2f} | {rc} | <= {target:g} s | "
                        f"{'yes' if met else 'NO'} |")
    print("| tree | command | wall s | CPU s | exit | target | met |\n|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    print("all targets met" if ok else "targets missed: see the NO rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
