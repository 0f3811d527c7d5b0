"""Benchmark of ``myrabot-desc sim``: simulated seconds per wall second.

    .venv/bin/python bench/bench_sim.py [--seconds 60] [--repeat 5] [--json] [--only whole]

Measures, on the bundled MYRAbot at a 1 kHz fixed step:

* ``vuelta`` for --seconds simulated (goal: 60 s in under 1 s of wall time),
  the full run (state machine, servos, exact arcs, verdict with the collision
  check and the tip-over margin) and the simulation alone (--no-collisions);
  cold (first call in the process, imports included) and warm (median and best
  of --repeat). Warm runs reuse what the first run derived from the robot (the
  Pinocchio arm, the collision geometry with its meshes, the support polygon:
  sim/prepared.py), as MuJoCo steps an MjModel compiled beforehand; the same run
  with that preparation redone each time is timed too;
* ``escoja`` and ``seguir`` at their default lengths;
* MuJoCo stepping the bundled model's MJCF (``myrabot-desc convert --to mjcf``)
  for the same simulated time at the same 1 ms step: full rigid-body dynamics
  with contacts, no controller, for scale (compiling the MJCF timed apart;
  stepping median and best of --repeat, each from a fresh MjData); the ratio with the robot
  prepared in the run (issue 29: >= 15x) is given in wall and in CPU time, medians both (CPU is
  the figure a shared machine keeps; for it each MuJoCo stepping is paired with a run of ours just
  before it, since this machine's speed drifts by tens of percent within a minute);
* the whole command ``sim vuelta --duration S`` (interpreter start, imports, build,
  run, verdict) against a plain MuJoCo script that imports MuJoCo, compiles the
  converted MJCF (written once beforehand) and steps the same S seconds at 1 ms:
  fresh processes, interleaved, best of --repeat CPU and wall (bench/_timing.py).
  Target (issue 29): ours <= 0.7x the script's CPU.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WHOLE_TARGET = 0.7          # whole command / plain MuJoCo script, CPU

PLAIN = """
import mujoco
m = mujoco.MjModel.from_xml_path({xml!r})
m.opt.timestep = 0.001
d = mujoco.MjData(m)
mujoco.mj_step(m, d, nstep={n})
"""


CPU: dict = {}      # fn -> median CPU seconds of its last timed() (the figure a shared machine keeps)


def timed(fn, repeat):
    walls, cpus = [], []
    out = None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    CPU[fn] = statistics.median(cpus)
    return statistics.median(walls), min(walls), out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--no-mujoco", action="store_true")
    ap.add_argument("--only", choices=["whole"], help="only the whole command vs the plain MuJoCo script")
    a = ap.parse_args(argv)
    S = a.seconds
    if a.only == "whole":
        w = whole_command(S, a.repeat)
        print(json.dumps(w, indent=2) if a.json else format_whole(w, S))
        return 0
    res = {"simulated_s": S, "rate_hz": 1000}

    t0 = time.perf_counter()
    from myrabot_desc.expand.packages import data_root
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import pointing, prepared, scene, vuelta

    robot = load_robot(None)
    res["load_bundled_s"] = round(time.perf_counter() - t0, 3)

    t0 = time.perf_counter()
    r = vuelta.run(robot, duration=S)
    cold = time.perf_counter() - t0
    assert r.passed, r.summary()
    res["vuelta_cold_s"] = round(cold, 3)
    med, best, r = timed(lambda: vuelta.run(robot, duration=S), a.repeat)
    res["vuelta_full_s"] = round(med, 4)
    res["vuelta_full_best_s"] = round(best, 4)
    res["vuelta_full_sim_per_wall"] = round(S / med, 1)

    def unprepared():
        prepared.clear(robot)
        return vuelta.run(robot, duration=S)

    med_p, best_p, _ = timed(unprepared, a.repeat)
    res["vuelta_full_with_preparation_s"] = round(med_p, 4)
    res["vuelta_full_with_preparation_cpu_s"] = round(CPU[unprepared], 4)
    res["vuelta_full_with_preparation_best_s"] = round(best_p, 4)
    med2, _, _ = timed(lambda: vuelta.run(robot, duration=S, check_collisions=False), a.repeat)
    res["vuelta_no_collisions_s"] = round(med2, 4)
    res["vuelta_no_collisions_sim_per_wall"] = round(S / med2, 1)
    res["vuelta_goal_met"] = med < 1.0

    esc = scene.load_layout(data_root() / "layouts" / "escoja.yaml")
    seg = scene.load_layout(data_root() / "layouts" / "seguir.yaml")
    med3, _, e = timed(lambda: pointing.run_escoja(robot, esc, which="1"), max(1, a.repeat // 2))
    res["escoja_s"] = round(med3, 3)
    res["escoja_simulated_s"] = e.duration
    med4, _, s = timed(lambda: pointing.run_seguir(robot, seg), max(1, a.repeat // 2))
    res["seguir_s"] = round(med4, 3)
    res["seguir_simulated_s"] = s.duration

    if not a.no_mujoco:
        res.update(bench_mujoco(S, a.repeat, ours=unprepared))
        if "mujoco_step_s" in res:
            res["ratio_mujoco_over_vuelta"] = round(res["mujoco_step_s"] / med, 1)
            res["ratio_mujoco_over_vuelta_with_preparation"] = round(res["mujoco_step_s"] / med_p, 1)
            # CPU, paired: each MuJoCo stepping right after one run of ours (prepared in the run)
            res["vuelta_full_with_preparation_cpu_s"] = res.pop("paired_ours_cpu_s")
            res["ratio_mujoco_over_vuelta_with_preparation_cpu"] = round(
                res["mujoco_step_cpu_s"] / res["vuelta_full_with_preparation_cpu_s"], 1)

    if not a.no_mujoco:
        res.update(whole_command(S, a.repeat))
    if a.json:
        print(json.dumps(res, indent=2))
    else:
        print(f"sim benchmark: bundled MYRAbot, {S:g} s simulated at 1 kHz ({int(S * 1000)} steps)")
        print(f"  load (build xacro + read)         {res['load_bundled_s']:.3f} s")
        print(f"  vuelta, first call (imports)      {res['vuelta_cold_s']:.3f} s")
        print(f"  vuelta, full verdict              {res['vuelta_full_s']:.4f} s median, "
              f"{res['vuelta_full_best_s']:.4f} s best of {a.repeat} "
              f"= {res['vuelta_full_sim_per_wall']:g} simulated s per wall s "
              f"({'meets' if res['vuelta_goal_met'] else 'misses'} the 60 s < 1 s goal)")
        print(f"    preparing the robot each time   {res['vuelta_full_with_preparation_s']:.4f} s median, "
              f"{res['vuelta_full_with_preparation_best_s']:.4f} s best")
        print(f"  vuelta, no collision check        {res['vuelta_no_collisions_s']:.4f} s  "
              f"= {res['vuelta_no_collisions_sim_per_wall']:g} simulated s per wall s")
        print(f"  escoja ({res['escoja_simulated_s']:g} s simulated)          {res['escoja_s']:.3f} s")
        print(f"  seguir ({res['seguir_simulated_s']:g} s simulated)         {res['seguir_s']:.3f} s")
        if "mujoco_step_s" in res:
            print(f"  MuJoCo {res['mujoco_version']}, MJCF of the bundled model ({res['mujoco_nbody']} bodies, "
                  f"nq {res['mujoco_nq']}), {S:g} s at 1 ms:")
            print(f"    compile (MjModel.from_xml_path)     {res['mujoco_compile_s']:.3f} s")
            print(f"    mj_step x {int(S * 1000)} (one call, nstep)    {res['mujoco_step_s']:.3f} s median, "
                  f"{res['mujoco_step_best_s']:.3f} s best = {res['mujoco_sim_per_wall']:g} simulated s per wall s")
            print(f"    Python loop of mj_step              {res['mujoco_loop_s']:.3f} s")
            print(f"  MuJoCo's stepping / vuelta's full run: {res['ratio_mujoco_over_vuelta']:g}x "
                  f"(medians; {res['ratio_mujoco_over_vuelta_with_preparation']:g}x with the robot prepared "
                  f"each time; {res['ratio_mujoco_over_vuelta_with_preparation_cpu']:g}x in CPU time)")
        elif "mujoco_error" in res:
            print(f"  MuJoCo: {res['mujoco_error']}")
        if "whole_ours_cpu_s" in res:
            print(format_whole(res, S))
    return 0


def whole_command(S, repeat) -> dict:
    """``sim vuelta --duration S`` as a user runs it vs a plain MuJoCo script stepping the same S s of
    the converted MJCF; fresh processes, interleaved, best of ``repeat`` (CPU and wall)."""
    sys.path.insert(0, str(ROOT / "bench"))
    from _timing import OUT, bench_env, best_of

    folder = OUT / "sim"
    folder.mkdir(parents=True, exist_ok=True)
    xml = folder / "myrabot.xml"
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "convert", "--to", "mjcf", "-o", str(xml)],
                       capture_output=True, text=True, cwd=ROOT, env=bench_env())
    if p.returncode != 0 or not xml.is_file():
        return {"whole_error": f"convert --to mjcf failed: {p.stderr.strip()[:200]}"}
    n = int(round(S * 1000))
    t = best_of({"ours": [sys.executable, "-m", "myrabot_desc", "sim", "vuelta", "--duration", f"{S:g}"],
                 "plain": [sys.executable, "-c", PLAIN.format(xml=str(xml), n=n)]}, repeat, cwd=ROOT)
    ours, plain = t["ours"], t["plain"]
    return {"whole_ours_cpu_s": round(ours["cpu"], 3), "whole_ours_wall_s": round(ours["wall"], 3),
            "whole_plain_cpu_s": round(plain["cpu"], 3), "whole_plain_wall_s": round(plain["wall"], 3),
            "whole_ratio_cpu": round(ours["cpu"] / plain["cpu"], 2), "whole_target": WHOLE_TARGET,
            "whole_met": ours["cpu"] / plain["cpu"] <= WHOLE_TARGET, "whole_runs": repeat}


def format_whole(w, S) -> str:
    if "whole_error" in w:
        return f"  whole command: {w['whole_error']}"
    return (f"  whole command `sim vuelta --duration {S:g}`  {w['whole_ours_cpu_s']:.3f} s CPU "
            f"({w['whole_ours_wall_s']:.3f} s wall), best of {w['whole_runs']}\n"
            f"  plain MuJoCo script, same {S:g} s of the MJCF  {w['whole_plain_cpu_s']:.3f} s CPU "
            f"({w['whole_plain_wall_s']:.3f} s wall)\n"
            f"  ratio (CPU)  {w['whole_ratio_cpu']:.2f}x  (target <= {w['whole_target']:g}x: "
            f"{'met' if w['whole_met'] else 'NOT met'})")


def bench_mujoco(S, repeat=1, ours=None):
    """MuJoCo stepping the converted MJCF for S s at 1 ms, ``repeat`` times from a fresh MjData;
    ``ours``: a run of ours timed (CPU) just before each stepping, so that both medians come from
    the same stretches of a machine whose speed drifts by tens of percent within a minute."""
    out = {}
    try:
        import mujoco
    except ImportError as exc:
        return {"mujoco_error": f"not installed ({exc})"}
    with tempfile.TemporaryDirectory() as d:
        xml = Path(d) / "myrabot.xml"
        p = subprocess.run([sys.executable, "-m", "myrabot_desc", "convert", "--to", "mjcf", "-o", str(xml)],
                           capture_output=True, text=True, cwd=ROOT)
        if p.returncode != 0 or not xml.is_file():
            return {"mujoco_error": f"convert --to mjcf failed: {p.stderr.strip()[:200]}"}
        t0 = time.perf_counter()
        m = mujoco.MjModel.from_xml_path(str(xml))
        compile_s = time.perf_counter() - t0
    m.opt.timestep = 0.001
    n = int(round(S / m.opt.timestep))
    steps, cpus, paired = [], [], []
    for _ in range(repeat):
        if ours is not None:
            c0 = time.process_time()
            ours()
            paired.append(time.process_time() - c0)
        dd = mujoco.MjData(m)
        t0, c0 = time.perf_counter(), time.process_time()
        mujoco.mj_step(m, dd, nstep=n)
        steps.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    one = statistics.median(steps)
    out["mujoco_step_cpu_s"] = round(statistics.median(cpus), 4)
    if paired:
        out["paired_ours_cpu_s"] = round(statistics.median(paired), 4)
    dd = mujoco.MjData(m)
    t0 = time.perf_counter()
    for _ in range(n):
        mujoco.mj_step(m, dd)
    loop = time.perf_counter() - t0
    out.update(mujoco_version=mujoco.__version__, mujoco_nbody=m.nbody, mujoco_nq=m.nq,
               mujoco_compile_s=round(compile_s, 3), mujoco_step_s=round(one, 3),
               mujoco_step_best_s=round(min(steps), 3), mujoco_loop_s=round(loop, 3),
               mujoco_sim_per_wall=round(S / one, 1), mujoco_final_time=round(dd.time, 3))
    return out


if __name__ == "__main__":
    sys.exit(main())
