"""`myrabot-desc build` against the `xacro` CLI on every robot of the real-robot corpus (tests/corpus).

    .venv/bin/python bench/bench_corpus_build.py [--repeat N] [--only ID,ID]

Each robot of tests/corpus/robots.yaml is built by both tools as fresh processes (imports
included), interleaved, best of N, with its xacro args and environment; the xacro CLI resolves
`$(find)` through the test shim (tests/corpus_shim, CORPUS_PACKAGE_PATH). Robots that `build`
refuses today (exit 2) are listed, not timed. Target (issue 13): build <= 0.8x xacro's wall time
on every corpus robot.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import BIN, ROOT, best_of, bench_env, fmt_s, save, table  # noqa: E402

CORPUS = ROOT / "tests" / "corpus"
SHIM = ROOT / "tests" / "corpus_shim"
TARGET = 0.8


def main(argv=None) -> int:
    import yaml

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5, help="runs per command (best is kept) [5]")
    ap.add_argument("--only", default="", help="comma-separated robot ids (default: all)")
    a = ap.parse_args(argv)
    only = set(filter(None, a.only.split(",")))
    robots = [r for r in yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"] if not only or r["id"] in only]
    rows, res, refused = [], {}, []
    for r in robots:
        pp = CORPUS / r.get("package_path", ".")
        env = dict(bench_env(), PYTHONPATH=str(SHIM), CORPUS_PACKAGE_PATH=str(pp),
                   **{k: str(v) for k, v in r.get("env", {}).items()})
        top, args = str(CORPUS / r["top"]), r.get("args", "").split()
        ours = [str(BIN / "myrabot-desc"), "build", top, *args, "--package-path", str(pp), "-o", "-"]
        if r.get("legacy"):
            ours += ["--legacy", "off", "--allow-errors"]  # what xacro does with legacy tags
        probe = subprocess.run(ours, env=env, capture_output=True)
        if probe.returncode not in (0, 1):
            refused.append(f"{r['id']}: {probe.stderr.decode(errors='replace').splitlines()[0][:160]}")
            continue
        t = best_of({"ours": ours, "xacro": [str(BIN / "xacro"), top, *args]}, a.repeat, env=env,
                    ok=(0, 1))
        ratio = t["ours"]["wall"] / t["xacro"]["wall"]
        res[r["id"]] = {"ours_wall": t["ours"]["wall"], "ours_cpu": t["ours"]["cpu"],
                        "xacro_wall": t["xacro"]["wall"], "xacro_cpu": t["xacro"]["cpu"], "ratio": ratio,
                        "n": a.repeat, "meets": ratio <= TARGET}
        rows.append([r["id"], fmt_s(t["ours"]["wall"]), fmt_s(t["ours"]["cpu"]), fmt_s(t["xacro"]["wall"]),
                     fmt_s(t["xacro"]["cpu"]), f"{ratio:.2f}×", "yes" if ratio <= TARGET else "NO"])
    print(f"build vs xacro CLI on the corpus (fresh processes, interleaved, best of {a.repeat})")
    print(table(rows, ["robot", "build wall", "build cpu", "xacro wall", "xacro cpu", "build/xacro",
                       f"<= {TARGET}×"]))
    if refused:
        print("not timed (build refuses them today):\n  " + "\n  ".join(refused))
    met = sum(v["meets"] for v in res.values())
    print(f"{met} of {len(res)} timed robots meet build <= {TARGET}× xacro")
    print(f"saved {save('corpus_build', {'robots': res, 'refused': refused})}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
