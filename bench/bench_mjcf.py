"""Time `myrabot-desc convert --to mjcf` against a checkout of the code before it (the MJCF writer
that went through MuJoCo's URDF compiler), on the bundled MYRAbot and a few real robots.

Both sides are fresh processes of this virtualenv's Python, interleaved (this tree, then the other
with its folder first on PYTHONPATH), best of N; wall clock and the child's CPU (the figure to
trust on a shared machine). The robots: the bundled MYRAbot, corpus robots (a diff-drive base, a
skid-steer, a mobile manipulator with many meshes, an arm) and example-robot-data's Talos.

    .venv/bin/python bench/bench_mjcf.py [--before /work/wt-base] [--repeat N] [--only ID,...]

Without a checkout at --before (``make bench`` elsewhere), only this tree is timed.
"""

from __future__ import annotations

import argparse
import os
import sys
import sysconfig
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import BIN, ROOT, bench_env, run_once  # noqa: E402

CORPUS = ROOT / "tests" / "corpus"
ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
ROBOTS = [
    ("myrabot", []),
    ("turtlebot3_burger", [str(CORPUS / "turtlebot3_description/urdf/turtlebot3_burger.urdf.xacro"),
                           "--package-path", str(CORPUS)]),
    ("husky", [str(CORPUS / "husky_description/urdf/husky.urdf.xacro"), "--package-path", str(CORPUS)]),
    # TIAGo's real inertia errors (I004, I005) stop a conversion unless allowed
    ("tiago", [str(CORPUS / "tiago_description/robots/tiago.urdf.xacro"), "--package-path", str(CORPUS),
               "--allow-errors"]),
    ("ur5e", [str(CORPUS / "ur_description/urdf/ur.urdf.xacro"), "name:=ur5e", "ur_type:=ur5e",
              "--package-path", str(CORPUS)]),
    ("talos", [str(ERD / "talos_data/robots/talos_reduced.urdf")]),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", default="/work/wt-base", help="a checkout of the code to compare with")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--only", default="", help="robot ids, comma-separated")
    args = ap.parse_args()
    before = Path(args.before).resolve()
    sides = {"ours": bench_env()}
    if (before / "myrabot_desc").is_dir():
        env = sides["ours"]
        sides["theirs"] = dict(env, PYTHONPATH=os.pathsep.join(filter(None, [str(before), env.get("PYTHONPATH")])),
                               PYTHONPYCACHEPREFIX=env["PYTHONPYCACHEPREFIX"] + "-before")
        print(f"| robot | this tree: wall s | CPU s | {before.name}: wall s | CPU s | CPU ratio |")
        print("|---|---|---|---|---|---|")
    else:
        print(f"{before}: no checkout to compare with; this tree only")
        print("| robot | wall s | CPU s |\n|---|---|---|")
    only = set(filter(None, args.only.split(",")))
    with tempfile.TemporaryDirectory() as d:
        for rid, argv in ROBOTS:
            if only and rid not in only:
                continue
            if argv and not Path(argv[0]).exists():
                print(f"| {rid} | not here |")
                continue
            # the console script: `python -m` from this folder would import this tree's package on both
            # sides (the working folder comes before PYTHONPATH)
            cmd = [str(BIN / "myrabot-desc"), "convert", *argv, "--to", "mjcf", "-q",
                   "-o", str(Path(d) / rid / "robot.xml")]
            res = {side: [] for side in sides}
            for k in range(args.repeat + 1):        # the first round warms caches and is not counted
                for side, env in sides.items():
                    wall, cpu, rc, err = run_once(cmd, env=env)
                    if rc != 0:
                        raise SystemExit(f"{rid} ({side}) exited {rc}: {err.decode(errors='replace')[-400:]}")
                    if k:
                        res[side].append((wall, cpu))
            best = {side: (min(w for w, _ in r), min(c for _, c in r)) for side, r in res.items()}
            row = f"| {rid} | {best['ours'][0]:.2f} | {best['ours'][1]:.2f} |"
            if "theirs" in best:
                row += f" {best['theirs'][0]:.2f} | {best['theirs'][1]:.2f} | {best['ours'][1] / best['theirs'][1]:.2f} |"
            print(row, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
