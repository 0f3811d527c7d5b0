"""Every command block of README.md and docs/*.md whose output is shown runs, and prints what the
document shows (timings and the scratch folder normalised; tests/docblocks.py)."""

from __future__ import annotations

import pytest
from docblocks import all_blocks, blocks, first_difference, matches, normalise, run_block
from helpers import ROOT

BLOCKS = all_blocks()


def test_the_documents_have_command_blocks():
    assert len(BLOCKS) >= 8          # README: build (2), info, check, convert, materials, sim, render


@pytest.mark.parametrize("block", BLOCKS, ids=[b.id for b in BLOCKS])
def test_doc_block_prints_what_it_shows(block, tmp_path):
    results = run_block(block, tmp_path / "out")
    failures, ran = [], 0
    for cmd, output in results:
        if output is None or not cmd.shown:
            continue
        ran += 1
        actual = normalise(output, str(tmp_path / "out"))
        expected = normalise("\n".join(cmd.expected))
        if not matches(expected, actual):
            failures.append(f"{block.doc.name}:{cmd.lineno}: $ {cmd.line}\n{first_difference(expected, actual)}")
    if ran == 0:
        pytest.skip("no command of this block can run here: " + "; ".join(
            f"{c.line.split()[0]}: {c.skip_reason()}" for c in block.commands if c.skip_reason()))
    assert not failures, "\n\n".join(failures)


def test_a_changed_output_fails(tmp_path):
    """The comparison is not blind: the README's info block with one number changed does not match."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    (block,) = [b for b in blocks(ROOT / "README.md", text) if b.commands[0].line == "myrabot-desc info --no-tree"]
    (cmd, output), = run_block(block, tmp_path / "out")
    actual = normalise(output)
    assert matches(normalise("\n".join(cmd.expected)), actual)
    changed = [ln.replace("4.6048 kg", "4.6049 kg") for ln in cmd.expected]
    assert changed != cmd.expected and not matches(normalise("\n".join(changed)), actual)


def test_matching_rules():
    assert matches(["a", "...", "d"], ["a", "b", "c", "d"])
    assert matches(["a", "... (2 more)", "d"], ["a", "d"])
    assert not matches(["a", "...", "d"], ["a", "b", "c"])
    assert not matches(["a", "b"], ["a", "b", "c"])
    assert normalise("x (25000 steps, 0.22 s wall)\nwrote a (1200x900, all view, 1.52 s)") == \
        ["x (25000 steps, T s wall)", "wrote a (1200x900, all view, T s)"]
    assert normalise("/tmp/x/out/a.png", "/tmp/x/out") == ["out/a.png"]
