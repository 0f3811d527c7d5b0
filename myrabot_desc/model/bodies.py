"""Rigid bodies: the links that move as one because fixed joints join them.

A rigid body is headed by a link that no fixed joint hangs from a parent link: a root, or the
child of a moving joint. Every link fixed to it (through any number of fixed joints) belongs to
it. A simulator fuses such links into one body (MuJoCo's ``fusestatic``, sdformat's lumping);
check weighs them together. A link's parent is its first parent joint (``model/tree.maps``), so
a link with two parents (a closed loop) still belongs to one body.

Pure Python, linear in the number of links (each chain of fixed joints is walked once).
"""

from __future__ import annotations

from myrabot_desc.model.tree import maps


def body_heads(robot, cut=()) -> dict[str, str]:
    """link -> the link that heads its rigid body (itself when no fixed joint joins it to a parent).
    ``cut``: links that head their own body whatever joins them to their parent (a simulator's free
    base under a URDF ``world`` link)."""
    parent_joint = maps(robot).parent_joint
    cut = set(cut)
    links = robot.links
    out: dict[str, str] = {}
    for name in links:
        if name in out:
            continue
        chain = []
        cur = name
        while cur not in out:
            chain.append(cur)
            pj = parent_joint.get(cur)
            if pj is None or pj.type != "fixed" or pj.parent not in links or pj.parent in chain or cur in cut:
                head = cur
                break
            cur = pj.parent
        else:
            head = out[cur]
        for n in chain:
            out[n] = head
    return out


def body_members(robot, cut=()) -> dict[str, list[str]]:
    """head link -> the links of its rigid body, head first, then in document order."""
    out: dict[str, list[str]] = {}
    heads = body_heads(robot, cut)
    for name, head in heads.items():
        if name == head:
            out.setdefault(head, []).insert(0, name)
        else:
            out.setdefault(head, []).append(name)
    return out


def body_masses(robot, cut=()) -> dict[str, float]:
    """head link -> the mass of its rigid body (negative masses count as 0)."""
    out: dict[str, float] = {}
    for name, head in body_heads(robot, cut).items():
        out[head] = out.get(head, 0.0) + max(robot.links[name].mass, 0.0)
    return out
