"""Loading and checking URDFs: `myrabot-desc check`/`info` against `check_urdf` and Pinocchio.

    .venv/bin/python bench/bench_load.py [--repeat N]

* all 69 example-robot-data URDFs (no mesh loading): our `check` in one call
  (target: under 10 s); `check_urdf` (urdfdom, C++) run once per file; one
  Python process loading each with Pinocchio's `buildModelFromUrdf`;
* the bundled MYRAbot URDF: `myrabot-desc info` (read + summary), `check_urdf`,
  and a Python process with Pinocchio.
Fresh processes, interleaved, best of N.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import sysconfig
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import BIN, ROOT, bench_env, best_of, fmt_s, have, save, table  # noqa: E402

ROBOTS = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"

PIN = """import sys, pinocchio as pin
ok = 0
for f in sys.argv[1:]:
    try:
        pin.buildModelFromUrdf(f)
        ok += 1
    except Exception:
        pass
print(ok)
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3, help="runs per command (best is kept) [3]")
    a = ap.parse_args(argv)
    files = [str(p) for p in sorted(ROBOTS.rglob("*.urdf"))]
    py, cli = str(BIN / "python"), str(BIN / "myrabot-desc")
    out = ROOT / "out" / "bench"
    out.mkdir(parents=True, exist_ok=True)
    urdf = out / "myrabot.urdf"
    subprocess.run([cli, "build", "-o", str(urdf)], check=True, capture_output=True, env=bench_env())
    check_urdf = "/usr/bin/check_urdf" if Path("/usr/bin/check_urdf").exists() else (
        "check_urdf" if have("check_urdf") else None)

    # --no-cache: the work itself (the result cache would answer every run after the first)
    cmds = {"myrabot-desc check (69 files, one call)": [cli, "check", "--no-cache", "--format", "json", "-o", "/dev/null",
                                                        *files],
            "Pinocchio buildModelFromUrdf (one process)": [py, "-c", PIN, *files]}
    r = best_of(cmds, a.repeat, ok=(0, 1))
    rows, res = [], {"files": len(files)}
    if check_urdf:
        # one process per file, as a CI step would run it; a sum of the best-of-N per file
        per = best_of({f: [check_urdf, f] for f in files}, a.repeat, ok=(0, 255), warmup=0)
        r["check_urdf (69 processes, summed)"] = {"wall": sum(v["wall"] for v in per.values()),
                                                  "cpu": sum(v["cpu"] for v in per.values()), "n": a.repeat}
    ours = r["myrabot-desc check (69 files, one call)"]["wall"]
    for k, v in r.items():
        rows.append(["69 example-robot-data URDFs", k, fmt_s(v["wall"]), fmt_s(v["cpu"]), f"{v['wall'] / ours:.2f}"])
    res["all69"] = r
    res["all69_meets_10s"] = ours < 10.0

    one = {"myrabot-desc info": [cli, "info", "--no-tree", str(urdf)],
           "Pinocchio buildModelFromUrdf": [py, "-c", PIN, str(urdf)]}
    if check_urdf:
        one["check_urdf"] = [check_urdf, str(urdf)]
    r1 = best_of(one, a.repeat * 3, ok=(0, 1))
    base = r1["myrabot-desc info"]["wall"]
    for k, v in r1.items():
        rows.append(["bundled MYRAbot URDF", k, fmt_s(v["wall"]), fmt_s(v["cpu"]), f"{v['wall'] / base:.2f}"])
    res["bundled"] = r1
    print(f"load/check (fresh processes, best of {a.repeat}; bundled: best of {a.repeat * 3})")
    print(table(rows, ["input", "command", "wall", "cpu", "time / ours"]))
    print(f"check of all {len(files)} URDFs in one call: {fmt_s(ours)} (target < 10 s: "
          f"{'yes' if ours < 10 else 'NO'})")
    save("load", res)
    return 0


if __name__ == "__main__":
    sys.exit(main())
