"""Compare two built robots: what changed, in numbers, and where each new value was written.

``compare(old, new)`` pairs the links, joints and sensors of two :class:`~myrabot_desc.model.parts.Robot`
(by name, then by structure) and returns a :class:`Comparison`: ``data``, a nested dict of every
change (the JSON report's ``changes``), and ``items``, the same changes as flat :class:`Item` rows,
each with a size to rank them by and the source span of the NEW value (``robot.origin``).

Units: lengths in mm, angles in degrees, masses in kg, inertias in kg·m² (as written). A value
counts as changed when |a − b| > 1e-12 + 1e-9·max(|a|, |b|); a frame has moved beyond 1e-6 mm or
1e-6 deg. Paths of the two builds' own folders (temporary checkouts, package roots) are replaced
by placeholders before texts are compared, so a model compared with itself at another path has
no change.
"""

from __future__ import annotations

import filecmp
import math
import os

from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as drive_model
from myrabot_desc.model.kinematics import world_transforms
from myrabot_desc.model.meshes import vertices
from myrabot_desc.records import Struct

REL = 1e-9
ABS = 1e-12
MOVED_MM = 1e-6
TURNED_DEG = 1e-6
STRUCTURAL = 1000.0       # the size of an added, removed, renamed or retyped part: ranked first


class Item(Struct):
    """One change, flat: what it is about and how big it is (for ranking and the text/Markdown tables)."""

    section: str              # link | joint | sensor | frame | mass | drive | element | finding | robot
    subject: str              # the link, joint, sensor, frame or element name
    what: str                 # what changed: 'origin xyz', 'mass', 'added', ...
    old: str                  # the old value as text ('' when added)
    new: str                  # the new value as text ('' when removed)
    change: str               # the change as text: '+1.0 mm', '×1.04', 'added'
    size: float               # for ranking: mm, deg, % or STRUCTURAL
    where: object = None         # Where of the new value (None: no source span)
    values: tuple = ()        # the new value's numbers as written (SI units), to find the line that wrote them


class Where(Struct):
    """Where a value is written: the span of the literal (or definition) and how it got there."""

    span: object                 # model.sources.Span
    kind: str                 # literal | property | param | default | arg | expr | element | changed-line
    name: str | None = None   # the property, parameter or arg name
    side: str = "new"         # 'old' for a removed part (its place in the old revision)
    hops: tuple = ()          # model.sources.Hop: the way from the use to the literal

    def text(self, shown=lambda f: f) -> str:
        s = self.span
        loc = f"{shown(s.file)}:{s.line}:{s.col}"
        if self.side == "old":
            loc += " (old)"
        if self.kind in ("property", "param", "default", "arg") and self.name:
            loc += f" ({self.kind} {self.name})"
        elif self.kind == "expr":
            loc += " (expression)"
        elif self.kind == "yaml":
            loc += " (YAML)"
        elif self.kind == "changed-line":
            loc += " (changed line)"
        return loc


class Comparison(Struct):
    data: dict
    items: list


# ---------------------------------------------------------------------------------------- numbers
def differs(a, b) -> bool:
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) != len(b) or any(differs(x, y) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return abs(a - b) > ABS + REL * max(abs(a), abs(b))
    return a != b


def mm(v) -> list:
    return [_r(float(x) * 1000.0, 4) for x in v]


def deg(v) -> list:
    return [_r(math.degrees(float(x)), 4) for x in v]


def _r(x: float, n: int) -> float:
    return round(x, n) + 0.0


def fmt(x, unit: str = "") -> str:
    if x is None:
        return "none"
    if isinstance(x, (list, tuple)):
        return "(" + ", ".join(fmt(v) for v in x) + ")" + (f" {unit}" if unit else "")
    if isinstance(x, float):
        s = f"{x:.6g}" if (x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e6)) else f"{x:.4f}".rstrip("0").rstrip(".")
        s = "0" if s in ("-0", "") else s
        return s + (f" {unit}" if unit else "")
    return str(x) + (f" {unit}" if unit else "")


def signed(x: float, unit: str = "") -> str:
    return ("+" if x > 0 else "") + fmt(float(x), unit)


def rel_size(a, b) -> float:
    """The change as a percentage of the larger magnitude (100 when one side is 0)."""
    m = max(abs(a), abs(b))
    return 100.0 * abs(b - a) / m if m else 0.0


# ---------------------------------------------------------------------------------------- matching
def match(old, new):
    """(link map, joint map, how) old name -> new name. By name first; then, among the rest, a joint
    pairs with one of the same type whose parent and child links pair (or whose parent pairs and whose
    origin is the same); a link pairs with a link that is the child of paired joints."""
    lmap = {n: n for n in old.links if n in new.links}
    jmap = {n: n for n in old.joints if n in new.joints}
    how: dict = {}
    for _ in range(4):
        taken = set(jmap.values())
        jn = [n for n in new.joints if n not in taken]
        for a in [n for n in old.joints if n not in jmap]:
            ja = old.joints[a]
            same = [b for b in jn if new.joints[b].type == ja.type and lmap.get(ja.parent) == new.joints[b].parent]
            cands = [b for b in same if lmap.get(ja.child, ja.child) == new.joints[b].child]
            rule = "same type, same parent and child links"
            if len(cands) != 1:
                cands = [b for b in same if not differs(ja.origin.xyz, new.joints[b].origin.xyz)
                         and not differs(ja.origin.rpy, new.joints[b].origin.rpy)]
                rule = "same type, same parent link, same origin"
            if len(cands) == 1:
                jmap[a] = cands[0]
                jn.remove(cands[0])
                how[("joint", a)] = rule
        lo = [n for n in old.links if n not in lmap]
        ln = [n for n in new.links if n not in set(lmap.values())]
        for a, b in jmap.items():
            ca, cb = old.joints[a].child, new.joints[b].child
            if ca in lo and cb in ln:
                lmap[ca] = cb
                lo.remove(ca)
                ln.remove(cb)
                how[("link", ca)] = f"child of the paired joints {a} / {b}"
    return lmap, jmap, how


# ---------------------------------------------------------------------------------------- the sides
class Side:
    """One robot and what the comparison asks of it, computed once."""

    def __init__(self, robot, label: str, placeholders: dict):
        self.robot = robot
        self.label = label
        self.placeholders = sorted(placeholders.items(), key=lambda kv: -len(kv[0]))   # path text -> placeholder
        self._frames = {}
        self._extent: dict = {}

    def norm(self, text):
        if not isinstance(text, str):
            return text
        for path, ph in self.placeholders:
            if path and path in text:
                text = text.replace(path, ph)
        return text

    def frames(self, pose: str = "zero"):
        f = self._frames.get(pose)
        if f is None:
            q = self.robot.rest_pose() if pose == "rest" else None
            f = self._frames[pose] = world_transforms(self.robot, q)
        return f

    def extent(self, g):
        """The mesh's axis-aligned extents in mm (scale applied), or None when it cannot be read."""
        if g.path is None:
            return None
        key = (str(g.path), tuple(g.scale))
        if key not in self._extent:
            try:
                v = vertices(g.path)
                lo, hi = v.min(axis=0), v.max(axis=0)
                self._extent[key] = [_r(float(h - lo_) * s * 1000.0, 3) for lo_, h, s in zip(lo, hi, g.scale)]
            except (InputError, Exception):
                self._extent[key] = None
        return self._extent[key]

    def element_where(self, part, *path: str) -> Where | None:
        """Where the element at ``path`` below ``part``'s element is written (its start tag)."""
        el = getattr(part, "ref", None)
        for tag in path:
            if el is None:
                return None
            el = self.robot.sources.child(el, tag)
        return self.where(el, None) if el is not None else None

    def where(self, part, field: str | None = None, side: str | None = None, hops_of: tuple = ()) -> Where | None:
        """Where ``field`` of ``part`` is written (the element's start tag when ``field`` is None; then
        ``hops_of``: fields whose ways from the use are kept, to find a changed call site)."""
        side = side or ("old" if self.label == "old" else "new")
        try:
            if field is None:
                ref = getattr(part, "ref", part)       # a part or Node's handle, or a handle as it is
                span = self.robot.sources.start_tag(ref) if ref is not None else None
                hops = ()
                for f in hops_of:
                    w = self.where(part, f, side)
                    if w is not None:
                        hops += w.hops
                return Where(span, "element", None, side, hops) if span is not None else None
            o = self.robot.origin(part, field)
        except Exception:        # a part read from a document without spans
            return None
        span = o.written or o.expr or o.at
        if span is None:
            return None
        kind = o.kind if o.written is not None or o.kind != "literal" else "literal"
        if o.written is None and o.expr is not None:
            kind = "expr"
        return Where(span, kind, o.name, side, tuple(h for h in o.hops if h.span is not None))


# ---------------------------------------------------------------------------------------- geometry
def geom_summary(g, side: Side) -> dict:
    if g is None:
        return {"type": None}
    if g.kind == "box":
        return {"box_mm": mm(g.size)}
    if g.kind == "cylinder":
        return {"cylinder_radius_mm": _r(g.radius * 1000, 4), "cylinder_length_mm": _r(g.length * 1000, 4)}
    if g.kind == "sphere":
        return {"sphere_radius_mm": _r(g.radius * 1000, 4)}
    return {"mesh": side.norm(g.filename), "scale": [float(s) for s in g.scale]}


def geom_text(s: dict) -> str:
    if "box_mm" in s:
        return "box " + " × ".join(fmt(v) for v in s["box_mm"]) + " mm"
    if "cylinder_radius_mm" in s:
        return f"cylinder r {fmt(s['cylinder_radius_mm'])} × {fmt(s['cylinder_length_mm'])} mm"
    if "sphere_radius_mm" in s:
        return f"sphere r {fmt(s['sphere_radius_mm'])} mm"
    if "mesh" in s:
        t = f"mesh {s['mesh'].rsplit('/', 1)[-1]}"
        if any(v != 1.0 for v in s["scale"]):
            t += f" scale {fmt(s['scale'])}"
        if s.get("extent_mm"):
            t += " (" + " × ".join(fmt(v) for v in s["extent_mm"]) + " mm)"
        return t
    return "no geometry"


def _same_bytes(a, b) -> bool:
    """Two mesh files hold the same bytes (compared, not hashed: most sizes differ or the files
    match; an unreadable file is the same as another unreadable one)."""
    def size(p):
        try:
            return os.stat(p).st_size if p is not None else None
        except OSError:
            return None
    sa, sb = size(a), size(b)
    if sa is None or sb is None or sa != sb:
        return sa is None and sb is None
    try:
        return filecmp.cmp(a, b, shallow=False)
    except OSError:
        return False


def _same_shape(x, y, so: Side, sn: Side) -> bool:
    """Two visuals/collisions are the same: origin, geometry and, for a mesh, the file's content."""
    if differs(x.origin.xyz, y.origin.xyz) or differs(x.origin.rpy, y.origin.rpy):
        return False
    gx, gy = geom_summary(x.geometry, so), geom_summary(y.geometry, sn)
    if gx != gy:
        return False
    if x.geometry is not None and x.geometry.kind == "mesh":
        if not _same_bytes(x.geometry.path, y.geometry.path) and so.extent(x.geometry) != sn.extent(y.geometry):
            return False
    return True


# ---------------------------------------------------------------------------------------- the comparison
class _Builder:
    def __init__(self, so: Side, sn: Side):
        self.so, self.sn = so, sn
        self.data: dict = {}
        self.items: list[Item] = []

    def add(self, *a, **k):
        self.items.append(Item(*a, **k))

    # ------------------------------------------------------------ joints
    def joint(self, a, b, lmap) -> dict:
        so, sn = self.so, self.sn
        ch: dict = {}
        name = b.name
        if a.type != b.type:
            ch["type"] = {"old": a.type, "new": b.type}
            self.add("joint", name, "type", a.type, b.type, f"{a.type} → {b.type}", STRUCTURAL / 2, sn.where(b, "type"))
        for k in ("parent", "child"):
            va, vb = lmap.get(getattr(a, k), getattr(a, k)), getattr(b, k)
            if va != vb:
                ch[k] = {"old": getattr(a, k), "new": vb}
                self.add("joint", name, k, getattr(a, k), vb, "moved", STRUCTURAL / 2, sn.where(b, k))
        if differs(a.origin.xyz, b.origin.xyz):
            d = [_r((y - x) * 1000, 4) for x, y in zip(a.origin.xyz, b.origin.xyz)]
            ch["xyz_mm"] = {"old": mm(a.origin.xyz), "new": mm(b.origin.xyz), "delta": d}
            self.add("joint", name, "origin xyz", fmt(mm(a.origin.xyz), "mm"), fmt(mm(b.origin.xyz), "mm"),
                     f"{fmt(math.hypot(*d))} mm", math.hypot(*d), sn.where(b, "origin.xyz"),
                     tuple(y for x, y in zip(a.origin.xyz, b.origin.xyz) if differs(x, y)))
        if differs(a.origin.rpy, b.origin.rpy):
            ch["rpy_deg"] = {"old": deg(a.origin.rpy), "new": deg(b.origin.rpy)}
            turn = max(abs(_wrap(y - x)) for x, y in zip(deg(a.origin.rpy), deg(b.origin.rpy)))
            self.add("joint", name, "origin rpy", fmt(deg(a.origin.rpy), "deg"), fmt(deg(b.origin.rpy), "deg"),
                     f"{fmt(turn)} deg", turn, sn.where(b, "origin.rpy"),
                     tuple(y for x, y in zip(a.origin.rpy, b.origin.rpy) if differs(x, y)))
        if differs(a.axis, b.axis):
            ch["axis"] = {"old": list(a.axis), "new": list(b.axis)}
            self.add("joint", name, "axis", fmt(list(a.axis)), fmt(list(b.axis)), "changed", STRUCTURAL / 4,
                     sn.where(b, "axis"))
        la, lb = _limit_view(a), _limit_view(b)
        if (la is None) != (lb is None):
            ch["limit"] = {"old": la, "new": lb}
            self.add("joint", name, "limit", fmt(la), fmt(lb), "added" if la is None else "removed", STRUCTURAL / 4,
                     sn.where(b, None) if lb is not None else None)
        elif la is not None:
            d = {}
            for k in sorted(set(la) | set(lb)):
                x, y = la.get(k), lb.get(k)
                if x is None or y is None or differs(x, y):
                    d[k] = {"old": x, "new": y}
                    unit = "mm" if k.endswith("_mm") else "deg" if k.endswith("_deg") else \
                        ("N·m" if k == "effort" and b.type != "prismatic" else "N" if k == "effort" else "")
                    label = k.replace("_mm", "").replace("_deg", "")
                    size = rel_size(x, y) if x is not None and y is not None else STRUCTURAL / 4
                    field = "limit." + label
                    change = (f"{signed(y - x, unit)}" if x is not None and y is not None else
                              ("removed" if y is None else "added"))
                    raw = getattr(b.limit, label, None) if b.limit is not None else None
                    self.add("joint", name, f"limit {label}", fmt(x, unit), fmt(y, unit), change, size,
                             sn.where(b, field) if y is not None else sn.element_where(b, "limit"),
                             (raw,) if raw is not None else ())
            if d:
                ch["limit"] = d
        na, nb = so.robot.node(a), sn.robot.node(b)          # each joint's markup read once for the three
        for k in ("mimic", "dynamics", "safety_controller"):
            va, vb = _extra(na, k), _extra(nb, k)
            if differs(sorted((va or {}).items()), sorted((vb or {}).items())):
                ch[k] = {"old": va, "new": vb}
                field = None
                for key in sorted(set(va or {}) | set(vb or {})):
                    if differs((va or {}).get(key), (vb or {}).get(key)):
                        field = f"{k}.{key}" if k != "safety_controller" else None
                        break
                self.add("joint", name, k, fmt(va), fmt(vb), "changed", STRUCTURAL / 8,
                         sn.where(b, field) if field and vb else sn.where(b, None))
        return ch

    # ------------------------------------------------------------ links
    def link(self, a, b) -> dict:
        so, sn = self.so, self.sn
        ch: dict = {}
        name = b.name
        ia, ib = a.inertial, b.inertial
        if (ia is None) != (ib is None):
            ch["inertial"] = {"old": "present" if ia else None, "new": "present" if ib else None}
            self.add("link", name, "inertial", "present" if ia else "none", "present" if ib else "none",
                     "added" if ib else "removed", STRUCTURAL / 2, sn.where(ib, None) if ib else None)
        elif ia is not None:
            if differs(ia.mass, ib.mass):
                ch["mass_kg"] = {"old": ia.mass, "new": ib.mass, "delta": round(ib.mass - ia.mass, 9)}
                self.add("link", name, "mass", fmt(ia.mass, "kg"), fmt(ib.mass, "kg"),
                         f"{signed(ib.mass - ia.mass, 'kg')} ({signed(100 * (ib.mass - ia.mass) / ia.mass if ia.mass else 100.0)} %)",
                         rel_size(ia.mass, ib.mass), sn.where(ib, "mass"), (ib.mass,))
            if differs(ia.origin.xyz, ib.origin.xyz):
                ch["inertial_xyz_mm"] = {"old": mm(ia.origin.xyz), "new": mm(ib.origin.xyz)}
                dist = math.dist(ia.origin.xyz, ib.origin.xyz) * 1000
                self.add("link", name, "centre of mass (link frame)", fmt(mm(ia.origin.xyz), "mm"),
                         fmt(mm(ib.origin.xyz), "mm"), f"{fmt(dist)} mm", dist, sn.where(ib, "origin.xyz"),
                         tuple(y for x, y in zip(ia.origin.xyz, ib.origin.xyz) if differs(x, y)))
            if differs(ia.origin.rpy, ib.origin.rpy):
                ch["inertial_rpy_deg"] = {"old": deg(ia.origin.rpy), "new": deg(ib.origin.rpy)}
                turn = max(abs(_wrap(y - x)) for x, y in zip(deg(ia.origin.rpy), deg(ib.origin.rpy)))
                self.add("link", name, "inertia axes (rpy)", fmt(deg(ia.origin.rpy), "deg"),
                         fmt(deg(ib.origin.rpy), "deg"), f"{fmt(turn)} deg", turn, sn.where(ib, "origin.rpy"),
                         tuple(y for x, y in zip(ia.origin.rpy, ib.origin.rpy) if differs(x, y) and y))
            comps = {}
            # a component's change as a share of the link's largest principal-axis moment (old or new):
            # a product of inertia going from 0 to 1e-9 is not a 100 % change of the link
            scale = max(abs(getattr(i, k)) for i in (ia, ib) for k in ("ixx", "iyy", "izz")) or 1.0
            for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
                x, y = getattr(ia, k), getattr(ib, k)
                if differs(x, y):
                    comps[k] = {"old": x, "new": y}
                    self.add("link", name, k, fmt(x, "kg·m²"), fmt(y, "kg·m²"),
                             f"×{fmt(y / x)}" if x else signed(y), 100.0 * abs(y - x) / scale, sn.where(ib, k), (y,))
            if comps:
                ch["inertia"] = comps
        for kind in ("visual", "collision"):
            self.shapes(kind, list(getattr(a, kind + "s")), list(getattr(b, kind + "s")), a.name, b.name, ch)
        return ch

    def shapes(self, kind, va, vb, la, lb, ch):
        so, sn = self.so, self.sn
        if len(va) != len(vb):
            ch[f"{kind}_count"] = {"old": len(va), "new": len(vb)}
        left_a, left_b = list(range(len(va))), list(range(len(vb)))
        for i in list(left_a):
            same = [k for k in left_b if _same_shape(va[i], vb[k], so, sn)]
            if same:
                left_a.remove(i)
                left_b.remove(same[0])
        for i, k in zip(left_a, left_b):
            x, y = va[i], vb[k]
            d = {}
            key = f"{kind}[{k}]"
            if differs(x.origin.xyz, y.origin.xyz):
                d["xyz_mm"] = {"old": mm(x.origin.xyz), "new": mm(y.origin.xyz)}
                dist = math.dist(x.origin.xyz, y.origin.xyz) * 1000
                self.add("link", lb, f"{key} origin xyz", fmt(mm(x.origin.xyz), "mm"), fmt(mm(y.origin.xyz), "mm"),
                         f"{fmt(dist)} mm", dist, sn.where(y, "origin.xyz"),
                         tuple(q for p, q in zip(x.origin.xyz, y.origin.xyz) if differs(p, q)))
            if differs(x.origin.rpy, y.origin.rpy):
                d["rpy_deg"] = {"old": deg(x.origin.rpy), "new": deg(y.origin.rpy)}
                turn = max(abs(_wrap(q - p)) for p, q in zip(deg(x.origin.rpy), deg(y.origin.rpy)))
                self.add("link", lb, f"{key} origin rpy", fmt(deg(x.origin.rpy), "deg"), fmt(deg(y.origin.rpy), "deg"),
                         f"{fmt(turn)} deg", turn, sn.where(y, "origin.rpy"),
                         tuple(q for p, q in zip(x.origin.rpy, y.origin.rpy) if differs(p, q) and q))
            gx, gy = geom_summary(x.geometry, so), geom_summary(y.geometry, sn)
            mesh_changed = (gx == gy and x.geometry is not None and x.geometry.kind == "mesh"
                            and not _same_shape(x._replace(origin=y.origin), y, so, sn))
            if gx != gy or mesh_changed:
                for g, s, side in ((x.geometry, gx, so), (y.geometry, gy, sn)):
                    if g is not None and g.kind == "mesh":
                        e = side.extent(g)
                        if e is not None:
                            s["extent_mm"] = e
                if gx != gy:
                    d["geometry"] = {"old": gx, "new": gy}
                    if x.geometry is not None and y.geometry is not None and x.geometry.kind != y.geometry.kind:
                        where = sn.element_where(y, "geometry", "*")     # another shape: where it is written
                    else:
                        where = sn.where(y, _geom_field(gx, gy, y.geometry))
                    self.add("link", lb, f"{key} geometry", geom_text(gx), geom_text(gy), _geom_change(gx, gy),
                             _geom_size(gx, gy), where, _geom_values(y.geometry))
            if d:
                ch[key] = d
        for i in left_a[len(left_b):]:
            x = va[i]
            s = geom_summary(x.geometry, so)
            if x.geometry is not None and x.geometry.kind == "mesh" and so.extent(x.geometry) is not None:
                s["extent_mm"] = so.extent(x.geometry)
            ch[f"{kind}[{i}] (old)"] = {"removed": s, "xyz_mm": mm(x.origin.xyz), "rpy_deg": deg(x.origin.rpy),
                                        "world_xyz_mm": _world(so.frames().get(la), x.origin.xyz)}
            self.add("link", lb, f"{kind}[{i}] (old)", geom_text(s), "", "removed", STRUCTURAL / 2,
                     so.where(x, None))
        for k in left_b[len(left_a):]:
            y = vb[k]
            s = geom_summary(y.geometry, sn)
            if y.geometry is not None and y.geometry.kind == "mesh" and sn.extent(y.geometry) is not None:
                s["extent_mm"] = sn.extent(y.geometry)
            ch[f"{kind}[{k}]"] = {"added": s, "xyz_mm": mm(y.origin.xyz), "rpy_deg": deg(y.origin.rpy),
                                  "world_xyz_mm": _world(sn.frames().get(lb), y.origin.xyz)}
            self.add("link", lb, f"{kind}[{k}]", "", geom_text(s), "added", STRUCTURAL / 2,
                     sn.where(y, None, hops_of=("origin.xyz", "origin.rpy") + _GEOM_FIELDS))


def _wrap(d: float) -> float:
    return (d + 180.0) % 360.0 - 180.0


def _world(T, xyz):
    if T is None:
        return None
    p = [T[r][0] * xyz[0] + T[r][1] * xyz[1] + T[r][2] * xyz[2] + T[r][3] for r in range(3)]
    return mm(p)


def _geom_change(gx, gy) -> str:
    if "box_mm" in gx and "box_mm" in gy:
        return ", ".join(f"{ax} {signed(b - a, 'mm')}" for ax, a, b in zip("xyz", gx["box_mm"], gy["box_mm"])
                         if differs(a, b))
    if "cylinder_radius_mm" in gx and "cylinder_radius_mm" in gy:
        out = []
        if differs(gx["cylinder_radius_mm"], gy["cylinder_radius_mm"]):
            out.append(f"r {signed(gy['cylinder_radius_mm'] - gx['cylinder_radius_mm'], 'mm')}")
        if differs(gx["cylinder_length_mm"], gy["cylinder_length_mm"]):
            out.append(f"length {signed(gy['cylinder_length_mm'] - gx['cylinder_length_mm'], 'mm')}")
        return ", ".join(out)
    if "sphere_radius_mm" in gx and "sphere_radius_mm" in gy:
        return f"r {signed(gy['sphere_radius_mm'] - gx['sphere_radius_mm'], 'mm')}"
    if "mesh" in gx and "mesh" in gy:
        if gx.get("mesh") != gy.get("mesh"):
            return "other mesh file"
        if gx.get("scale") != gy.get("scale"):
            return "scale changed"
        if gx.get("extent_mm") and gy.get("extent_mm"):
            return "mesh replaced: " + ", ".join(f"{ax} {signed(b - a, 'mm')}" for ax, a, b in
                                                 zip("xyz", gx["extent_mm"], gy["extent_mm"]) if differs(a, b))
        return "mesh file content changed"
    return "other shape"


def _geom_size(gx, gy) -> float:
    nums = lambda s: [v for k, v in s.items() if k.endswith("_mm") for v in (v if isinstance(v, list) else [v])]
    a, b = nums(gx), nums(gy)
    if len(a) == len(b) and a:
        return max(abs(y - x) for x, y in zip(a, b))
    return STRUCTURAL / 4


def _geom_field(gx, gy, g) -> str | None:
    if g is None:
        return None
    if g.kind == "box":
        return "geometry.size"
    if g.kind == "sphere":
        return "geometry.radius"
    if g.kind == "cylinder":
        if "cylinder_radius_mm" in gx and differs(gx["cylinder_radius_mm"], gy["cylinder_radius_mm"]) \
                or "cylinder_radius_mm" not in gx:
            return "geometry.radius"
        return "geometry.length"
    if g.kind == "mesh":
        return "geometry.scale" if gx.get("mesh") == gy.get("mesh") and gx.get("scale") != gy.get("scale") \
            else "geometry.filename"
    return None


_GEOM_FIELDS = ("geometry.size", "geometry.radius", "geometry.length", "geometry.filename")


def _geom_values(g) -> tuple:
    if g is None:
        return ()
    if g.kind == "box":
        return tuple(g.size)
    if g.kind == "cylinder":
        return (g.radius, g.length)
    if g.kind == "sphere":
        return (g.radius,)
    return tuple(g.scale)


def _limit_view(j):
    if j.limit is None:
        return None
    out = {}
    for k in ("lower", "upper", "effort", "velocity"):
        v = getattr(j.limit, k)
        if v is None:
            continue
        if k in ("lower", "upper"):
            if j.type == "continuous":
                continue
            out[k + ("_mm" if j.type == "prismatic" else "_deg")] = _r(v * 1000, 4) if j.type == "prismatic" \
                else _r(math.degrees(v), 4)
        else:
            out[k] = float(v)
    return out


def _extra(n, k):
    """mimic / dynamics / safety_controller of a joint (its Node ``n``) as {attribute: number or text}."""
    c = n.child(k) if n is not None else None
    if c is None:
        return None
    out = {}
    for a, v in c.attrs:
        try:
            out[a] = float(v)
        except ValueError:
            out[a] = v
    return out


def _rot_angle_deg(A, B) -> float:
    """The angle between two rotations (3x3 of 4x4 transforms): 2·asin(‖A − B‖_F / (2√2)), exactly 0
    for the same matrix."""
    s = 0.0
    for r in range(3):
        for c in range(3):
            s += (A[r][c] - B[r][c]) ** 2
    x = min(1.0, math.sqrt(s) / (2.0 * math.sqrt(2.0)))
    return math.degrees(2.0 * math.asin(x))


def frames_moved(so: Side, sn: Side, lmap, pose: str) -> dict:
    fo, fn = so.frames(pose), sn.frames(pose)
    moved = {}
    for a, b in sorted(lmap.items(), key=lambda kv: kv[1]):
        if a in fo and b in fn:
            A, B = fo[a], fn[b]
            dp = [(B[k][3] - A[k][3]) * 1000.0 for k in range(3)]
            da = _rot_angle_deg(A, B)
            if max(abs(x) for x in dp) > MOVED_MM or da > TURNED_DEG:
                moved[b] = {"old_xyz_mm": mm([A[k][3] for k in range(3)]), "new_xyz_mm": mm([B[k][3] for k in range(3)]),
                            "moved_mm": [_r(x, 4) for x in dp], "distance_mm": _r(math.sqrt(sum(x * x for x in dp)), 4),
                            "rotated_deg": _r(da, 4)}
    return moved


def _first_changed_joint(robot_new, link, changed_joints) -> object:
    """The joint nearest the root on the way to ``link`` whose values changed (the cause of a move)."""
    path = []
    seen = set()
    j = robot_new.parent_joint(link)
    while j is not None and j.name not in seen:
        seen.add(j.name)
        path.append(j)
        j = robot_new.parent_joint(j.parent)
    for j in reversed(path):
        if j.name in changed_joints:
            return j
    return None


# ---------------------------------------------------------------------------------------- drive
def drive_facts(side: Side) -> dict | None:
    """The drive as the comparison sees it: kind, wheels, measured radius/separation/wheelbase, the
    plugin's own numbers; None for a robot without one."""
    robot = side.robot
    d = drive_model.main_drive(robot, guess=True)
    if d is None or not d.left or not d.right or d.missing(robot):
        return None
    g = drive_model.measure(robot, d)
    wheels = g.wheels
    out = {"kind": d.label, "source": d.source, "left": list(d.left), "right": list(d.right),
           "radius_mm": {w.joint: (_r(w.radius * 1000, 3) if w.radius is not None else None) for w in wheels},
           "separation_mm": _r(g.separation * 1000, 3) if g.separation is not None else None,
           "wheelbase_mm": _r((max(w.origin[0] for w in wheels) - min(w.origin[0] for w in wheels)) * 1000, 3)
           if wheels else None}
    plug = {}
    if d.separation is not None:
        plug["separation_mm"] = _r(d.separation * 1000, 3)
    if d.radius is not None:
        plug["radius_mm"] = _r(d.radius * 1000, 3)
    if d.torque is not None:
        plug["torque"] = d.torque
    if d.accel is not None:
        plug["accel"] = d.accel
    if d.update_rate is not None:
        plug["update_rate"] = d.update_rate
    if d.source == "plugin":
        plug["legacy"] = d.legacy
    if plug:
        out["plugin"] = plug
    out["_drive"] = d
    out["_radius"] = g.radius
    out["_separation"] = g.separation
    return out


def drive_effect(do: dict, dn: dict) -> dict:
    """What the change does to the robot for the same velocity command: the wheel speeds come from the
    controller's separation and radius (the plugin's, else unchanged outside the URDF); the motion from
    the wheels as built."""
    out = {}
    ro, rn, so_, sn_ = do["_radius"], dn["_radius"], do["_separation"], dn["_separation"]
    if not (ro and rn and so_ and sn_):
        return out
    po, pn = do.get("plugin", {}), dn.get("plugin", {})
    rpo = po.get("radius_mm", ro * 1000) / 1000
    rpn = pn.get("radius_mm", rn * 1000 if "radius_mm" not in po else po["radius_mm"]) / 1000
    spo = po.get("separation_mm", so_ * 1000) / 1000
    spn = pn.get("separation_mm", sn_ * 1000 if "separation_mm" not in po else po["separation_mm"]) / 1000
    if "plugin" not in do and "plugin" not in dn:      # the controller's numbers live outside the URDF: unchanged
        rpo = rpn = ro
        spo = spn = so_
    speed = (rn / rpn) / (ro / rpo)
    turn = (spn * rn / (rpn * sn_)) / (spo * ro / (rpo * so_))
    if abs(speed - 1) > 1e-6:
        out["speed_factor"] = _r(speed, 4)
    if abs(turn - 1) > 1e-6:
        out["turn_factor"] = _r(turn, 4)
    if do.get("plugin", {}).get("legacy") != dn.get("plugin", {}).get("legacy"):
        out["turns_the_other_way"] = True
    return out


def effect_text(e: dict) -> list[str]:
    """'turns 1.06× faster for the same command', 'drives 0.95× as fast for the same command'."""
    out = []
    for key, verb in (("turn_factor", "turns"), ("speed_factor", "drives")):
        f = e.get(key)
        if f is not None:
            out.append(f"{verb} {f:.2f}× {'faster' if f > 1 else 'as fast'} for the same command")
    if e.get("turns_the_other_way"):
        out.append("turns the other way for the same command (legacyMode)")
    return out


# ---------------------------------------------------------------------------------------- other elements
def _canon_val(s, side: Side):
    if s is None:
        return None
    s = side.norm(s)
    try:
        return tuple(round(float(x), 9) for x in s.split()) if s.split() else s.strip()
    except ValueError:
        return s.strip()


def canon(el, side: Side):
    """A Node (model/nodes.py) as nested tuples, numbers rounded and paths normalised."""
    els = el.elements
    return (el.tag, tuple(sorted((k, _canon_val(v, side)) for k, v in el.attrs)),
            _canon_val(el.text or "", side) if not els else "", tuple(canon(c, side) for c in els))


def key_of(el) -> str:
    return f"{el.tag}" + "".join(f"[{a}={el.get(a)}]" for a in ("name", "reference", "type") if el.get(a))


def describe(x, y, so: Side, sn: Side, path: str = "") -> list[str]:
    here = f"{path}/{x.tag}" if path else x.tag
    out = []
    for k in sorted({a for a, _ in x.attrs} | {a for a, _ in y.attrs}):
        if _canon_val(x.get(k), so) != _canon_val(y.get(k), sn):
            out.append(f"{here}@{k}: {x.get(k)} -> {y.get(k)}")
    cx, cy = list(x.elements), list(y.elements)
    if not cx and not cy:
        if _canon_val(x.text, so) != _canon_val(y.text, sn):
            out.append(f"{here}: {(x.text or '').strip()} -> {(y.text or '').strip()}")
        return out
    if [c.tag for c in cx] != [c.tag for c in cy]:
        out.append(f"{here}: children {[c.tag for c in cx]} -> {[c.tag for c in cy]}")
        return out
    for c1, c2 in zip(cx, cy):
        if canon(c1, so) != canon(c2, sn):
            out += describe(c1, c2, so, sn, here)
    return out


def _first_leaf_change(x, y, so, sn):
    """The first element of ``y`` (new) whose own text or attributes differ from ``x``'s, with the attribute."""
    for k in sorted({a for a, _ in x.attrs} | {a for a, _ in y.attrs}):
        if _canon_val(x.get(k), so) != _canon_val(y.get(k), sn):
            return y, k if y.get(k) is not None else None
    cx, cy = list(x.elements), list(y.elements)
    if not cx and not cy:
        return y, "#text"
    if [c.tag for c in cx] != [c.tag for c in cy]:
        return y, None
    for c1, c2 in zip(cx, cy):
        if canon(c1, so) != canon(c2, sn):
            return _first_leaf_change(c1, c2, so, sn)
    return y, None


def others(robot):
    """The top-level elements besides the tree's links and joints (a typeless <joint> is an SRDF-like
    group or a transmission's: compared as markup)."""
    return [n for n in robot.top_nodes() if n.tag not in ("link", "joint") or (n.tag == "joint" and not n.get("type"))]


# ---------------------------------------------------------------------------------------- compare
def compare(old, new, placeholders_old: dict | None = None, placeholders_new: dict | None = None) -> Comparison:
    """Every change from robot ``old`` to robot ``new`` (see the module doc)."""
    so, sn = Side(old, "old", placeholders_old or {}), Side(new, "new", placeholders_new or {})
    bld = _Builder(so, sn)
    out = bld.data
    if old.name != new.name:
        out["robot_name"] = {"old": old.name, "new": new.name}
        bld.add("robot", new.name, "name", old.name, new.name, "renamed", STRUCTURAL, None)
    lmap, jmap, how = match(old, new)
    renamed_l = {a: b for a, b in lmap.items() if a != b}
    renamed_j = {a: b for a, b in jmap.items() if a != b}
    added_l = sorted(n for n in new.links if n not in set(lmap.values()))
    removed_l = sorted(n for n in old.links if n not in lmap)
    added_j = sorted(n for n in new.joints if n not in set(jmap.values()))
    removed_j = sorted(n for n in old.joints if n not in jmap)
    if renamed_l:
        out["links_renamed"] = [{"old": a, "new": b, "matched_by": how[("link", a)]} for a, b in sorted(renamed_l.items())]
        for a, b in sorted(renamed_l.items()):
            bld.add("link", b, "renamed", a, b, "renamed", STRUCTURAL, sn.where(new.links[b], "name"))
    if renamed_j:
        out["joints_renamed"] = [{"old": a, "new": b, "matched_by": how[("joint", a)]} for a, b in sorted(renamed_j.items())]
        for a, b in sorted(renamed_j.items()):
            bld.add("joint", b, "renamed", a, b, "renamed", STRUCTURAL, sn.where(new.joints[b], "name"))
    if added_l:
        out["links_added"] = added_l
        for n in added_l:
            bld.add("link", n, "added", "", _link_text(new.links[n]), "added", STRUCTURAL, sn.where(new.links[n], None))
    if removed_l:
        out["links_removed"] = removed_l
        for n in removed_l:
            bld.add("link", n, "removed", _link_text(old.links[n]), "", "removed", STRUCTURAL,
                    so.where(old.links[n], None))
    if added_j:
        out["joints_added"] = []
        for n in added_j:
            j = new.joints[n]
            out["joints_added"].append({"name": n, "type": j.type, "parent": j.parent, "child": j.child,
                                        "xyz_mm": mm(j.origin.xyz), "rpy_deg": deg(j.origin.rpy)})
            bld.add("joint", n, "added", "", f"{j.type} {j.parent} → {j.child} at {fmt(mm(j.origin.xyz), 'mm')}",
                    "added", STRUCTURAL, sn.where(j, None))
    if removed_j:
        out["joints_removed"] = []
        for n in removed_j:
            j = old.joints[n]
            out["joints_removed"].append({"name": n, "type": j.type, "parent": j.parent, "child": j.child})
            bld.add("joint", n, "removed", f"{j.type} {j.parent} → {j.child}", "", "removed", STRUCTURAL,
                    so.where(j, None))
    jch = {}
    for a, b in sorted(jmap.items(), key=lambda kv: kv[1]):
        c = bld.joint(old.joints[a], new.joints[b], lmap)
        if c:
            jch[b] = c
    lch = {}
    for a, b in sorted(lmap.items(), key=lambda kv: kv[1]):
        c = bld.link(old.links[a], new.links[b])
        if c:
            lch[b] = c
    if jch:
        out["joints_changed"] = jch
    if lch:
        out["links_changed"] = lch
    # frames in the world: at the zero pose; at the rest pose where that differs
    changed_joints = set(jch) | set(added_j) | set(renamed_j.values())
    for pose in ("zero", "rest"):
        moved = frames_moved(so, sn, lmap, pose)
        if pose == "rest":
            zero = out.get("frames_moved_zero_pose", {})
            moved = {k: v for k, v in moved.items() if k not in zero
                     or abs(zero[k]["distance_mm"] - v["distance_mm"]) > 1e-4
                     or abs(zero[k]["rotated_deg"] - v["rotated_deg"]) > 1e-4}
        if moved:
            out[f"frames_moved_{pose}_pose"] = moved
            for link, m in moved.items():
                cause = _first_changed_joint(new, link, changed_joints)
                where = None
                if cause is not None:
                    c = jch.get(cause.name, {})
                    field = "origin.rpy" if "rpy_deg" in c and "xyz_mm" not in c else "origin.xyz" \
                        if "xyz_mm" in c else None
                    where = sn.where(cause, field) if field else sn.where(cause, None)
                text = []
                if m["distance_mm"] > MOVED_MM:
                    text.append(f"{fmt(m['distance_mm'])} mm")
                if m["rotated_deg"] > TURNED_DEG:
                    text.append(f"{fmt(m['rotated_deg'])} deg")
                bld.add("frame", link, f"moved ({pose} pose)", fmt(m["old_xyz_mm"], "mm"), fmt(m["new_xyz_mm"], "mm"),
                        ", ".join(text), m["distance_mm"] + m["rotated_deg"], where)
    # the whole robot's mass and centre of mass (zero pose)
    mo, co = _mass(so)
    mn, cn = _mass(sn)
    if abs(mo - mn) > 1e-9 or max(abs(x - y) for x, y in zip(co, cn)) > 1e-9:
        out["total_mass_kg"] = {"old": round(mo, 9), "new": round(mn, 9), "delta": round(mn - mo, 9)}
        out["centre_of_mass_mm"] = {"old": mm(co), "new": mm(cn), "moved": [_r((y - x) * 1000, 4) for x, y in zip(co, cn)]}
        if abs(mo - mn) > 1e-9:
            bld.add("mass", new.name, "total mass", fmt(mo, "kg"), fmt(mn, "kg"),
                    f"{signed(mn - mo, 'kg')} ({signed(100 * (mn - mo) / mo if mo else 100.0)} %)", rel_size(mo, mn), None)
        dist = math.dist(co, cn) * 1000
        if dist > 1e-6:
            bld.add("mass", new.name, "centre of mass", fmt(mm(co), "mm"), fmt(mm(cn), "mm"), f"{fmt(dist)} mm", dist, None)
    # the drive
    do, dn = drive_facts(so), drive_facts(sn)
    pub = lambda d: {k: v for k, v in d.items() if not k.startswith("_")} if d else None
    if pub(do) != pub(dn):
        block: dict = {"old": pub(do), "new": pub(dn)}
        if do and dn:
            eff = drive_effect(do, dn)
            if eff:
                block["effect"] = eff
                block["effect_text"] = effect_text(eff)
        out["drive"] = block
        _drive_items(bld, do, dn, jch)
    # every other top-level element (gazebo, transmission, ros2_control, material...)
    oth, sensors = _compare_others(bld, so, sn, lmap)
    if sensors:
        out.update(sensors)
    if oth:
        out["other_elements"] = oth
    bld.items.sort(key=lambda it: -it.size)
    return Comparison(out, bld.items)


def _link_text(link) -> str:
    parts = []
    if link.inertial is not None:
        parts.append(f"{fmt(link.inertial.mass, 'kg')}")
    if link.visuals:
        parts.append(f"{len(link.visuals)} visual")
    if link.collisions:
        parts.append(f"{len(link.collisions)} collision")
    return ", ".join(parts) or "empty"


def _mass(side: Side):
    fr = side.frames()
    total, acc = 0.0, [0.0, 0.0, 0.0]
    for name, link in side.robot.links.items():
        i = link.inertial
        if i is None or name not in fr:
            continue
        T = fr[name]
        p = [T[r][0] * i.origin.xyz[0] + T[r][1] * i.origin.xyz[1] + T[r][2] * i.origin.xyz[2] + T[r][3]
             for r in range(3)]
        total += i.mass
        acc = [acc[k] + i.mass * p[k] for k in range(3)]
    return total, ([a / total for a in acc] if total else [0.0, 0.0, 0.0])


def _drive_items(bld, do, dn, jch):
    sn = bld.sn
    if do is None or dn is None:
        d = dn or do
        bld.add("drive", d["kind"], "drive", "" if do is None else d["kind"], "" if dn is None else d["kind"],
                "added" if do is None else "removed", STRUCTURAL, None)
        return
    new_drive = dn["_drive"]

    def joint_where():
        for n in dn["left"] + dn["right"]:
            if n in jch and "xyz_mm" in jch[n]:
                return sn.where(sn.robot.joints[n], "origin.xyz")
        return None

    if do["kind"] != dn["kind"] or do["left"] != dn["left"] or do["right"] != dn["right"]:
        bld.add("drive", dn["kind"], "kind and wheels", f"{do['kind']} {do['left']}/{do['right']}",
                f"{dn['kind']} {dn['left']}/{dn['right']}", "changed", STRUCTURAL / 2, sn.where(new_drive.plugin, None)
                if new_drive.plugin is not None else None)
    for key, label in (("separation_mm", "wheel separation (built)"), ("wheelbase_mm", "wheelbase (built)")):
        a, b = do.get(key), dn.get(key)
        if a is not None and b is not None and differs(a, b):
            bld.add("drive", dn["kind"], label, fmt(a, "mm"), fmt(b, "mm"), signed(b - a, "mm"), abs(b - a), joint_where())
    ra, rb = do["_radius"], dn["_radius"]
    if ra and rb and differs(round(ra * 1000, 3), round(rb * 1000, 3)):
        bld.add("drive", dn["kind"], "wheel radius (built)", fmt(ra * 1000, "mm"), fmt(rb * 1000, "mm"),
                signed((rb - ra) * 1000, "mm"), abs(rb - ra) * 1000, None)
    pa, pb = do.get("plugin", {}), dn.get("plugin", {})
    keys = {"separation_mm": "separation", "radius_mm": "radius", "torque": "torque", "accel": "accel",
            "update_rate": "update_rate"}
    for k in sorted(set(pa) | set(pb)):
        if k == "legacy":
            continue
        a, b = pa.get(k), pb.get(k)
        if a is None or b is None or differs(a, b):
            where = None
            d = new_drive
            spec = d.spec
            if spec is not None and d.plugin is not None:
                key = {"separation": spec.separation, "radius": spec.radius or spec.diameter, "torque": spec.torque,
                       "accel": spec.accel, "update_rate": spec.rate}.get(keys.get(k, k))
                if key:
                    where = sn.where(d.plugin, key)
            label, unit = {"separation_mm": ("wheel separation", "mm"), "radius_mm": ("wheel radius", "mm"),
                           "torque": ("torque", "N·m"), "accel": ("acceleration", d.spec.accel_unit if d.spec else ""),
                           "update_rate": ("update rate", "Hz")}.get(k, (k, ""))
            bld.add("drive", dn["kind"], f"plugin {label}", fmt(a, unit), fmt(b, unit),
                    signed(b - a, unit) if a is not None and b is not None else "changed",
                    rel_size(a, b) if a is not None and b is not None else STRUCTURAL / 4, where)
    eff = drive_effect(do, dn)
    for t in effect_text(eff):
        f = max(abs(eff.get("turn_factor", 1) - 1), abs(eff.get("speed_factor", 1) - 1)) * 100
        bld.add("drive", dn["kind"], "effect", "", "", t, STRUCTURAL / 2 + f, None)


def _compare_others(bld, so: Side, sn: Side, lmap):
    def bag(side):
        out: dict = {}
        for el in others(side.robot):
            out.setdefault(key_of(el), []).append(el)
        return out

    a, b = bag(so), bag(sn)
    out = {}
    for k in sorted(set(a) | set(b)):
        ca = sorted(repr(canon(e, so)) for e in a.get(k, []))
        cb = sorted(repr(canon(e, sn)) for e in b.get(k, []))
        if ca == cb:
            continue
        if not ca:
            out[k] = "added"
            bld.add("element", k, "added", "", "", "added", STRUCTURAL / 2, sn.where(b[k][0], None))
        elif not cb:
            out[k] = "removed"
            bld.add("element", k, "removed", "", "", "removed", STRUCTURAL / 2, so.where(a[k][0], None))
        else:
            # pair the identical ones first, then the rest in order
            la, lb = list(a[k]), list(b[k])
            for x in list(la):
                cx = canon(x, so)
                same = [y for y in lb if canon(y, sn) == cx]
                if same:
                    la.remove(x)
                    lb.remove(same[0])
            descs = []
            for x, y in zip(la, lb):
                d = describe(x, y, so, sn)
                descs += d
                el, attr = _first_leaf_change(x, y, so, sn)
                where = None
                try:
                    where = Where(*_span_of(sn, el, attr)) if el is not None else None
                except Exception:
                    where = None
                bld.add("element", k, "changed", "", "", "; ".join(d)[:300], STRUCTURAL / 8, where)
            extra = len(lb) - len(la)
            if extra:
                descs.append(f"{abs(extra)} {'more' if extra > 0 else 'fewer'}")
                if not la and not lb:
                    pass
            out[k] = "changed: " + "; ".join(descs)
    return out, _sensors(bld, so, sn, lmap)


def _span_of(side: Side, el, attr):
    src = side.robot.sources
    if attr is not None:
        o = src.origin(el, attr)
        span = o.written or o.expr or o.at
        if span is not None:
            kind = "expr" if o.written is None and o.expr is not None else o.kind
            return span, kind, o.name, "new"
    span = src.start_tag(el)
    if span is None:
        raise ValueError
    return span, "element", None, "new"


def _sensors(bld, so: Side, sn: Side, lmap) -> dict:
    """Sensors added, removed or renamed: by name, then by type and (paired) link."""
    old = {s.name or f"{s.type}@{s.reference}": s for s in so.robot.sensors()}
    new = {s.name or f"{s.type}@{s.reference}": s for s in sn.robot.sensors()}
    smap = {n: n for n in old if n in new}
    left_new = [n for n in new if n not in smap]
    for n in [n for n in old if n not in smap]:
        s = old[n]
        c = [m for m in left_new if new[m].type == s.type and new[m].reference == lmap.get(s.reference, s.reference)]
        if len(c) == 1:
            smap[n] = c[0]
            left_new.remove(c[0])
    out: dict = {}
    ren = sorted((a, b) for a, b in smap.items() if a != b)
    if ren:
        out["sensors_renamed"] = [{"old": a, "new": b} for a, b in ren]
        for a, b in ren:
            bld.add("sensor", b, "renamed", a, b, "renamed", STRUCTURAL, sn.where(new[b], None))
    added = sorted(n for n in new if n not in set(smap.values()))
    removed = sorted(n for n in old if n not in smap)
    if added:
        out["sensors_added"] = [{"name": n, "type": new[n].type, "link": new[n].reference} for n in added]
        for n in added:
            bld.add("sensor", n, "added", "", f"{new[n].type} on {new[n].reference}", "added", STRUCTURAL,
                    sn.where(new[n], None))
    if removed:
        out["sensors_removed"] = [{"name": n, "type": old[n].type, "link": old[n].reference} for n in removed]
        for n in removed:
            bld.add("sensor", n, "removed", f"{old[n].type} on {old[n].reference}", "", "removed", STRUCTURAL,
                    so.where(old[n], None))
    return out
