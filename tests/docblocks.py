"""The command blocks of README.md and docs/*.md, run as a user would type them.

A block is a fenced code block whose lines start with ``$ `` (a command) followed by what it prints
(stdout and stderr as a terminal shows them). The commands of one block run in order in one bash,
in the repository (their relative paths are the README's), with ``out/`` moved to a scratch folder.
The comparison normalises what differs from run to run: timings (``0.22 s wall``, ``, 1.52 s)``)
and the scratch folder. An expected line ``...`` or ``... (a note)`` stands for any number of lines.

Used by tests/docs/test_doc_blocks.py (the comparison) and bench/bench_docs.py (the timings the
README quotes).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

# Commands shown but not run here, with why (a server, a GUI).
NOT_RUN = {
    "myrabot-desc view": "a server that runs until stopped (tests/view/test_viewer_browser.py drives it)",
    "python -m mujoco.viewer": "a GUI window",
}
# Commands that need a peer tool: skipped (not failed) when it is not installed.
NEEDS = {"ign ": "ign"}

TIMING = re.compile(r"\b\d+(?:\.\d+)? s( wall)?\)")


@dataclass
class Command:
    line: str                       # as written, without "$ "
    expected: list[str] = field(default_factory=list)
    lineno: int = 0

    @property
    def shown(self) -> bool:
        return bool(self.expected)

    def skip_reason(self) -> str | None:
        for prefix, why in NOT_RUN.items():
            if self.line.startswith(prefix):
                return why
        for prefix, tool in NEEDS.items():
            if self.line.startswith(prefix) and shutil.which(tool) is None:
                return f"{tool} is not installed"
        return None


@dataclass
class Block:
    doc: Path
    lineno: int
    commands: list[Command]

    @property
    def id(self) -> str:
        return f"{self.doc.name}:{self.lineno}"

    def shown(self) -> bool:
        return any(c.shown for c in self.commands)


def blocks(doc: Path, text: str | None = None) -> list[Block]:
    """The command blocks of one Markdown file."""
    text = doc.read_text(encoding="utf-8") if text is None else text
    out, inside, cur, start = [], False, None, 0
    for n, raw in enumerate(text.splitlines(), 1):
        if raw.startswith("```"):
            if not inside:
                inside, cur, start = True, [], n
            else:
                inside = False
                if cur:
                    out.append(Block(doc, start, cur))
            continue
        if not inside:
            continue
        if raw.startswith("$ "):
            cur.append(Command(raw[2:], [], n))
        elif cur:
            cur[-1].expected.append(raw)
    return out


def all_blocks() -> list[Block]:
    return [b for d in DOCS for b in blocks(d) if b.shown()]


# What a peer tool prints about its own installation, not about the input.
NOISE = re.compile(r"^Library error: libignition-tools-backward\.so not found")


def normalise(text: str, scratch: str | None = None) -> list[str]:
    if scratch:
        text = text.replace(scratch.rstrip("/") + "/", "out/")
    lines = [TIMING.sub(lambda m: "T s" + (m.group(1) or "") + ")", ln.rstrip()) for ln in text.splitlines()
             if not NOISE.match(ln)]
    while lines and not lines[-1]:
        lines.pop()
    return lines


def _is_ellipsis(line: str) -> bool:
    return line.strip() == "..." or line.strip().startswith("... (")


def matches(expected: list[str], actual: list[str]) -> bool:
    """Line by line, ``...`` lines matching any run of lines (the first match that lets the rest
    match: backtracking over the few ellipses a block has)."""
    exp = [ln.rstrip() for ln in expected]
    while exp and not exp[-1]:
        exp.pop()

    def go(i: int, j: int) -> bool:
        if i == len(exp):
            return j == len(actual)
        if _is_ellipsis(exp[i]):
            return any(go(i + 1, k) for k in range(j, len(actual) + 1))
        return j < len(actual) and exp[i] == actual[j] and go(i + 1, j + 1)

    return go(0, 0)


def first_difference(expected: list[str], actual: list[str]) -> str:
    """A short account of where they part (for the failure message)."""
    import difflib

    exp = [ln.rstrip() for ln in expected]
    return "\n".join(difflib.unified_diff(exp, actual, "README (expected)", "program (actual)", lineterm="", n=1))


MARK = "@@myrabot-desc-doc-command@@"


def run_block(block: Block, scratch: Path, env: dict | None = None, timeout: float = 600) -> list[tuple[Command, str | None]]:
    """Run the block's commands in order in one bash (cwd: the repository; ``out/`` is ``scratch``);
    [(command, output or None when not run)]."""
    scratch.mkdir(parents=True, exist_ok=True)
    bindir = str(Path(sys.executable).parent)
    env = dict(os.environ if env is None else env)
    env.pop("MUJOCO_GL", None)          # a user's shell: not what a test before set for its own MuJoCo import
    env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
    env.setdefault("PYTHONUNBUFFERED", "1")          # stdout and stderr in the order printed
    env.setdefault("MYRABOT_DESC_CACHE_DIR", str(scratch / ".cache"))
    env["COLUMNS"] = "100"
    script = ["set +e", "__rc=0"]
    run = []
    for i, c in enumerate(block.commands):
        if c.skip_reason():
            continue
        cmd = re.sub(r"(?<![\w/.])out/", str(scratch) + "/", c.line)
        script.append(f"printf '\\n{MARK} {i}\\n'; ( exit $__rc ); {cmd} 2>&1; __rc=$?")
        run.append(i)
    r = subprocess.run(["bash", "-c", "\n".join(script)], cwd=ROOT, env=env, capture_output=True, text=True,
                       timeout=timeout, stdin=subprocess.DEVNULL)
    outputs: dict[int, str] = {}
    for part in r.stdout.split(f"\n{MARK} ")[1:]:
        head, _, body = part.partition("\n")
        outputs[int(head)] = body
    return [(c, outputs.get(i)) for i, c in enumerate(block.commands)]
