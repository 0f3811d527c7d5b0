"""Build a Pinocchio model from our Robot, with urdfdom's real errors captured.

urdfdom prints its reasons ("Two root links found...") on C-level stderr (fd 2)
and Pinocchio raises only "does not contain a valid URDF model" (env-notes.md §4);
we redirect fd 2 around the call and put the captured text into our error.
"""

from __future__ import annotations

import os

from myrabot_desc.errors import InputError
from myrabot_desc.model.tree import MAX_TREE_DEPTH, depth


def capture_fd2(fn, *args, **kwargs):
    """Run fn with file descriptor 2 redirected; return (result, captured_text)."""
    import sys
    import tempfile      # here: every command that reads a model imports this module (~4 ms)

    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            result = fn(*args, **kwargs)
            error = None
        except Exception as exc:  # re-raised after fd 2 is restored
            result, error = None, exc
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        tmp.seek(0)
        text = tmp.read().decode("utf-8", errors="replace")
    if error is not None:
        raise _Wrapped(error, text)
    return result, text


class _Wrapped(Exception):
    def __init__(self, error, text):
        super().__init__(str(error))
        self.error, self.text = error, text


def _clean(text: str) -> str:
    lines = [ln.strip() for ln in text.splitlines() if ln.strip() and "Library error" not in ln]
    return "; ".join(dict.fromkeys(lines))


# Pinocchio 3's Data holds second-order derivative tensors of nv x nv x nv doubles: about
# 32 nv^3 bytes (measured: 200 DOF 260 MB, 400 DOF 2 GB). Real robots have under 100.
MAX_DOF = 200
_DOF = {"fixed": 0, "floating": 6, "planar": 3}


def build_model(robot, floating: bool = False):
    """pinocchio.Model of ``robot`` (free-flyer root when ``floating``)."""
    import pinocchio as pin

    d = depth(robot)
    if d > MAX_TREE_DEPTH:      # Pinocchio's parser recurses per joint: SIGSEGV near 4,000
        raise InputError(f"the joint tree is {d} joints deep, over the {MAX_TREE_DEPTH} Pinocchio is given "
                         "(its parser recurses once per joint)", robot.loc)
    dof = sum(_DOF.get(j.type, 1) for j in robot.joints.values()) + (6 if floating else 0)
    if dof > MAX_DOF:
        raise InputError(f"{dof} degrees of freedom, over the {MAX_DOF} Pinocchio is given (its data holds "
                         f"nv x nv x nv tensors: about {32 * dof ** 3 / 1e9:.1f} GB here)", robot.loc)
    xml = robot.urdf_text
    try:
        if floating:
            model, _ = capture_fd2(pin.buildModelFromXML, xml, pin.JointModelFreeFlyer())
        else:
            model, _ = capture_fd2(pin.buildModelFromXML, xml)
    except _Wrapped as w:
        detail = _clean(w.text) or str(w.error)
        raise InputError(f"Pinocchio (urdfdom) rejects the URDF: {detail}", robot.loc) from None
    return model
