"""I: inertia against the link's geometry (solid body of uniform density at the declared mass).

Primitives are always measured (closed forms, cheap). Meshes are measured only when
mesh files are loaded (`--inertia`), and only when watertight.

Without meshes no numpy is needed for an ordinary robot: pure-Python screens, with margins for the
ulps by which they differ from numpy's products, clear the links that cannot be reported; the others
are measured in pure Python where that gives numpy's floats to the bit (unrotated shapes, a diagonal
tensor), else with numpy, so that the numbers a finding reports are the same either way.
"""

from __future__ import annotations

import math

from myrabot_desc.checks.examples import tetrahedron_stl
from myrabot_desc.checks.rule import Finding, Fix, FixInfo, LazyFix, SetValue, rule
from myrabot_desc.model import shapes as G
from myrabot_desc.model.inertia import eigh3, tensor
from myrabot_desc.model.kinematics import pose_matrix, pose_stack
from myrabot_desc.model.transforms import matmul3, place, pose_T, rotate, transpose3


def _part(body: str, name: str = "chassis") -> str:
    """Example snippet: link `name` with `body` inside, fixed to base_link."""
    inner = "\n".join("  " + line for line in body.splitlines())
    return (f'<link name="{name}">\n{inner}\n</link>\n<joint name="{name}_joint" type="fixed">\n'
            f'  <parent link="base_link"/>\n  <child link="{name}"/>\n</joint>')


def _inertial(mass, ixx, iyy, izz, xyz="0 0 0") -> str:
    return (f'<inertial>\n  <origin xyz="{xyz}"/>\n  <mass value="{mass}"/>\n'
            f'  <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/>\n</inertial>')


def _collision(geometry: str, xyz="0 0 0") -> str:
    return f'<collision>\n  <origin xyz="{xyz}"/>\n  <geometry>{geometry}</geometry>\n</collision>'


_BOX = '<box size="0.3 0.25 0.1"/>'
_DISC = '<cylinder radius="0.17" length="0.063"/>'

RATIO_LIMIT = 10.0
MARKER_SIZE = 0.005                 # m: geometry smaller than this is a frame marker; findings drop to info
DENSITY_RANGE = (100.0, 23000.0)    # kg/m³: below balsa-and-foam structures, above osmium


class Solid:
    """A link's geometry as a uniform solid at the declared mass (link frame), or why not.

    ``props`` of primitives only are pure Python: placed_primitive's (numpy's floats to the bit) or
    combine_pure's (combine's volume and centroid, its tensor within a few ulps); with meshes,
    combine's (numpy is loaded with them)."""

    # (20,000 of them in a star)
    __slots__ = ("link", "source", "items", "props", "why_not", "marker", "desc")

    def __init__(self, ctx, link, same: dict | None = None):
        self.link = link
        self.source, self.items = ctx.shapes(link, "collision")
        self.props = None
        self.why_not = None
        self.marker = False
        if len(self.items) == 1:        # most links: one primitive, unrotated (no numpy for it)
            mass = link.inertial.mass if link.inertial else 0.0
            one = _one_shape(self.items[0], mass if mass > 0 else 1.0, same)
            self.desc = one[0]
            if one[1] is not NotImplemented:
                self.props, self.marker = one[1], one[2]
                return
        else:
            self.desc = (", ".join(G.describe(it.geometry) for it in self.items[:3])
                         + (" ..." if len(self.items) > 3 else ""))
        if not self.items:
            self.why_not = "no geometry"
            return
        mass = link.inertial.mass if link.inertial else 0.0
        parts = []
        meshes = False
        for it in self.items:
            g = it.geometry
            mesh = None
            if g.kind == "mesh":
                if not ctx.opts.load_meshes:
                    self.why_not = "mesh geometry (measured with --inertia)"
                    return
                mesh = ctx.mesh(g)
                if mesh is None or isinstance(mesh, str):
                    self.why_not = f"mesh {g.filename} cannot be read" + (f" ({mesh})" if mesh else "")
                    return
                meshes = True
            sp = G.shape_props(g, mesh)
            if sp is None:
                self.why_not = (f"mesh {g.filename.rsplit('/', 1)[-1]} is not watertight"
                                if mesh is not None and not mesh.is_watertight else
                                f"mesh {g.filename.rsplit('/', 1)[-1]} has no positive volume (inverted or open)")
                return
            parts.append((*sp, it.origin))
        if meshes:                      # numpy is loaded with the meshes: combine's floats at once
            self.props = G.combine([(*pt[:3], pose_matrix(pt[3])) for pt in parts], mass if mass > 0 else 1.0)
        else:
            self.props = G.combine_pure([(*pt[:3], pose_T(pt[3])) for pt in parts], mass if mass > 0 else 1.0)
        sizes = [G.size_of(it.geometry, ctx.mesh(it.geometry) if it.geometry.kind == "mesh" else None)
                 for it in self.items]
        self.marker = all(sz is not None and sz < MARKER_SIZE for sz in sizes)

    @property
    def severity(self):
        """info for frame markers (a 1 mm box on a sensor frame), else the rule's default."""
        return "info" if self.marker else None

    def framed(self) -> tuple:
        """(com in the inertial frame, tensor in the inertial axes about the solid's com as three
        row lists) of ``props``: R^T (com - p) and R^T I R, R and p the inertial origin's."""
        R, p = pose_T(self.link.inertial.origin)
        Rt = transpose3(R)
        t = [list(row) for row in matmul3(matmul3(Rt, self.props.inertia), R)]
        c = self.props.com
        return rotate(Rt, (c[0] - p[0], c[1] - p[1], c[2] - p[2])), t


def _one_shape(item, mass: float, same: dict | None) -> tuple:
    """(description, placed_primitive's props or NotImplemented, marker) of a link's one shape at
    ``mass``. ``same``: the results by the identity of the values they come from: the links of one
    macro repeat their shape, origin and mass, which the loader reads into the same objects (an
    identity is never a -0.0 taken for 0.0); the objects are kept with the result, so no id is reused."""
    g, o = item.geometry, item.origin
    key = (g.__class__, *map(id, g), id(o.xyz), id(o.rpy), id(mass))
    hit = same.get(key) if same is not None else None
    if hit is None:
        props = G.placed_primitive(g, o, mass)
        marker = False
        if props is not NotImplemented:
            sz = G.size_of(g)
            marker = sz is not None and sz < MARKER_SIZE
        hit = (G.describe(g), props, marker, (g, o, mass))
        if same is not None:
            same[key] = hit
    return hit


def solids(ctx) -> dict:
    """link -> its Solid, for every link with mass (built once per robot and mesh option)."""
    def build():
        same: dict = {}
        return {link.name: Solid(ctx, link, same) for link in ctx.robot.links.values()
                if link.inertial and link.inertial.mass > 0}
    return ctx.fact("solids", build, meshes=True)


def fmt(x: float) -> str:
    return f"{x:.3g}"


def inertia_line(t) -> str:
    """The <inertia/> element of a 3x3 tensor (an array or nested lists)."""
    return _line(_six(t))


@rule("I006", "inertia-vs-geometry", "warning",
      bad=_part(_collision(_BOX) + "\n" + _inertial(1, 1, 1, 1)),
      message="link chassis: inertia ixx/iyy/izz 1/1/1 kg·m², but a solid box 0.3×0.25×0.1 m of 1 kg gives "
              "0.00604/0.00833/0.0127 (ratio 166×/120×/79×); fix: "
              '<inertia ixx="0.006042" ixy="0" ixz="0" iyy="0.008333" iyz="0" izz="0.01271"/>',
      good=_part(_collision(_BOX) + "\n" + _inertial(1, 0.006042, 0.008333, 0.01271)),
      fix=FixInfo("always", "unsafe", "the six `<inertia>` values become the solid body's (4 significant digits, "
                  "as the message prints them). Unsafe: it assumes a uniform density filling the collision "
                  "geometry, which a hollow shell or a part with a motor inside is not."))
def inertia_vs_geometry(ctx):
    """The inertia differs more than 10× from the solid body of the link's collision geometry.

    We compute the tensor of the collision geometry (visual when there is none) as a
    uniform solid at the declared mass, about its centroid, in the inertial frame's
    axes, and compare the diagonal. 10× either way is beyond any real mass
    distribution: it is a placeholder (ixx=iyy=izz=1 on a 1 kg part is 100× too large)
    and it makes the body spin too easily or too sluggishly. Fix: the computed values
    given in the message (`--inertia --suggest` prints the `<inertia/>` line).
    """
    suggest = ctx.opts.suggest
    solid = [(name, s) for name, s in solids(ctx).items() if s.props is not None]
    if not suggest:                     # (suggest: a line for every link) only the links that may be reported
        solid = _beyond_limit(solid)
    if not solid:
        return
    # links repeat (the same props and origin objects: _one_shape, the loader): each frame and
    # comparison is made once per distinct set of the objects it reads (kept alive by the links)
    frame_key = [(id(s.props), id(s.link.inertial.origin.xyz), id(s.link.inertial.origin.rpy)) for _, s in solid]
    first: dict = {}
    for k, key in enumerate(frame_key):
        first.setdefault(key, k)
    framed_of = {key: _unrotated(solid[k][1].props, solid[k][1].link.inertial.origin) or _rotated(solid[k][1])
                 for key, k in first.items()}
    compared: dict = {}
    for (name, s), fkey in zip(solid, frame_key):
        i = s.link.inertial
        key = (fkey, id(i.ixx), id(i.iyy), id(i.izz), id(i.mass), s.desc)
        c = compared.get(key)
        if c is None:
            c = compared[key] = _compare(i, s.desc, framed_of[fkey])
        texts, line, tail, data = c
        if suggest:
            ctx.suggestions.append((name, line))
        if tail is not None:
            yield Finding(
                f"link {name}: {tail}", i.loc or s.link.loc,
                # tuples: the report writes them as lists; the collector stops scanning them (8 lists x 20,000 links)
                {"link": name, "declared": data[0], "computed": data[1], "ratios": data[2], "geometry": s.source,
                 "fix": line, "computed_tensor": data[3], "computed_com": data[4]},
                severity=s.severity, fix=LazyFix(_solid_fix, i, texts, name, s.source))


SCREEN = 1e-6      # relative: a screen's measure this close to a limit leaves the verdict to the reported floats


def _beyond_limit(solid: list) -> list:
    """The (name, Solid) of ``solid`` whose diagonal may differ more than RATIO_LIMIT from the solid
    body's: framed()'s floats clear the others (a margin of SCREEN on the ratio and on the zeroing
    of round-off), so that the texts and the <inertia/> line are made for the findings only. Links
    repeat their objects (the loader, _one_shape): each set is screened once."""
    seen: dict = {}
    out = []
    for name, s in solid:
        i = s.link.inertial
        key = (id(s.props), id(i.origin.xyz), id(i.origin.rpy), id(i.ixx), id(i.iyy), id(i.izz))
        hit = seen.get(key)
        if hit is None:
            hit = seen[key] = _may_exceed(s)
        if hit:
            out.append((name, s))
    return out


def _may_exceed(s) -> bool:
    com, t = s.framed()
    flat = [v for row in t for v in row]
    if not all(map(math.isfinite, flat)) or not all(map(math.isfinite, com)):
        return True
    lim = 1e-6 * max(map(abs, flat))
    i = s.link.inertial
    for d, c in zip((float(i.ixx), float(i.iyy), float(i.izz)), (t[0][0], t[1][1], t[2][2])):
        if abs(abs(c) - lim) <= SCREEN * lim:
            return True
        if abs(c) < lim:
            c = 0.0
        if c <= 0 or d <= 0:
            if (c <= 0) != (d <= 0):
                return True
            continue
        r = d / c
        if not max(r, 1 / r) <= RATIO_LIMIT * (1 - SCREEN):
            return True
    return False


def _compare(i, desc: str, framed) -> tuple:
    """(the six texts, the <inertia/> line, the message after "link NAME: " or None when within
    RATIO_LIMIT, (declared, computed, ratios, tensor, com)) of inertial ``i`` against its solid."""
    t9, com = framed
    comp = (tuple(t9[0:3]), tuple(t9[3:6]), tuple(t9[6:9]))
    texts = _six(comp)
    line = _line(texts)
    dd, cd = (float(i.ixx), float(i.iyy), float(i.izz)), (t9[0], t9[4], t9[8])
    ratios = []
    worst = -math.inf
    for d, c in zip(dd, cd):
        if c <= 0 or d <= 0:
            r = math.inf if (c <= 0) != (d <= 0) else 1.0
        else:
            r = d / c
        ratios.append(r)
        w = max(r, 1 / r) if r > 0 else math.inf
        if w > worst:
            worst = w
    tail = None
    if worst > RATIO_LIMIT:
        tail = (f"inertia ixx/iyy/izz {dd[0]:.3g}/{dd[1]:.3g}/{dd[2]:.3g} kg·m², but a solid "
                f"{desc} of {i.mass:g} kg gives {cd[0]:.3g}/{cd[1]:.3g}/{cd[2]:.3g} "
                f"(ratio {_ratio(ratios[0])}/{_ratio(ratios[1])}/{_ratio(ratios[2])}); fix: {line}")
    return texts, line, tail, (dd, cd, tuple(ratios), comp, com)


def _unrotated(props, origin):
    """(flat tensor, com) of ``props`` in an inertial frame without rotation (less round-off), or
    None (a rotated frame: ``_rotated``; a value that is not finite).

    R is then the identity (zeros of either sign): every product of R^T t R and R^T (com - p) is
    by 1 or a zero, and neither t nor com holds a -0 (combine's sums start at +0), so the floats
    are t's and com - p's."""
    r, p, y = origin.rpy
    if r != 0 or p != 0 or y != 0:
        return None
    (a, b, c), (d, e, f), (g, h, k) = props.inertia
    t9 = [a, b, c, d, e, f, g, h, k]
    x, yy, z = origin.xyz
    cx, cy, cz = props.com
    com = (cx - float(x), cy - float(yy), cz - float(z))
    if not all(map(math.isfinite, t9)) or not all(map(math.isfinite, com)):
        return None
    lim = 1e-6 * max(map(abs, t9))
    return [0.0 if abs(v) < lim else v for v in t9], com


def _rotated(s) -> tuple:
    """(flat tensor, com) of Solid ``s`` in its inertial frame: ``framed()``, less the round-off of
    the rotation (rpy 1.570796 leaves products of inertia of 1e-17 that no part has). In pure
    Python, as the screens: numpy's 3x3 products would differ in the last bits only, and would cost
    a check its import (~0.1 s) for a robot with one rotated part."""
    com, t = s.framed()
    t9 = [v for row in t for v in row]
    mags = [abs(v) for v in t9]
    lim = 1e-6 * (math.nan if any(map(math.isnan, mags)) else max(mags))    # (NaN: nothing is round-off)
    return [0.0 if abs(v) < lim else v for v in t9], com


def _six(t) -> tuple:
    """ixx, ixy, ixz, iyy, iyz, izz of a 3x3 tensor written to 4 significant digits."""
    return (f"{t[0][0]:.4g}", f"{t[0][1]:.4g}", f"{t[0][2]:.4g}", f"{t[1][1]:.4g}", f"{t[1][2]:.4g}", f"{t[2][2]:.4g}")


def _line(v) -> str:
    return (f'<inertia ixx="{v[0]}" ixy="{v[1]}" ixz="{v[2]}" '
            f'iyy="{v[3]}" iyz="{v[4]}" izz="{v[5]}"/>').replace('"-0"', '"0"')


_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def tensor_fix(inertial, t, title: str, safety: str = "unsafe") -> Fix:
    """Set the six values of ``inertial``'s <inertia> to tensor ``t`` (4 significant digits, as
    inertia_line prints them)."""
    return _texts_fix(inertial, _six(t), title, safety)


def _solid_fix(inertial, texts, name: str, source: str) -> Fix:
    return _texts_fix(inertial, texts, f"inertia of {name} from its {source} geometry")


def _texts_fix(inertial, texts, title: str, safety: str = "unsafe") -> Fix:
    return Fix(tuple(SetValue(inertial, k, float(v) + 0.0) for k, v in zip(_KEYS, texts)), safety, title)


def _ratio(r: float) -> str:
    """declared / computed: ``166×``, ``1.5×``, ``0.5×``, ``7e-06×`` (never ``1/x``: the ratios are
    joined with ``/``)."""
    if math.isinf(r):
        return "∞"
    return f"{r:.0f}×" if r >= 10 else f"{r:.2g}×"


@rule("I007", "radius-of-gyration", "warning",
      bad=_part(_collision(_DISC) + "\n" + _inertial(3.6, 0.01, 0.01, 0.5)),
      message="link chassis: radius of gyration √(0.5/3.6) = 0.373 m about axis (0 0 1), but no point of the "
              "geometry is farther than 0.17 m from that axis",
      good=_part(_collision(_DISC) + "\n" + _inertial(3.6, 0.0272, 0.0272, 0.05202)))
def radius_of_gyration(ctx):
    """A radius of gyration √(I/m) larger than the body: no mass distribution inside the shape gives it.

    Every bit of mass lies within the link's geometry, so about any axis through the
    centre of mass I ≤ m·ρ², with ρ the farthest point of the geometry from that axis.
    Example: the Roomba base, izz 0.5 at 3.6 kg is √(0.5/3.6) = 0.37 m on a 0.17 m
    radius disc. Fix: the solid-body values (`--inertia --suggest`).
    """
    # links that repeat their points, inertial origin, tensor and mass (the loader's shared values)
    # are measured once: the key's objects stay alive with the links
    key_of: dict = {}
    found: dict = {}                        # key -> (the message after "link NAME: ", its data) or None
    some, whole = pure_hull_points(ctx, 8), pure_hull_points(ctx)
    meshes = set()
    for name, s in solids(ctx).items():
        pts = some[name]
        if pts is None:
            meshes.add(name)
            continue
        i = s.link.inertial
        key = key_of[name] = _gyration_key(i, pts)
        if key not in found:
            found[key] = _pure_gyration(i, pts, whole, name)
    if meshes and ctx.opts.load_meshes:     # (numpy is loaded with the meshes)
        _numpy_gyration(ctx, meshes, found, key_of)
    for name, s in solids(ctx).items():
        key = key_of.get(name)
        worst = found[key] if key is not None else None
        if worst:
            link = s.link
            tail, kg, reach, moment = worst
            yield Finding(f"link {name}: {tail}", link.inertial.loc or link.loc,
                          {"link": name, "radius_of_gyration": kg, "reach": reach, "moment": moment},
                          severity=s.severity)


def _gyration_key(i, pts) -> tuple:
    """The identities of what radius_of_gyration reads of a link: its points and inertial."""
    return (id(pts), id(i.origin.xyz), id(i.origin.rpy), id(i.ixx), id(i.ixy), id(i.ixz), id(i.iyy),
            id(i.iyz), id(i.izz), id(i.mass))


def _pure_gyration(i, some, whole, name):
    """radius_of_gyration's measure of link ``name`` of primitives in pure Python: eigh3's principal
    axes, the farthest point from each; _worst's result. ``some``: some of its points (a subset of
    ``whole[name]``, pure_hull_points): most links are clear, and a subset's farthest point is at most
    the whole set's, each measured alike, so a link they clear is clear; the rest are measured whole."""
    t = tensor(i)
    if not math.isfinite(sum(v for row in t for v in row) + i.mass):
        return None                     # (numpy's eigh has no moments for these either)
    ev, V = eigh3(t)
    axes = [V[r][n] for n in range(3) for r in range(3)]
    reaches = _reaches(i, some, axes)
    if reaches is not None and _worst(i, ev, axes, reaches) is None:
        return None
    reaches = _reaches(i, whole[name], axes)
    return None if reaches is None else _worst(i, ev, axes, reaches)


def _reaches(i, pts, axes):
    """The farthest distance of ``pts`` (link frame) from each principal axis (``axes``: flat, three
    by three) through the inertial origin of ``i``; None for a point that is not finite."""
    R, (px, py, pz) = pose_T(i.origin)
    if any(i.origin.rpy):
        (a, b, c), (d, e, f), (g, h, k) = R
        local = []                      # R^T (x - p): the points in the inertial frame
        for x, y, z in pts:
            x, y, z = x - px, y - py, z - pz
            local.append((a * x + d * y + g * z, b * x + e * y + h * z, c * x + f * y + k * z))
    else:                               # (the products by 1 and 0 give these floats, up to zeros' signs)
        local = [(x - px, y - py, z - pz) for x, y, z in pts]
    sq = [x * x + y * y + z * z for x, y, z in local]
    if not math.isfinite(sum(sq)):
        return None                     # a point not finite (nor is its square)
    reaches = []
    for n in range(3):
        u = axes[3 * n:3 * n + 3]
        col = u.index(1.0) if 1.0 in u else u.index(-1.0) if -1.0 in u else None
        if col is not None and u.count(0.0) == 2:   # a unit axis (a diagonal tensor): the coordinate is the product
            far = max([q - p[col] * p[col] for q, p in zip(sq, local)])
        else:
            ux, uy, uz = u
            far = max([q - (x * ux + y * uy + z * uz) ** 2 for q, (x, y, z) in zip(sq, local)])
        reaches.append(math.sqrt(max(far, 0.0)))
    return reaches


def _numpy_gyration(ctx, names, found: dict, key_of: dict) -> None:
    """radius_of_gyration's measure of the links ``names`` (those with meshes) with numpy, into
    ``found`` and ``key_of``: one stacked product per point count."""
    import numpy as np

    pts_of = hull_points(ctx)
    by_size: dict[int, list] = {}          # one link per key, grouped by point count: one stacked product per group
    for name, s in solids(ctx).items():
        pts = pts_of[name]
        if pts is not None and name in names:
            key = key_of[name] = _gyration_key(s.link.inertial, pts)
            if key not in found:
                found[key] = None
                by_size.setdefault(len(pts), []).append((key, s))
    for group in by_size.values():
        pts = np.array([pts_of[s.link.name] for _, s in group], dtype=float)
        T = pose_stack(s.link.inertial.origin for _, s in group)
        local = (pts - T[:, None, :3, 3]) @ T[:, :3, :3]           # points in the inertial frame
        tensors: list[float] = []
        for _, s in group:
            i = s.link.inertial
            tensors.extend((i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz))   # Inertial.tensor()
        ev, vec = np.linalg.eigh(np.array(tensors, dtype=float).reshape(-1, 3, 3))
        sq = (local ** 2).sum(2)
        reach = np.stack([np.sqrt(np.maximum(sq - (local @ vec[:, :, k:k + 1])[:, :, 0] ** 2, 0)).max(1)
                          for k in range(3)], axis=1)
        ev, axes, reaches = ev.ravel().tolist(), np.swapaxes(vec, 1, 2).ravel().tolist(), reach.ravel().tolist()
        for n, (key, s) in enumerate(group):
            found[key] = _worst(s.link.inertial, ev[3 * n:3 * n + 3], axes[9 * n:9 * n + 9], reaches[3 * n:3 * n + 3])


def _worst(i, ev, axes, reaches):
    """(the message after "link NAME: ", radius of gyration, reach, moment) of the principal axis of
    inertial ``i`` whose radius of gyration most exceeds its reach, or None: ``ev`` the principal
    moments, ``axes`` their axes (flat, three by three), ``reaches`` the farthest point from each."""
    mass = i.mass
    worst = None
    for b in range(3):
        e = ev[b]
        if e <= 0:
            continue
        reach = reaches[b]
        kg = math.sqrt(e / mass)
        if kg > 1.1 * reach + 1e-4 and (worst is None or kg / max(reach, 1e-9) > worst[0]):
            worst = (kg / max(reach, 1e-9), kg, reach, e, axes[3 * b:3 * b + 3])
    if worst is None:
        return None
    _, kg, reach, moment, u = worst
    u = _canonical_axis(u)
    return (f"radius of gyration √({moment:.3g}/{i.mass:g}) = {kg:.3g} m about axis "
            f"({u[0]:.2g} {u[1]:.2g} {u[2]:.2g}), but no point of the geometry is farther than "
            f"{reach:.3g} m from that axis", kg, reach, float(moment))


def _canonical_axis(u) -> list:
    """``u`` or ``-u`` (one axis), whichever has its component of largest magnitude (the first of
    equals) positive, and no -0.0: the same axis whichever solver's sign came out."""
    big = max(range(3), key=lambda k: abs(u[k]))
    s = -1.0 if u[big] < 0 else 1.0
    return [s * v + 0.0 for v in u]


def pure_hull_points(ctx, samples: int = 32) -> dict:
    """hull_points in pure Python, without meshes (a mesh's link: None, as hull_points without
    --inertia): link -> list of (x, y, z), within an ulp or so of hull_points' rows, built for a link
    when first asked; links that repeat a shape and its origin share the list. What I007 and I010
    measure. ``samples`` 8 gives some of the 32's points, bit for bit (every fourth of a ring: the
    angles 2πk/8 are 2π(4k)/32, and a box has its corners either way): the rules ask those first."""
    return ctx.fact(f"pure_hull_points/{samples}", lambda: _PurePoints(solids(ctx), samples))


class _PurePoints(dict):
    """pure_hull_points' map: a link's points are placed when first asked."""

    def __init__(self, solids_of: dict, samples: int):
        super().__init__()
        self.solids, self.samples = solids_of, samples
        self.placed_of: dict = {}       # a shape and origin's objects -> their placed points

    def __missing__(self, name: str):
        lists = []
        items = _hull_items(self.solids[name].link)
        for it in items or ():
            g, o = it.geometry, it.origin
            if g.kind == "mesh":
                items = None
                break
            key = (g.__class__, *map(id, g), id(o.xyz), id(o.rpy))
            pts = self.placed_of.get(key)
            if pts is None:
                pts = self.placed_of[key] = place(pose_T(o), G.surface_points(g, self.samples))
            lists.append(pts)
        if items:
            self[name] = lists[0] if len(lists) == 1 else [q for x in lists for q in x]
        else:
            self[name] = None
        return self[name]


def hull_points(ctx) -> dict:
    """link -> points bounding its geometry (link frame; see _hull_items), None when unknown, for every
    link of solids(ctx); the callers take extremes (extents, farthest distances), which every vertex
    gives as well as a hull would. Built once for the links with meshes that I007 and I010 measure
    (with --inertia), with one stacked product per shape size (the same bits as one product per shape)."""
    return ctx.fact("hull_points", lambda: _stack_hull_points(ctx), meshes=True)


_CX, _CY, _CZ = [0, 0, 0, 0, 1, 1, 1, 1], [0, 0, 1, 1, 0, 0, 1, 1], [0, 1, 0, 1, 0, 1, 0, 1]


def _stack_hull_points(ctx) -> dict:
    import numpy as np

    parts: dict[str, list | None] = {}
    by_size: dict = {}      # point count or "box" -> [(points in the shape frame or box size, origin, key)]
    placed_of: dict = {}    # key -> its placed points, one array for the links that repeat a primitive
    for name, s in solids(ctx).items():
        items = _hull_items(s.link)
        keys = []
        for it in items or ():
            g, o = it.geometry, it.origin
            if g.kind == "mesh":
                mesh = ctx.mesh(g) if ctx.opts.load_meshes else None
                if mesh is None or isinstance(mesh, str):
                    items = None
                    break
                key = (len(placed_of), )                # a mesh's shape is its own
                local = np.asarray(mesh.vertices)    # the rules use extremes only: no hull needed (nor scipy)
                size = len(local)
            else:
                # the same shape and origin objects (a macro's links: the loader shares their values)
                # give the same points: placed once (the objects stay alive with the links)
                key = (g.__class__, *map(id, g), id(o.xyz), id(o.rpy))
                if key in placed_of:
                    keys.append(key)
                    continue
                if g.kind == "box":     # corners made below, all at once
                    local, size = g.size, "box"
                else:
                    local = G.surface_points(g, 32)
                    size = len(local)
            placed_of[key] = None
            by_size.setdefault(size, []).append((local, o, key))
            keys.append(key)
        parts[name] = None if not items else keys
    for key, group in by_size.items():
        if key == "box":
            # surface_points' corners (x outer, z inner), each coordinate s / 2 or -(s / 2) as there
            h = np.array([t[0] for t in group], dtype=float) / 2
            both = np.stack((-h, h), axis=1)
            local = np.stack((both[:, _CX, 0], both[:, _CY, 1], both[:, _CZ, 2]), axis=2)
        else:
            local = np.array([t[0] for t in group], dtype=float)
        T = pose_stack(t[1] for t in group)
        placed = local @ np.swapaxes(T[:, :3, :3], 1, 2) + T[:, None, :3, 3]
        placed.flags.writeable = False      # rows shared by the links that repeat a shape
        for t, pts in zip(group, placed):
            placed_of[t[2]] = pts
    # one shape: its rows as they are (vstack would copy them, 20,000 times in a star)
    return {name: (None if k is None else placed_of[k[0]] if len(k) == 1 else np.vstack([placed_of[x] for x in k]))
            for name, k in parts.items()}


def _hull_items(link):
    """The shapes hull_points measures, or None: collision and visual shapes of a primitive-only
    link (cheap, lenient); when meshes are involved only the collision shapes (visual meshes are
    the slow ones to load), else the visuals."""
    cols = [c for c in link.collisions if c.geometry is not None]
    if not link.visuals:            # (most links of a big model): the collisions, meshes or not
        return cols or None
    vis = [v for v in link.visuals if v.geometry is not None]
    items = cols + vis
    if any(it.geometry.kind == "mesh" for it in items):
        items = cols or vis
    return items or None


@rule("I008", "density-plausible", "warning",
      bad=_part(_collision('<cylinder radius="0.135" length="0.015"/>') + "\n"
                + _inertial(0.05, 0.000229, 0.000229, 0.000456), "plate"),
      message="link plate: 0.05 kg in cylinder r 0.135 l 0.015 m (0.000859 m³) is a density of 58.2 kg/m³ "
              "(wood is 500–700, aluminium 2700)",
      good=_part(_collision('<cylinder radius="0.135" length="0.015"/>') + "\n"
                 + _inertial(0.52, 0.00238, 0.00238, 0.00474), "plate"))
def density(ctx):
    """The mass over the geometry's volume gives an implausible density (< 100 or > 23000 kg/m³).

    Real parts range from foam and hollow shells (a few hundred kg/m³) to steel
    (7850) and tungsten (19300). 50 g for a 0.27 m wooden disc (44 kg/m³) or 5 kg
    on a small sphere say the mass or the geometry is wrong. Fix: weigh the part, or
    use its material's density × volume.
    """
    for name, s in solids(ctx).items():
        if s.props is None or s.props.volume <= 0:
            continue
        m = s.link.inertial.mass
        rho = m / s.props.volume
        lo, hi = DENSITY_RANGE
        if rho < lo or rho > hi:
            yield Finding(f"link {name}: {m:g} kg in {s.desc} ({s.props.volume:.3g} m³) is a density of "
                          f"{rho:.3g} kg/m³ " + ("(wood is 500–700, aluminium 2700)" if rho < lo else "(denser than any metal)"),
                          s.link.inertial.loc or s.link.loc,
                          {"link": name, "mass": m, "volume": s.props.volume, "density": rho, "geometry": s.source},
                          severity=s.severity)


@rule("I010", "inertial-origin-inside", "warning",
      bad=_part(_collision(_BOX, "0.125 0 0") + "\n" + _inertial(1, 0.006042, 0.008333, 0.01271, "-0.2 0 0")),
      message="link chassis: inertial origin (-0.2 0 0) lies 0.175 m outside the box bounding its geometry "
              "(-0.025 -0.125 -0.05 .. 0.275 0.125 0.05); geometric centroid (0.125 0 0)",
      good=_part(_collision(_BOX, "0.125 0 0") + "\n" + _inertial(1, 0.006042, 0.008333, 0.01271, "0.125 0 0")))
def origin_inside(ctx):
    """The centre of mass (`<inertial><origin>`) must lie within the link's geometry.

    A body's centre of mass is always inside its convex hull. An origin far outside
    the visual/collision shapes usually means the inertial was copied from another
    link or written in the wrong frame. A link whose collision covers only part of it
    (a quadruped's hip: a cylinder off to one side, the motor only in the visual mesh)
    is measured with its visuals too before it is reported. Fix: the geometry's
    centroid (given), or the CAD's centre of mass.
    """
    every = solids(ctx)
    some, whole = pure_hull_points(ctx, 8), pure_hull_points(ctx)
    loaded = ctx.opts.load_meshes           # (and numpy with them)
    found: dict = {}                    # link -> (message, data) or None
    first: dict = {}                    # links that repeat their points and origin (shared objects): tested once
    meshes = set()                      # links whose measure reads a mesh: numpy's
    for name, s in every.items():
        pts = some[name]
        if pts is None or loaded and any(v.geometry is not None and v.geometry.kind == "mesh"
                                         for v in s.link.visuals):
            meshes.add(name)            # (a visual mesh widens the box of a link that falls outside)
            continue
        key = (id(pts), id(s.link.inertial.origin.xyz))
        if key not in first:
            # inside some points' box grown by their margin is inside the whole set's (a larger box,
            # a larger margin): those clear most links
            p = [float(v) for v in s.link.inertial.origin.xyz]
            first[key] = _beyond(pts, p) is not None and _beyond(whole[name], p) is not None
        if first[key]:
            found[name] = _pure_outside(s, whole[name])
    if meshes and loaded:
        found.update(_numpy_outside(ctx, meshes))
    for name, s in every.items():
        hit = found.get(name)
        if hit:
            yield Finding(f"link {name}: {hit[0]}", s.link.inertial.loc or s.link.loc, {"link": name, **hit[1]})


def _outside(lo, hi, p, out, centroid) -> tuple:
    """(the message after "link NAME: ", the data after the link's name) of origin_inside."""
    return (f"inertial origin ({' '.join(f'{v:.3g}' for v in p)}) lies {out:.3g} m outside "
            f"the box bounding its geometry ({' '.join(f'{v:.3g}' for v in lo)} .. "
            f"{' '.join(f'{v:.3g}' for v in hi)}); geometric centroid "
            f"({' '.join(f'{v:.3g}' for v in centroid)})",
            {"origin": list(p), "distance": out, "centroid": centroid})


def _numpy_outside(ctx, names) -> dict:
    """origin_inside's verdict on the links ``names`` (those with meshes, or None: all) with numpy:
    link -> _outside's pair for the links outside."""
    import numpy as np

    pts_of = hull_points(ctx)
    by_size: dict[int, list] = {}
    key_of = {}                         # links that repeat their points and origin (shared objects) tested once
    for name, s in solids(ctx).items():
        pts = pts_of[name]
        if pts is not None and (names is None or name in names):
            key = key_of[name] = (id(pts), id(s.link.inertial.origin.xyz))
            group = by_size.setdefault(len(pts), {})
            if key not in group:
                group[key] = name
    outside = set()
    for group in by_size.values():      # the test below, for all links at once (same arithmetic)
        names = list(group.values())
        pts = np.array([pts_of[n] for n in names], dtype=float)
        lo, hi = pts.min(1), pts.max(1)
        margin = (0.1 * (hi - lo).max(1) + 0.005)[:, None]
        p = np.array([ctx.robot.links[n].inertial.origin.xyz for n in names], dtype=float)
        gap = np.maximum(np.maximum(lo - margin - p, p - hi - margin), 0)
        outside.update(key for key, g in zip(group, gap.max(1).tolist()) if g > 0)
    found = {}
    for name, s in solids(ctx).items():
        if key_of.get(name) not in outside:
            continue
        pts = _with_visuals(ctx, s.link, pts_of[name])
        lo, hi = pts.min(0), pts.max(0)
        size = float((hi - lo).max())
        margin = 0.1 * size + 0.005
        p = np.array(s.link.inertial.origin.xyz)
        gap = np.maximum(np.maximum(lo - margin - p, p - hi - margin), 0)
        if gap.max() > 0:
            out = float(np.linalg.norm(np.maximum(np.maximum(lo - p, p - hi), 0)))
            centroid = list(s.props.com) if s.props is not None else ((lo + hi) / 2).tolist()
            found[name] = _outside(lo.tolist(), hi.tolist(), p.tolist(), out, centroid)
    return found


def _pure_outside(s, pts):
    """origin_inside's verdict on one link of primitives (``pts``: its pure_hull_points, whose box
    the origin already lies beyond) in pure Python, its visual shapes added as _with_visuals adds
    them: _outside's pair, or None."""
    link = s.link
    p = [float(v) for v in link.inertial.origin.xyz]
    extra = []
    for v in link.visuals:
        g = v.geometry
        if g is not None and g.kind != "mesh":      # (meshes not loaded: _with_visuals skips them too)
            extra.extend(place(pose_T(v.origin), G.surface_points(g, 32)))
    box = _beyond([*pts, *extra], p)
    if box is None:
        return None
    lo, hi = box
    d = [max(lo[k] - p[k], p[k] - hi[k], 0.0) for k in range(3)]
    centroid = list(s.props.com) if s.props is not None else [(lo[k] + hi[k]) / 2 for k in range(3)]
    return _outside(lo, hi, p, math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), centroid)


def _beyond(pts, p):
    """(lo, hi) of the points when ``p`` lies outside their box grown by origin_inside's margin, else None."""
    cols = list(zip(*pts))
    lo, hi = [min(c) for c in cols], [max(c) for c in cols]
    margin = 0.1 * max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) + 0.005
    if any(max(lo[k] - margin - p[k], p[k] - hi[k] - margin) > 0 for k in range(3)):
        return lo, hi
    return None


def _with_visuals(ctx, link, pts):
    """``pts`` (the shapes hull_points measured) and the link's visual shapes, for a link whose
    centre of mass fell outside the first: a partial collision (a quadruped's hip: a cylinder
    off to one side, the motor by the joint only in the visual mesh) bounds only part of the body.
    Visual meshes are read here only for such links (few), so I010 stays cheap."""
    import numpy as np

    extra = []
    for it in link.visuals:
        g = it.geometry
        if g is None:
            continue
        if g.kind == "mesh":
            mesh = ctx.mesh(g) if ctx.opts.load_meshes else None
            if mesh is None or isinstance(mesh, str):
                continue
            local = np.asarray(mesh.vertices, dtype=float)
        else:
            local = np.asarray(G.surface_points(g, 32), dtype=float)
        if not len(local):
            continue

        T = pose_matrix(it.origin)
        extra.append(local @ T[:3, :3].T + T[:3, 3])
    return np.vstack([pts, *extra]) if extra else pts


@rule("I011", "inertia-not-measurable", "info", needs="meshes", options=("inertia",),
      bad=_part(_collision('<mesh filename="meshes/shell.stl"/>') + "\n" + _inertial(0.1, 1e-05, 1e-05, 1e-05),
                "shell"),
      message="link shell: inertia not compared with geometry: mesh shell.stl is not watertight",
      good=_part(_collision('<mesh filename="meshes/closed.stl"/>') + "\n" + _inertial(0.1, 1e-05, 1e-05, 1e-05),
                 "shell"),
      files={"meshes/shell.stl": tetrahedron_stl(0.1, open_=True), "meshes/closed.stl": tetrahedron_stl(0.1)},
      note="meshes/shell.stl: a 0.1 m tetrahedron with one face missing; meshes/closed.stl: the whole one.")
def not_measurable(ctx):
    """The link's inertia could not be compared with its geometry (mesh not watertight or unreadable).

    A mesh with holes has no volume, so its solid-body inertia is undefined. Fix:
    a closed collision mesh (or primitive collision shapes); the inertia itself may be fine.
    """
    if not ctx.opts.load_meshes:
        return
    for name, s in solids(ctx).items():
        if s.props is None and s.why_not and s.why_not != "no geometry":
            yield Finding(f"link {name}: inertia not compared with geometry: {s.why_not}", s.link.loc,
                          {"link": name, "reason": s.why_not})
