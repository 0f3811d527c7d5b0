"""`check` against `build` of the same robot: the bundled MYRAbot and every robot of the real-robot
corpus (tests/corpus/robots.yaml), each pair as fresh processes, interleaved, best of N, CPU time.

Targets (issue 29): check <= 1.5x build's CPU on the bundled robot, <= 1.8x on every corpus robot.
Both commands read the same inputs with the same options and start from the same state: bytecode
caches on (out/bench/pycache, as after `pip install`), files in the page cache (one warm-up run of
each), and no result cache for check (`--no-cache`: what a pre-commit run pays after the model
changed; the warm-cache figure is bench_lint.py's). CPU is the child's user+sys; wall is beside it.
The machine's `python -c pass` and `python -c "import numpy"` are timed in the same run.

    .venv/bin/python bench/bench_check_vs_build.py [--repeat N] [--only ID,ID] [--no-corpus] [--before DIR]

The bundled robot's pair runs at least 21 times (a pair is a quarter of a second): on a shared
2-core machine one command's CPU time spreads over 5-10 % between runs, so the ratio of two bests of
a few runs moves by several hundredths, where the bests of a few tens agree with their medians.

--before DIR: also time check with the package of DIR first on PYTHONPATH (a checkout or `git archive`
of earlier code, with its xacro/ and meshes/), interleaved with the pair.

With valgrind installed, the bundled robot's pair is also counted in instructions (callgrind, one run
each, PYTHONHASHSEED=0): the same count on every run, whatever else the machine does, where CPU
times on a shared machine move by several percent between runs. The check is counted twice: here
(this repository's pyproject.toml has a [tool.myrabot-desc] table, which a configured project pays
for: `tomllib`) and from a folder without configuration.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import BIN, ROOT, baseline, baseline_text, bench_env, fmt_s, machine, run_once, save, table  # noqa: E402

CORPUS = ROOT / "tests" / "corpus"
BUNDLED, EACH = 1.5, 1.8
BUNDLED_RUNS = 21


def pair(inputs: list[str], repeat: int, env: dict, before: str = "") -> dict:
    cli = str(BIN / "myrabot-desc")
    cmds = {"build": [cli, "build", *inputs, "-o", "/dev/null"],
            "check": [cli, "check", "--no-cache", *inputs, "-o", "/dev/null"]}
    envs = {"build": env, "check": env}
    if before:
        cmds["check (before)"] = cmds["check"]
        envs["check (before)"] = {**env, "PYTHONPATH": before}
    res = {k: {"wall": [], "cpu": []} for k in cmds}
    for k in range(repeat + 1):             # the first round warms the page and bytecode caches
        for name, argv in cmds.items():
            wall, cpu, rc, err = run_once(argv, env=envs[name])
            # check exits 1 with findings and 2 with error findings; an input build refuses fails
            if rc not in (0, 1, 2) or (name == "build" and rc == 2):
                raise SystemExit(f"{name} exited {rc}: {err.decode(errors='replace')[-200:]}")
            if k:
                res[name]["wall"].append(wall)
                res[name]["cpu"].append(cpu)
    return {k: {"wall": min(v["wall"]), "cpu": min(v["cpu"]), "n": repeat} for k, v in res.items()}


def instructions(argv: list, env: dict, cwd=None) -> int | None:
    """Instructions executed by ``argv`` (callgrind's count, the child and its interpreter start
    included), or None without valgrind."""
    vg = shutil.which("valgrind")
    if vg is None:
        return None
    subprocess.run(argv, env=env, cwd=cwd, capture_output=True)      # bytecode caches written
    p = subprocess.run([vg, "--tool=callgrind", "--callgrind-out-file=/dev/null", *argv], env=env, cwd=cwd,
                       capture_output=True, text=True)
    m = re.search(r"Collected : (\d+)", p.stderr)
    return int(m.group(1)) if m else None


def counted(env: dict) -> dict | None:
    """The bundled robot's build and check in instructions (see the module docstring)."""
    cli = str(BIN / "myrabot-desc")
    env = {**env, "PYTHONHASHSEED": "0"}
    with tempfile.TemporaryDirectory() as bare:
        got = {"build": instructions([cli, "build", "-o", os.devnull], env, ROOT),
               "check": instructions([cli, "check", "--no-cache", "-o", os.devnull], env, ROOT),
               "check, no configuration": instructions([cli, "check", "--no-cache", "-o", os.devnull], env, bare)}
    return got if all(got.values()) else None


def main(argv=None) -> int:
    import yaml

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=7, help="runs per command (best is kept) [7; the bundled robot 21]")
    ap.add_argument("--only", default="", help="comma-separated corpus ids (default: all)")
    ap.add_argument("--no-corpus", action="store_true", help="the bundled robot only")
    ap.add_argument("--before", default="", help="folder with earlier code, its check timed beside")
    a = ap.parse_args(argv)
    env = bench_env()
    base = baseline(max(a.repeat, 5))
    only = set(filter(None, a.only.split(",")))
    todo = [("bundled MYRAbot", [], {}, BUNDLED, max(a.repeat, BUNDLED_RUNS))]
    if not a.no_corpus:
        for r in yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]:
            if only and r["id"] not in only:
                continue
            inputs = [str(CORPUS / r["top"]), *r.get("args", "").split(), "--package-path",
                      str(CORPUS / r.get("package_path", "."))]
            todo.append((r["id"], inputs, {k: str(v) for k, v in r.get("env", {}).items()}, EACH, a.repeat))
    rows, res, met = [], {}, 0
    for name, inputs, extra, limit, runs in todo:
        try:
            t = pair(inputs, runs, {**env, **extra}, a.before)
        except SystemExit as exc:       # an input build or check refuses: listed, not timed
            rows.append([name, "—", "—", "—", "—", "—", "—", f"not timed: {str(exc)[:80]}"])
            continue
        b, c = t["build"], t["check"]
        ratio = c["cpu"] / b["cpu"]
        ok = ratio <= limit
        met += ok
        res[name] = {"build": b, "check": c, "cpu_ratio": ratio, "limit": limit, "met": ok}
        was = ""
        if "check (before)" in t:
            res[name]["check_before"] = t["check (before)"]
            was = f"{t['check (before)']['cpu'] / b['cpu']:.2f}× ({fmt_s(t['check (before)']['cpu'])})"
        rows.append([name, fmt_s(b["cpu"]), fmt_s(c["cpu"]), fmt_s(b["wall"]), fmt_s(c["wall"]), f"{ratio:.2f}×",
                     was or "—", f"≤ {limit}×: " + ("yes" if ok else "NO")])
    m = machine()
    print(f"check --no-cache vs build, fresh processes, interleaved, best of {a.repeat} "
          f"(the bundled robot: {max(a.repeat, BUNDLED_RUNS)})")
    print(table(rows, ["robot", "build cpu", "check cpu", "build wall", "check wall", "cpu ratio",
                       "before: ratio (cpu)", "target"]))
    print(f"{met} of {len(res)} timed robots meet the target")
    ins = counted(env)
    if ins is not None:
        b = ins["build"]
        print(f"bundled MYRAbot in instructions (callgrind): build {b / 1e6:.0f} M, check {ins['check'] / 1e6:.0f} M "
              f"({ins['check'] / b:.3f}×), check from a folder without configuration "
              f"{ins['check, no configuration'] / 1e6:.0f} M ({ins['check, no configuration'] / b:.3f}×)")
    print(f"this machine: {baseline_text(base)}; {m['cores']} cores, {m['cpu']}, Python {m['python']}, "
          f"{m['date']}, load average {m['load']:.1f}")
    print(f"saved {save('check_vs_build', {'robots': res, 'baseline': base, 'instructions': ins})}")
    return 0 if met == len(res) else 1      # (make bench lists the benches that missed a target)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
