"""The physics verdicts' speed targets (issue 24), each paired with its peer in the same run.

    .venv/bin/python bench/bench_physics.py [--repeat N] [--only settle|check]

* ``sim settle`` of the bundled MYRAbot, the whole command (interpreter start, build, MJCF in memory,
  3 s of MuJoCo at 2 ms, the verdict) against a plain MuJoCo script doing the same steps on the same
  MJCF (written once beforehand by ``convert --to mjcf``): load it on a floor, the ``home`` keyframe,
  1500 ``mj_step``. Target: ours <= 1.5 s wall.
* ``check --inertia`` of every corpus robot (its xacro args, one process each, as CI runs it) with the
  new rules (P005 self-collision, P006 gravity torque) against the same command with
  ``--ignore P005,P006``; interleaved, best of N per robot, summed over the corpus. Target: the rules
  add <= 20 %.

Fresh processes, wall clock and the child's CPU time (wait4), best of N (bench/_timing.py).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import BIN, OUT, ROOT, best_of, bench_env, fmt_s, save, table  # noqa: E402

CORPUS = ROOT / "tests" / "corpus"
SETTLE_TARGET = 1.5          # s, whole command
CHECK_TARGET = 1.20          # with / without the new rules

PLAIN = """
import os
os.environ.setdefault("MUJOCO_GL", "disable")
import mujoco
m = mujoco.MjModel.from_xml_path({scene!r})
d = mujoco.MjData(m)
mujoco.mj_resetDataKeyframe(m, d, 0)
for _ in range(1500):
    mujoco.mj_step(m, d)
assert abs(d.qpos[2] - m.key_qpos[0][2]) < 0.02
"""


def settle(repeat: int) -> dict:
    folder = OUT / "physics"
    folder.mkdir(parents=True, exist_ok=True)
    import subprocess

    subprocess.run([str(BIN / "myrabot-desc"), "convert", "--to", "mjcf", "-o", str(folder / "myrabot.xml")],
                   check=True, env=bench_env(), capture_output=True)
    cmds = {"ours": [str(BIN / "myrabot-desc"), "sim", "settle"],
            "plain": [sys.executable, "-c", PLAIN.format(scene=str(folder / "scene.xml"))]}
    t = best_of(cmds, repeat, cwd=folder)
    ours, plain = t["ours"], t["plain"]
    print(table([["sim settle (bundled MYRAbot, 3 s)", fmt_s(ours["wall"]), fmt_s(ours["cpu"]),
                  fmt_s(plain["wall"]), fmt_s(plain["cpu"]), f"<= {SETTLE_TARGET:g} s",
                  "yes" if ours["wall"] <= SETTLE_TARGET else "NO"]],
                ["what", "ours wall", "ours cpu", "plain MuJoCo wall", "plain cpu", "target", "met"]))
    return {"ours_wall": ours["wall"], "ours_cpu": ours["cpu"], "plain_wall": plain["wall"],
            "plain_cpu": plain["cpu"], "target": SETTLE_TARGET, "met": ours["wall"] <= SETTLE_TARGET}


def check(repeat: int) -> dict:
    import yaml

    robots = yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]
    rows, res = [], {}
    tot = {"with": [0.0, 0.0], "without": [0.0, 0.0]}
    for r in robots:
        pp = CORPUS / r.get("package_path", ".")
        env = dict(bench_env(), **{k: str(v) for k, v in r.get("env", {}).items()})
        base = [str(BIN / "myrabot-desc"), "check", "--inertia", "--no-cache", "-o", "/dev/null",
                str(CORPUS / r["top"]), *r.get("args", "").split(), "--package-path", str(pp)]
        t = best_of({"with": base, "without": base + ["--ignore", "P005,P006"]}, repeat, env=env, ok=(0, 1, 2))
        for k in tot:
            tot[k][0] += t[k]["wall"]
            tot[k][1] += t[k]["cpu"]
        res[r["id"]] = {k: {"wall": t[k]["wall"], "cpu": t[k]["cpu"]} for k in t}
        rows.append([r["id"], fmt_s(t["with"]["wall"]), fmt_s(t["without"]["wall"]),
                     f"{t['with']['wall'] / t['without']['wall']:.2f}×", fmt_s(t["with"]["cpu"]),
                     fmt_s(t["without"]["cpu"]), f"{t['with']['cpu'] / t['without']['cpu']:.2f}×"])
    wall, cpu = tot["with"][0] / tot["without"][0], tot["with"][1] / tot["without"][1]
    rows.append(["corpus total", fmt_s(tot["with"][0]), fmt_s(tot["without"][0]), f"{wall:.2f}×",
                 fmt_s(tot["with"][1]), fmt_s(tot["without"][1]), f"{cpu:.2f}×"])
    print(table(rows, ["robot", "with wall", "without wall", "ratio", "with cpu", "without cpu", "cpu ratio"]))
    print(f"P005 + P006 add {100 * (wall - 1):.1f} % wall, {100 * (cpu - 1):.1f} % CPU to `check --inertia` on the corpus "
          f"(target <= {100 * (CHECK_TARGET - 1):.0f} %: {'met' if wall <= CHECK_TARGET else 'MISSED'})")
    return {"robots": res, "wall_ratio": wall, "cpu_ratio": cpu, "target": CHECK_TARGET, "met": wall <= CHECK_TARGET}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5, help="runs per command (best is kept) [5]")
    ap.add_argument("--only", choices=["settle", "check"], default=None)
    a = ap.parse_args(argv)
    out = {}
    if a.only in (None, "settle"):
        out["settle"] = settle(a.repeat)
    if a.only in (None, "check"):
        out["check"] = check(a.repeat)
    print(f"saved {save('physics', out)}")
    return 0 if all(v["met"] for v in out.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
