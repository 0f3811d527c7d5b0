"""What the test folders share: where things are, and the CLI run in-process.

Importable from every test folder (``pythonpath = ["tests"]`` in pyproject.toml)::

    from helpers import ROOT, FIXTURES, invoke
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from myrabot_desc.commands.main import main

ROOT = Path(__file__).resolve().parents[1]      # the repository
TESTS = ROOT / "tests"
FIXTURES = TESTS / "fixtures"                   # the seed's files, small xacro cases, wander_bot
BAD = TESTS / "bad"                             # hostile inputs (hardening)
CORPUS = TESTS / "corpus"                       # the real-robot corpus (data, see its README.md)
SHIM = TESTS / "corpus_shim"                    # the test-only ament_index_python for the xacro CLI
DATA = TESTS / "data"                           # schemas
SEED = FIXTURES / "seed_myrabot"
WANDER = FIXTURES / "wander_bot"


def invoke(*args, **kwargs):
    """``myrabot-desc ARGS`` in this process (click's CliRunner); the Result."""
    return CliRunner().invoke(main, [str(a) for a in args], **kwargs)
