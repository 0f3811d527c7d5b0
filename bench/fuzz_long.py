"""Long fuzzing run (issue 7): 10,000+ mutated URDF/xacro/material cases, every command, 2 workers.

Usage::

    python bench/fuzz_long.py                 # cases 0..9999
    python bench/fuzz_long.py --start 20000 --cases 50000 --workers 4
    python bench/fuzz_long.py --case 1810 --show   # rerun one case with a traceback, keep its files

A case is reproducible from its number (tests/bad/fuzzlib.py). Exit code 1 when any case broke the
property (exception, traceback, "internal error", hang, exit code outside 0/1/2, a file opened
outside the allowed roots, network or subprocess); the failures go to out/fuzz_failures.json.
"""

from __future__ import annotations

import argparse
import collections
import json
import multiprocessing as mp
import os
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tests" / "bad"))

import fuzzlib  # noqa: E402
import harness  # noqa: E402

_seeds = None
_scratch = None


def _init(scratch):
    global _seeds, _scratch
    harness.prepare_worker(memory_cap=True)
    _seeds = fuzzlib.seed_files()
    _scratch = Path(scratch)


def _one(case):
    r = fuzzlib.run_case(case, _seeds, _scratch)
    return {k: r[k] for k in ("case", "command", "what", "code", "problems", "seconds", "crash", "stderr")}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--case", type=int, help="run this one case in-process")
    ap.add_argument("--show", action="store_true", help="with --case: print the input and keep it")
    a = ap.parse_args()
    scratch = Path(tempfile.mkdtemp(prefix="fuzz_long_"))
    if a.case is not None:
        _init(scratch)
        os.environ["MYRABOT_DESC_DEBUG"] = "1"    # let the traceback through
        work = scratch / "show"
        src, command, what = fuzzlib.make_case(a.case, _seeds, work / "in")
        print(f"case {a.case}: {command} on {src} ({what})")
        r = harness.invoke(harness.argv_for(command, src, work / "out"), time_limit=60)
        print(f"exit {r['code']} in {r['seconds']:.2f} s\n{r['stderr']}{r['stdout'][-2000:]}{r['crash'] or ''}")
        return 0
    t0 = time.time()
    codes: collections.Counter = collections.Counter()
    per_cmd: collections.Counter = collections.Counter()
    failures, slowest = [], []
    ctx = mp.get_context("fork")
    with ctx.Pool(a.workers, initializer=_init, initargs=(str(scratch),), maxtasksperchild=2000) as pool:
        pending = [(c, pool.apply_async(_one, (c,))) for c in range(a.start, a.start + a.cases)]
        for i, (c, p) in enumerate(pending, 1):
            try:
                r = p.get(timeout=120)
            except mp.TimeoutError:
                r = {"case": c, "command": "?", "what": "?", "code": None, "seconds": 120,
                     "problems": ["still running after 120 s (hang in C code?)"], "crash": None, "stderr": ""}
            codes[r["code"]] += 1
            per_cmd[r["command"]] += 1
            slowest = sorted(slowest + [(r["seconds"], c, r["command"], r["what"])], reverse=True)[:5]
            if r["problems"]:
                failures.append(r)
                print(f"FAIL case {c}: {r['command']} on {r['what']}: {r['problems'][0][:200]}", flush=True)
            if i % 1000 == 0:
                print(f"{i} cases, {len(failures)} failures, {time.time() - t0:.0f} s", flush=True)
    wall = time.time() - t0
    print(f"\n{a.cases} cases (#{a.start}..#{a.start + a.cases - 1}) in {wall:.0f} s with {a.workers} workers")
    print("commands: " + ", ".join(f"{k} {v}" for k, v in sorted(per_cmd.items())))
    print("exit codes: " + ", ".join(f"{k}: {v}" for k, v in sorted(codes.items(), key=lambda kv: str(kv[0]))))
    print("slowest: " + "; ".join(f"#{c} {cmd} {what} {s:.1f} s" for s, c, cmd, what in slowest))
    print(f"failures: {len(failures)}")
    if failures:
        out = REPO / "out"
        out.mkdir(exist_ok=True)
        (out / "fuzz_failures.json").write_text(json.dumps(failures, indent=1))
        print(f"details in {out / 'fuzz_failures.json'}; rerun one with --case N --show")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
