"""Rigid bodies: the links that move as one because fixed joints join them.

A simulator fuses such links into one body (MuJoCo's ``fusestatic``, sdformat's lumping); check
weighs them together. Pure Python, one walk down the tree.
"""

from __future__ import annotations

from typing import NamedTuple


class Bodies(NamedTuple):
    """The links merged into rigid bodies across fixed joints (see ``rigid_bodies``)."""

    host: dict          # link -> the link heading its body (itself when not merged)
    merged: tuple       # the fixed joints merged, in walk order

    def members(self, head: str) -> list[str]:
        return [n for n, h in self.host.items() if h == head]

    def masses(self, robot) -> dict[str, float]:
        """head link -> the mass of its body (negative masses count as 0)."""
        out: dict[str, float] = {}
        for link, head in self.host.items():
            out[head] = out.get(head, 0.0) + max(robot.links[link].mass, 0.0)
        return out


def rigid_bodies(robot, keep=frozenset(), stop=frozenset()) -> Bodies:
    """Every link's rigid body: a link on a fixed joint belongs to its parent's body, unless the
    joint is in ``keep`` or its parent in ``stop`` (MJCF: the ``world`` link, whose children are
    the bodies a simulator sets free or welds). One walk down from the roots (breadth first, in
    document order); links it does not reach (on a cycle) are bodies of their own."""
    children = robot.joints_by_parent()
    host: dict = {}
    merged = []
    order = list(robot.roots)
    for r in order:
        host[r] = r
    i = 0
    while i < len(order):
        parent = order[i]
        i += 1
        for j in children.get(parent, []):
            if j.child in host or j.child not in robot.links:
                continue
            if j.type == "fixed" and parent not in stop and j.name not in keep:
                host[j.child] = host[parent]
                merged.append(j)
            else:
                host[j.child] = j.child
            order.append(j.child)
    for n in robot.links:          # links outside the tree (cycles): bodies of their own
        if n not in host:
            host[n] = n
    return Bodies(host, tuple(merged))
