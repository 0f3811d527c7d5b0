"""What stops a conversion: a model with no tree, values no URDF reader accepts, a collision
mesh that cannot be read. ``convert`` refuses such a model (exit 2, every reason on its own
``file:line: error:`` line, nothing written) unless ``--allow-errors`` is given; then the
converters leave those parts out and the report says so.

Pure Python (the SDF path must not import numpy): meshes are only checked for existence,
size and, for binary STL, a header that matches the file (model/meshes.precheck); MJCF, which
reads every mesh anyway, adds what its reader finds.
"""

from __future__ import annotations

from pathlib import Path

from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import unresolved_reason
from myrabot_desc.model import meshes as meshio
from myrabot_desc.model import tree
from myrabot_desc.records import Struct

# loader issues that no URDF reader would accept (urdfdom refuses the document): the text is not a
# number, the element lacks what identifies it. NaN, inf and out-of-range numbers parse; they stay
# warnings (check reports them).
UNREADABLE = ("not a number", "expected 3 numbers", "expected 4 numbers", "without a name", "needs <parent",
              "unknown geometry", "<geometry> is empty")


class Problem(Struct):
    message: str
    loc: object = None
    kind: str = "model"          # report kind of what it concerns
    name: str = ""

    def __str__(self) -> str:
        return str(InputError(self.message, self.loc))


def tree_problems(robot) -> list[Problem]:
    """Several roots, a link with two parents, links on a cycle (unreachable from the root): the
    model's tree facts (model/tree.py), said as convert refuses them."""
    out: list[Problem] = []
    for child, js in tree.parents(robot).items():
        if len(js) > 1:
            out.append(Problem(f"link '{child}' is the child of {len(js)} joints ("
                               + ", ".join(f"'{j.name}'" for j in js) + "): not a tree", js[1].loc, "link", child))
    roots = robot.roots
    if len(roots) > 1:
        out.append(Problem(f"the model has {len(roots)} root links ({', '.join(repr(r) for r in roots[:5])}"
                           f"{', ...' if len(roots) > 5 else ''}): a URDF is one tree", robot.loc, "model"))
    seen = tree.reachable(robot)
    lost = [n for n in robot.links if n not in seen]
    if lost:
        j = next((j for j in robot.joints.values() if j.child in lost), None)
        out.append(Problem(f"the joints form a cycle: {len(lost)} link(s) cannot be reached from "
                           f"{'a root' if roots else 'any root (there is none)'} ({', '.join(repr(n) for n in lost[:5])}"
                           f"{', ...' if len(lost) > 5 else ''})", j.loc if j else robot.loc, "link", lost[0]))
    return out


def inertial_problems(robot) -> list[Problem]:
    """An <inertial> with a mass but no <inertia> element (a misspelt ``<intertia>``): urdfdom refuses
    it, and converting it would invent a tensor."""
    out: list[Problem] = []
    for link in robot.links.values():
        ine = link.inertial
        ref = getattr(ine, "ref", None) if ine is not None else None
        if ref is None or not hasattr(ref, "find") or ref.find("inertia") is not None:
            continue
        others = [c.tag for c in ref if isinstance(c.tag, str) and c.tag not in ("mass", "origin")]
        hint = f" (it has <{others[0]}>: a misspelt <inertia>?)" if others else ""
        out.append(Problem(f"link '{link.name}': <inertial> has no <inertia> element{hint}; URDF readers refuse "
                           "it and a converter would have to invent the tensor", ine.loc or link.loc, "link",
                           link.name))
    return out


def value_problems(robot) -> list[Problem]:
    return [Problem(f"{d.code} {d.message}", d.loc, "value") for d in robot.load_issues
            if any(k in d.message for k in UNREADABLE)]


def mesh_problems(robot) -> list[Problem]:
    """Collision meshes that are missing, outside the model's roots, empty or over the limits."""

    out: list[Problem] = []
    checked: dict[object, str | None] = {}
    for link in robot.links.values():
        for k, c in enumerate(link.collisions):
            g = c.geometry
            if getattr(g, "kind", None) != "mesh":
                continue
            if g.path is None:
                base = robot.source.parent if robot.source else Path.cwd()
                why = unresolved_reason(g.filename, robot.package_roots, base, robot.allow_roots) or "cannot be found"
            else:
                if g.path not in checked:
                    checked[g.path] = meshio.unreadable(g.path)
                why = checked[g.path]
            if why:
                out.append(Problem(f"collision mesh {g.filename} of link '{link.name}': {why}", c.loc or link.loc,
                                   "collision", link.name if k == 0 else f"{link.name}[{k}]"))
    return out


def triangle_problem(path, size: int | None = None) -> str | None:
    """Why this mesh file holds no triangles a reader can take, or None (model/meshes.unreadable)."""
    return meshio.unreadable(path)


def problems(robot, tree_found: list[Problem] | None = None) -> list[Problem]:
    """Every reason to refuse ``robot``; ``tree_found``: its tree_problems when already known."""
    if tree_found is None:
        tree_found = tree_problems(robot)
    return tree_found + value_problems(robot) + inertial_problems(robot) + mesh_problems(robot)


def refuse_or_record(found: list[Problem], allow: bool, report=None, notes=None) -> None:
    """Raise (every reason, exit 2) or, with --allow-errors, put each in the report as dropped."""

    if not found:
        return
    if not allow:
        raise InputError(found[0].message, found[0].loc, more=found[1:])
    for p in found:
        if notes is not None:
            notes.warn(f"{p.message}: converted anyway (--allow-errors)", p.loc)
        if report is not None:
            report.set("error", p.message, "dropped", "converted anyway (--allow-errors): left out or read as "
                       "the URDF default", p.loc)
