"""What the hostile corpus costs: every input of tests/bad through every command (as
tests/hardening/test_hostile_inputs.py runs them: forked workers, the harness's audit hook, CPU
limit and memory cap), with the CPU seconds of each run and the peak resident memory of the
workers (an upper bound of any one run's: a worker runs many).

    .venv/bin/python bench/hostile_costs.py [--jobs 2]

Prints the slowest runs and the totals; exits 1 when a run has a problem or passes the issue's
bounds (10 s of CPU, 1 GB).
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import resource
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
BAD = HERE.parent / "tests" / "bad"
sys.path.insert(0, str(BAD))

import harness  # noqa: E402
import make_corpus  # noqa: E402


def one(task):
    r = harness.run_one(task)
    r["maxrss"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return {k: r[k] for k in ("case", "command", "code", "seconds", "maxrss", "problems")}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    cases = [c for c in json.loads((BAD / "cases.json").read_text()) if c["targets"] != "asset"]
    with tempfile.TemporaryDirectory() as tmp:
        root = make_corpus.materialize(Path(tmp) / "bad")
        tasks = []
        for c in cases:
            for cmd in (["materials"] if c["targets"] == "material" else list(harness.COMMANDS)):
                tasks.append((c["path"], cmd, c["expect"], str(root), str(Path(tmp) / "out"),
                              harness.extra_args(c["path"])))
        with mp.get_context("fork").Pool(args.jobs, initializer=harness.prepare_capped_worker) as pool:
            results = pool.map(one, tasks, chunksize=4)
    results.sort(key=lambda r: -r["seconds"])
    print(f"{len(results)} runs of {len(cases)} inputs")
    for r in results[:10]:
        print(f"  {r['seconds']:6.2f} s  {r['case']} [{r['command']}] exit {r['code']}")
    peak = max(r["maxrss"] for r in results)
    print(f"slowest {results[0]['seconds']:.2f} s of CPU; workers' peak resident memory {peak / 2**20:.0f} MB")
    bad = [r for r in results if r["problems"]]
    for r in bad[:20]:
        print(f"PROBLEM {r['case']} [{r['command']}]: {'; '.join(r['problems'])}")
    return 1 if bad or results[0]["seconds"] > harness.TIME_LIMIT or peak > (1 << 30) else 0


if __name__ == "__main__":
    sys.exit(main())
