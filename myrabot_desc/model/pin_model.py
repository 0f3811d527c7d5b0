"""Build a Pinocchio model from our Robot, with urdfdom's real errors captured.

urdfdom prints its reasons ("Two root links found...") on C-level stderr (fd 2)
and Pinocchio raises only "does not contain a valid URDF model" (env-notes.md §4);
we redirect fd 2 around the call and put the captured text into our error.
"""

from __future__ import annotations

import os

from myrabot_desc import xmltree
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


def build_model(robot, floating: bool = False, lean: bool = False):
    """pinocchio.Model of ``robot`` (free-flyer root when ``floating``).

    ``lean``: urdfdom is given only what the Model is built from (``lean_urdf``), not the whole
    document: the same Model, without parsing the visuals, collisions and Gazebo blocks (most of the
    bundled robot's text). A flaw urdfdom finds only in what is left out (a visual's
    geometry, a material) then goes unreported here."""
    import pinocchio as pin

    d = depth(robot)
    if d > MAX_TREE_DEPTH:      # Pinocchio's parser recurses per joint: SIGSEGV near 4,000
        raise InputError(f"the joint tree is {d} joints deep, over the {MAX_TREE_DEPTH} Pinocchio is given "
                         "(its parser recurses once per joint)", robot.loc)
    dof = sum(_DOF.get(j.type, 1) for j in robot.joints.values()) + (6 if floating else 0)
    if dof > MAX_DOF:
        raise InputError(f"{dof} degrees of freedom, over the {MAX_DOF} Pinocchio is given (its data holds "
                         f"nv x nv x nv tensors: about {32 * dof ** 3 / 1e9:.1f} GB here)", robot.loc)
    xml = (lean_urdf(robot) if lean else None) or robot.urdf_text
    try:
        if floating:
            model, _ = capture_fd2(pin.buildModelFromXML, xml, pin.JointModelFreeFlyer())
        else:
            model, _ = capture_fd2(pin.buildModelFromXML, xml)
    except _Wrapped as w:
        detail = _clean(w.text) or str(w.error)
        raise InputError(f"Pinocchio (urdfdom) rejects the URDF: {detail}", robot.loc) from None
    return model


def lean_urdf(robot) -> str | None:
    """The robot's URDF cut to what Pinocchio's Model is built from, copied from the document as
    written: the ``<robot>`` start tag, every top-level ``<joint>`` whole and every top-level
    ``<link>`` with its ``<inertial>`` elements only, in document order. None when the robot was
    not read by xmltree (whose elements know where they start in the bytes) or its root has a
    namespace (urdfdom would read its elements by their prefixed names): the caller gives the
    whole document then.

    The cuts fall on a ``<`` that starts a node, and every ``<`` of a document is one, a comment's
    or a CDATA section's own, or an end tag: the text between a node's start and the next node's
    start is the node and its tail; the last child's span ends at its parent's end tag, the last
    ``</`` before the parent's next sibling (text holds no ``<``)."""
    root = robot.root_element
    doc = root.getroottree() if type(root) is xmltree.Element else None
    tag = root.tag
    if type(doc) is not xmltree.Document or tag[:1] == "{" or not len(root):
        return None
    data = doc.data
    nodes = list(root)
    following = [n for n in doc if n is not root and n._pos > root._pos]
    root_end = data.rfind(b"</", 0, following[0]._pos if following else len(data))
    out = [data[root._pos:nodes[0]._pos]]
    add = out.append
    for k, el in enumerate(nodes):
        t = el.tag
        if t != "joint" and t != "link":
            continue
        end = nodes[k + 1]._pos if k + 1 < len(nodes) else root_end
        if t == "joint" or not len(el):
            add(data[el._pos:end])
            continue
        add(data[el._pos:el[0]._pos])
        last = len(el) - 1
        for j, c in enumerate(el):
            if c.tag == "inertial":
                add(data[c._pos:el[j + 1]._pos if j < last else data.rfind(b"</", el[last]._pos, end)])
        add(b"</link>")
    add(f"</{tag}>".encode())
    return b"".join(out).decode("utf-8", errors="replace")
