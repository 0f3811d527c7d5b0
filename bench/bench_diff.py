"""`myrabot-desc diff FILE --rev A..B` against two `myrabot-desc build`s of the same two revisions.

    .venv/bin/python bench/bench_diff.py [--repeat N]

Two corpus robots' real revisions (tests/fixtures/model_history: Husky's track narrowed, the
UR10e's dynamics update) are committed into a git repository each, and the PR2 (tests/corpus'
pr2_description, the largest corpus robot, 83 files) with one property changed (caster_offset_x
0.2246 -> 0.23) as a second commit. Timed as fresh processes, interleaved, best of N:
`diff --rev HEAD~1..HEAD` (git archive of both revisions, two builds, two loads, the comparison,
`check` on both sides), `diff --no-check`, and the two revisions built one after the other by
`build` (two processes, `sh -c 'build A && build B'`).

Target (issue 26): the default diff (with check) <= 2x the two builds, in CPU time (user + sys of
the process and its children): the figure to read on a shared machine, and the exit code judges
it. Wall time is given too (diff builds its two sides in two processes at once when a core is
idle, diff/run._idle_core, so its wall time is below its CPU time on a quiet machine).
`python -c pass` and `import numpy` (one BLAS thread, as the CLI runs it) are timed in the same
run to scale the figures to another machine: diff pays numpy's import, the two builds do not.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import BIN, ROOT, baseline, baseline_text, bench_env, best_of, fmt_s, save, table  # noqa: E402

HISTORY = ROOT / "tests" / "fixtures" / "model_history"
CASES = {"husky_track_narrowed": ("husky_description/urdf/husky.urdf.xacro", []),
         "ur10e_dynamics_update": ("ur_description/urdf/ur.urdf.xacro", ["name:=ur10e", "ur_type:=ur10e"])}


def repo_of(case: str, dest: Path) -> Path:
    dest.mkdir(parents=True)

    def git(*a):
        subprocess.run(["git", *a], cwd=dest, check=True, capture_output=True)
    git("init", "-q")
    git("config", "user.email", "bench@example.org")
    git("config", "user.name", "bench")
    for side in ("old", "new"):
        for p in dest.iterdir():
            if p.name != ".git":
                shutil.rmtree(p) if p.is_dir() else p.unlink()
        shutil.copytree(HISTORY / case / side, dest, dirs_exist_ok=True)
        git("read-tree", "--empty")
        git("add", "-A")
        git("commit", "-q", "-m", side)
    return dest


def pr2_repo(dest: Path) -> tuple[Path, Path, Path]:
    """pr2_description in a repository, then its caster_offset_x changed; (repo, old tree, new tree)."""
    repo = dest / "pr2"
    shutil.copytree(ROOT / "tests" / "corpus" / "pr2_description", repo / "pr2_description")

    def git(*a):
        subprocess.run(["git", *a], cwd=repo, check=True, capture_output=True)
    git("init", "-q")
    git("config", "user.email", "bench@example.org")
    git("config", "user.name", "bench")
    git("add", "-A")
    git("commit", "-q", "-m", "old")
    old = dest / "pr2_old"
    shutil.copytree(repo, old, ignore=shutil.ignore_patterns(".git"))
    base = repo / "pr2_description" / "urdf" / "base_v0" / "base.urdf.xacro"
    base.write_text(base.read_text().replace('name="caster_offset_x" value="0.2246"', 'name="caster_offset_x" value="0.23"'))
    git("commit", "-q", "-am", "new")
    new = dest / "pr2_new"
    shutil.copytree(repo, new, ignore=shutil.ignore_patterns(".git"))
    return repo, old, new


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5, help="runs per command (best is kept) [5]")
    a = ap.parse_args(argv)
    cli = str(BIN / "myrabot-desc")
    rows, out = [], {}
    with tempfile.TemporaryDirectory() as d:
        runs = [(case, top, args, repo_of(case, Path(d) / case), HISTORY / case / "old", HISTORY / case / "new")
                for case, (top, args) in CASES.items()]
        runs.append(("pr2 (corpus, caster_offset_x)", "pr2_description/robots/pr2.urdf.xacro", [], *pr2_repo(Path(d))))
        for case, top, args, repo, old, new in runs:
            two_builds = ["sh", "-c", f'"$0" build "$1" {" ".join(args)} --package-path "$2" > /dev/null && '
                                      f'"$0" build "$3" {" ".join(args)} --package-path "$4" > /dev/null',
                          cli, str(old / top), str(old), str(new / top), str(new)]
            cmds = {"diff": [cli, "diff", top, *args, "--rev", "HEAD~1..HEAD", "--package-path", "."],
                    "diff --no-check": [cli, "diff", top, *args, "--rev", "HEAD~1..HEAD", "--package-path", ".",
                                        "--no-check"],
                    "two builds": two_builds}
            res = best_of(cmds, a.repeat, cwd=repo, env=bench_env(), ok=(0, 1))
            out[case] = res
            base = res["two builds"]
            for name in ("diff", "diff --no-check", "two builds"):
                r = res[name]
                rows.append([case, name, fmt_s(r["wall"]), fmt_s(r["cpu"]),
                             f"{r['wall'] / base['wall']:.2f}×", f"{r['cpu'] / base['cpu']:.2f}×"])
        ref = baseline(a.repeat)
    print(table(rows, ["revisions", "command", "wall", "cpu", "wall / two builds", "cpu / two builds"]))
    print(f"this machine: {baseline_text(ref)}")
    worst = max(out[c]["diff"]["wall"] / out[c]["two builds"]["wall"] for c in out)
    worst_cpu = max(out[c]["diff"]["cpu"] / out[c]["two builds"]["cpu"] for c in out)
    print(f"target: diff <= 2x two builds in CPU time; worst {worst_cpu:.2f}x cpu "
          f"({'met' if worst_cpu <= 2.0 else 'not met'}), {worst:.2f}x wall")
    save("diff", {"results": out, "reference": ref, "worst_wall_ratio": worst, "worst_cpu_ratio": worst_cpu})
    return 0 if worst_cpu <= 2.0 else 1


if __name__ == "__main__":
    sys.exit(main())
