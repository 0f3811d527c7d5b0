"""Scale targets of issue 17: big generated trees through check and convert, as fresh processes.

Targets: check and convert of a 20,000-link star in <= 5 s each; of a 5,000-link chain in <= 3 s,
without a crash (Pinocchio used to SIGSEGV past ~4,000 joints deep). Trees from bench/gen_tree.py.
Times are wall and child CPU (best of N; the CPU figure is the one to trust on a shared machine).
Each child runs under a memory cap (--mem-gb, address space) and a time limit (--timeout): a
conversion that grows without bound fails its row instead of the machine.

    .venv/bin/python bench/bench_scale.py [--repeat N] [--only check,sdf] [--kinds star]
"""

from __future__ import annotations

import argparse
import resource
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import BIN, bench_env, run_once  # noqa: E402
from gen_tree import tree_urdf  # noqa: E402

CASES = [("star", 20_000, 5.0), ("chain", 5_000, 3.0)]
COMMANDS = ("check", "sdf", "mjcf")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--only", default=",".join(COMMANDS), help="commands to time: check,sdf,mjcf")
    ap.add_argument("--kinds", default="star,chain", help="trees: star,chain")
    ap.add_argument("--mem-gb", type=float, default=4.0, help="address-space cap of each child (GB)")
    ap.add_argument("--timeout", type=int, default=120, help="CPU seconds allowed to each child")
    args = ap.parse_args()
    only, kinds = set(args.only.split(",")), set(args.kinds.split(","))
    # inherited by every child: a runaway stops at the cap (MemoryError or SIGKILL: exit < 0, a NO row)
    cap = int(args.mem_gb * 2**30)
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    resource.setrlimit(resource.RLIMIT_CPU, (args.timeout, args.timeout + 5))
    work = Path(tempfile.mkdtemp(prefix="bench_scale_"))
    exe = str(BIN / "myrabot-desc")
    rows, ok = [], True
    for kind, n, target in CASES:
        if kind not in kinds:
            continue
        src = work / f"{kind}_{n}.urdf"
        src.write_text(tree_urdf(kind, n))
        for name, argv in [("check", ["check", "--no-cache", str(src), "-o", "/dev/null"]),
                           ("sdf", ["convert", "--to", "sdf", str(src), "-o", str(work / "o.sdf")]),
                           ("mjcf", ["convert", "--to", "mjcf", str(src), "-o", str(work / "m" / "o.xml")])]:
            if name not in only:
                continue
            runs = [run_once([exe, *argv], env=bench_env()) for _ in range(args.repeat)]
            wall = min(r[0] for r in runs)
            cpu = min(r[1] for r in runs)
            rc = runs[0][2]
            crashed = rc < 0 or rc > 2
            met = cpu <= target and not crashed
            ok &= met
            why = runs[0][3].decode(errors="replace").strip().splitlines()[-1:] if rc else []
            rows.append(f"| {kind} {n:,} | {name if name == 'check' else 'convert ' + name} | {wall:.2f} | {cpu:.2f} | "
                        f"{rc} | <= {target:g} s | {'yes' if met else 'NO'} | {' '.join(why)[:100]} |")
    print("| tree | command | wall s | CPU s | exit | target | met | note |\n|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    print("all targets met" if ok else "targets missed: see the NO rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
