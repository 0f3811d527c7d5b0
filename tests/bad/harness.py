"""Run myrabot-desc commands in-process on hostile input and watch what they do.

Used by tests/hardening/test_hostile_inputs.py, tests/hardening/test_fuzz.py and bench/fuzz_long.py. Each run happens in a
worker process (forked, so the heavy imports are paid once) with:

* a Python audit hook recording every ``open`` (path), ``socket.connect``, ``subprocess.Popen``,
  ``os.system``, ``os.exec*``, ``os.posix_spawn`` and ``os.fork`` -- C libraries that open files
  themselves (libxml2, MuJoCo, urdfdom) are not seen by it; the strace test covers those;
* a CPU-time limit (``ITIMER_PROF``) and a wall-clock limit six times longer for runs that block
  (a hang inside C code is caught by the parent's timeout);
* in workers, an address-space cap (``cap_memory``): a bomb fails its run, not the machine;
* click's CliRunner, so the exit code, stdout and stderr are exactly the CLI's.
"""

from __future__ import annotations

import os
import re
import signal
import sys
from pathlib import Path

TIME_LIMIT = 10.0       # seconds of CPU a run may take: issue 17 bounds every run by 10 s (the
                        # slowest hostile case, block_bomb, takes 3.6-5.4 s of CPU on a loaded 2-core machine)
WALL_FACTOR = 6         # ... and of wall time, this many times longer (a blocked run)
COMMANDS = {
    "build": ["build", "{F}", "-o", "{OUT}/x.urdf"],
    "check": ["check", "{F}"],
    "check-inertia": ["check", "--inertia", "{F}"],
    "info": ["info", "{F}"],
    "convert-sdf": ["convert", "--to", "sdf", "{F}", "-o", "{OUT}/x.sdf"],
    "convert-mjcf": ["convert", "--to", "mjcf", "{F}", "-o", "{OUT}/mjcf/x.xml"],
    "sim-drive": ["sim", "drive", "{F}", "--csv", "{OUT}/x.csv"],
}
MATERIAL_COMMANDS = {"materials": ["materials", "{F}", "-o", "{OUT}/x.sdf"]}
WATCHED = {"socket.connect", "socket.sendto", "subprocess.Popen", "os.system", "os.exec", "os.posix_spawn",
           "os.fork", "os.forkpty", "pty.spawn"}

_state = {"on": False, "opens": [], "events": []}


def _hook(event, args):
    if not _state["on"]:
        return
    if event == "open":
        p = args[0]
        if isinstance(p, int):
            return
        if isinstance(p, bytes):
            p = os.fsdecode(p)
        mode, flags = args[1], args[2]
        writing = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
            (isinstance(flags, int) and flags & (os.O_WRONLY | os.O_RDWR | os.O_CREAT))
        _state["opens"].append(("w:" if writing else "r:") + str(p))
    elif event in WATCHED:
        _state["events"].append(f"{event} {args!r}"[:200])


class Timeout(BaseException):
    """Raised by the alarm; a BaseException so that `except Exception` in the code cannot swallow it."""


def _alarm(signum, frame):
    raise Timeout()


MEMORY_HEADROOM = 1 << 30     # bytes of address space a run may add to the worker's (RLIMIT_AS)


def cap_memory(headroom: int = MEMORY_HEADROOM) -> None:
    """Cap this process's address space at what it maps now plus ``headroom``: a bomb that gets
    past our limits fails its run with MemoryError instead of taking the machine down."""
    import resource

    try:
        with open("/proc/self/status") as f:
            size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize:"))
    except (OSError, StopIteration):
        return
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    cap = size + headroom
    if hard != resource.RLIM_INFINITY:
        cap = min(cap, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    _state["cap"] = headroom


def _recap() -> None:
    """Before each run: the cap is what the worker maps now plus the headroom (a long-lived
    worker's caches grow; the headroom is per run)."""
    import resource

    if not _state.get("cap"):
        return
    resource.setrlimit(resource.RLIMIT_AS, (resource.RLIM_INFINITY, resource.getrlimit(resource.RLIMIT_AS)[1]))
    cap_memory(_state["cap"])


def prepare_worker(memory_cap: bool = False):
    """Import what the commands import (so module loading is not seen as file access), hook audits;
    ``memory_cap``: in a worker process, cap its address space (cap_memory)."""
    import importlib

    os.environ.setdefault("MUJOCO_GL", "disable")   # as convert_mjcf does: no GL probing subprocess
    for mod in ("numpy", "lxml.etree", "xacro", "yaml", "trimesh", "trimesh.exchange.dae", "collada", "yourdfpy",
                "pinocchio", "mujoco", "PIL.Image", "PIL.ImageDraw", "PIL.ImageFont", "scipy.optimize",
                "scipy.spatial", "coal", "networkx",
                "myrabot_desc.commands.main", "myrabot_desc.commands.build", "myrabot_desc.commands.check",
                "myrabot_desc.commands.convert", "myrabot_desc.convert.sdf", "myrabot_desc.convert.mjcf",
                "myrabot_desc.commands.materials", "myrabot_desc.commands.sim", "myrabot_desc.commands.info",
                "myrabot_desc.sim.drive", "myrabot_desc.sim.diffdrive",
                "myrabot_desc.sim.plot", "myrabot_desc.info", "myrabot_desc.checks", "myrabot_desc.model.pin_model",
                "myrabot_desc.model.kinematics", "myrabot_desc.materials.ogre", "myrabot_desc.materials.resolve"):
        try:
            importlib.import_module(mod)
        except Exception:  # optional
            pass
    # trimesh registers loaders lazily; touch them once outside the audit window
    try:
        import trimesh

        trimesh.load(trimesh.util.wrap_as_stream(b"solid x\nendsolid x\n"), file_type="stl")
    except Exception:
        pass
    sys.addaudithook(_hook)
    signal.signal(signal.SIGALRM, _alarm)
    signal.signal(signal.SIGPROF, _alarm)
    os.environ.pop("MYRABOT_DESC_DEBUG", None)
    if memory_cap:
        cap_memory()


def prepare_capped_worker():
    prepare_worker(memory_cap=True)


def invoke(argv: list[str], time_limit: float = TIME_LIMIT, env: dict | None = None) -> dict:
    """Run the CLI in this process. Returns exit code, output, opens, events, seconds, crash text."""
    import time
    import traceback

    from click.testing import CliRunner

    from myrabot_desc.commands.main import main

    runner = CliRunner()
    _state["opens"], _state["events"] = [], []
    crash = None
    t0 = time.perf_counter()
    saved_env = {k: os.environ.get(k) for k in (env or {})}
    os.environ.update(env or {})
    _recap()
    c0 = time.process_time()
    try:
        # The limit is CPU time (the machine may be shared: wall time measures the neighbours);
        # a run blocked without using CPU (a FIFO) is caught by the wall-clock limit, 6x longer.
        signal.setitimer(signal.ITIMER_PROF, time_limit)
        signal.setitimer(signal.ITIMER_REAL, time_limit * WALL_FACTOR)
        _state["on"] = True
        try:
            res = runner.invoke(main, argv, catch_exceptions=True)
        finally:
            _state["on"] = False
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.setitimer(signal.ITIMER_PROF, 0)
        code, out, err = res.exit_code, res.stdout, res.stderr
        if res.exception is not None and not isinstance(res.exception, SystemExit):
            crash = "".join(traceback.format_exception(res.exception))[-3000:]
    except Timeout:
        _state["on"] = False
        code, out, err, crash = None, "", "", f"timeout after {time_limit} s of CPU (or {time_limit * WALL_FACTOR} s)"
    finally:
        # build_cmd turns the cyclic GC off and freezes (a one-shot CLI): a worker runs many
        # commands, so turn it back on and collect what the run left (else it piles up to the cap)
        import gc

        gc.unfreeze()
        gc.enable()
        gc.collect()
        for k, v in saved_env.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    return {"argv": argv, "code": code, "stdout": _clip(out), "stderr": _clip(err),
            "opens": sorted(set(_state["opens"])), "events": list(_state["events"]),
            "seconds": time.process_time() - c0, "wall": time.perf_counter() - t0, "crash": crash}


def _clip(text: str, n: int = 3000) -> str:
    return text if len(text) <= 2 * n else text[:n] + "\n[...]\n" + text[-n:]


def allowed_roots(case_dir: Path, out_dir: Path) -> list[Path]:
    from myrabot_desc.expand.packages import data_root

    roots = [case_dir, out_dir, Path(sys.prefix), Path(sys.base_prefix), Path(sys.exec_prefix),
             Path(os.__file__).resolve().parent, data_root(), Path("/dev/null"), Path("/dev/urandom")]
    for p in sys.path:
        if p and Path(p).is_dir():
            roots.append(Path(p))
    return [r.resolve() for r in roots]


def outside(opens: list[str], roots: list[Path]) -> list[str]:
    """Opened paths (as given, then resolved) outside every root.

    Writing a new file straight in the temp folder is fine (tempfile probes it; stderr capture).
    """
    import tempfile

    tmp = Path(tempfile.gettempdir()).resolve()
    bad = []
    for entry in opens:
        kind, p = entry[:2], entry[2:]
        if Path(p).resolve() == tmp or (kind == "w:" and Path(p).resolve().parent == tmp):
            continue
        try:
            real = Path(p).resolve()
        except (OSError, RuntimeError):
            real = Path(p)
        if not any(real == r or real.is_relative_to(r) for r in roots):
            bad.append(p)
    return bad


LOC_RE = re.compile(r"^(?P<file>[^\s:][^:]*?)(?::(?P<line>\d+))?: error: ", re.M)


def problems(run: dict, command: str, expect: str, case_dir: Path, out_dir: Path, src: Path,
             time_limit: float = TIME_LIMIT) -> list[str]:
    """Everything wrong with one run (empty = it behaved)."""
    errs = []
    text = (run["stderr"] or "") + (run["stdout"] or "")
    if run["crash"]:
        errs.append(f"crash: {run['crash'].strip().splitlines()[-1]}")
        return errs
    if "Traceback" in text:
        errs.append("traceback in the output")
    if "MemoryError" in text:         # the worker's memory cap fired: a bomb got past our limits
        errs.append("ran out of memory (the worker's address-space cap)")
    if "internal error" in text:
        errs.append("internal error: " + next(ln for ln in text.splitlines() if "internal error" in ln)[:300])
    if run["seconds"] > time_limit:
        errs.append(f"took {run['seconds']:.1f} s")
    if run["events"]:
        errs.append(f"network/subprocess: {run['events'][:3]}")
    far = outside(run["opens"], allowed_roots(case_dir, out_dir))
    if far:
        errs.append(f"opened outside the allowed roots: {far[:5]}")
    code = run["code"]
    if expect == "not-robot":   # any XML builds, as with xacro; the robot commands refuse it
        if command == "build" and code != 0:
            errs.append(f"exit {code}, expected 0 (build expands any XML)")
        expect = "reject" if command != "build" else "-"
    if expect == "reject":
        if code != 2:
            errs.append(f"exit {code}, expected 2 (reject)")
    elif command in ("check", "check-inertia"):
        if code not in (0, 1, 2):
            errs.append(f"exit {code}")
        elif expect == "defect" and code != 2 and re.search(r"\b0 errors, 0 warnings", text):
            errs.append("check found nothing wrong with a defective model")
    elif code not in (0, 1, 2) or (code == 1 and command not in ("sim-drive", "build")):
        errs.append(f"exit {code}")
    if code == 2:
        # one clear message naming a file (with its line when the problem has one)
        m = LOC_RE.search(text)
        if not m:
            errs.append(f"exit 2 without a 'file[:line]: error:' line: {text.strip()[:300]!r}")
    if code not in (0, None) and not (command == "sim-drive" and code == 1):
        leftovers = [str(p.relative_to(out_dir)) for p in out_dir.rglob("*") if p.is_file()]
        if leftovers:
            errs.append(f"exit {code} but files left behind: {leftovers[:5]}")
    if any(p.name.startswith((".staging.", ".x.")) for p in out_dir.rglob("*")):
        errs.append("temporary files left behind")
    return errs


def argv_for(command: str, src: Path, out_dir: Path, extra=()) -> list[str]:
    table = MATERIAL_COMMANDS if command == "materials" else COMMANDS
    return [a.replace("{F}", str(src)).replace("{OUT}", str(out_dir)) for a in table[command]] + list(extra)


def run_one(task) -> dict:
    """Worker entry: (case_path, command, expect, corpus_root, out_base, extra) -> result with problems."""
    import shutil

    rel, command, expect, root, out_base, extra = task
    root = Path(root)
    src = root / rel
    out_dir = Path(out_base) / (re.sub(r"[^\w.-]", "_", rel) + "." + command)
    shutil.rmtree(out_dir, ignore_errors=True)
    out_dir.mkdir(parents=True)
    cwd = os.getcwd()
    try:
        scratch = Path(out_base) / "cwd"
        scratch.mkdir(exist_ok=True)
        os.chdir(scratch)      # MuJoCo drops MUJOCO_LOG.TXT into the working folder
        run = invoke(argv_for(command, src, out_dir, extra))
    finally:
        os.chdir(cwd)
    case_dir = src.parent if src.parent != root else root
    # meshes/ and paths/ cases read from their package folder (the case folder itself)
    run["problems"] = problems(run, command, expect, case_dir, out_dir, src)
    run["case"], run["command"], run["expect"] = rel, command, expect
    shutil.rmtree(out_dir, ignore_errors=True)
    return run


def extra_args(rel: str) -> list[str]:
    return ["--no-env"] if "no_env" in rel else []
