"""I: masses and inertia tensors on their own (no geometry needed)."""

from __future__ import annotations

from collections import defaultdict

from myrabot_desc.checks.inertia_geometry import Solid, inertia_line, solids, tensor_fix
from myrabot_desc.checks.rule import Finding, Fix, FixInfo, InsertInto, SetValue, rule
from myrabot_desc.model import drive as D
from myrabot_desc.model.inertia import principal_moments
from myrabot_desc.model.tree import maps

TRIANGLE_TOL = 1e-3      # relative: a + b >= c (1 - tol); URDF files round to ~6 digits
ZERO_MOMENT = 1e-12      # kg·m²: below this a moment is rounding noise (1 g at 0.03 mm); MuJoCo's mjMINVAL is 1e-15
NOISE = 1e-9             # relative to the largest moment: eigenvalues this small are round-off of 0


def _inertial(body: str, name: str = "finger", jtype: str = "revolute") -> str:
    """Example snippet: link `name` with `body` inside, on a joint to base_link."""
    inner = "\n".join("  " + line for line in body.splitlines())
    more = ('\n  <axis xyz="0 1 0"/>\n  <limit lower="-1" upper="1" effort="2" velocity="3"/>'
            if jtype == "revolute" else "")
    return (f'<link name="{name}">\n{inner}\n</link>\n<joint name="{name}_joint" type="{jtype}">\n'
            f'  <parent link="base_link"/>\n  <child link="{name}"/>{more}\n</joint>')


def _inertia(mass, ixx, iyy, izz, ixy=0, ixz=0, iyz=0) -> str:
    return (f'<inertial>\n  <mass value="{mass}"/>\n  <inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" '
            f'iyy="{iyy}" iyz="{iyz}" izz="{izz}"/>\n</inertial>')


_FINGER_BOX = '<collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>'


def _has_geometry(ctx, head: str) -> list[str]:
    r = ctx.robot
    return [n for n, h in ctx.body_of.items() if h == head and (r.links[n].visuals or r.links[n].collisions)]


@rule("I001", "moving-link-mass", "error",
      bad=_inertial(_FINGER_BOX),
      message="link finger moves (joint finger_joint, revolute) and has geometry but no mass",
      good=_inertial(_FINGER_BOX + "\n" + _inertia(0.02, 6.667e-06, 6.667e-06, 1.333e-06)),
      fix=FixInfo("sometimes", "unsafe", "when the link's geometry can be measured (primitives; meshes with "
                  "--inertia), it gets a mass and the solid-body inertia at that mass, centred on the geometry: "
                  "an `<inertial>` is added, or the massless one filled in. The mass is an estimate: the geometry's "
                  "volume times the median density of the robot's other links whose mass and geometry are known "
                  "(1000 kg/m³, about that of plastic parts, when there are none). Unsafe: the real mass is the "
                  "maker's to give."))
def moving_link_mass(ctx):
    """A link that moves (its parent joint is not fixed) and has geometry needs a positive mass.

    Gazebo's URDF→SDF conversion drops a massless moving link together with everything
    attached below it; MuJoCo refuses it (mjMINVAL); Pinocchio's dynamics turn NaN when
    nothing below the joint has mass. Fix: an `<inertial>` with the part's real mass and
    inertia (`check --inertia --suggest` computes the tensor from the geometry). A virtual
    joint's link (other joints mimic the joint, its link has a visual and no collision: a
    bicycle model's steering and traction joints, model/drive.virtual_joints) is no physical
    body and is reported as a warning, with what Gazebo does to it.
    """
    r = ctx.robot
    virtual = D.virtual_joints(r)
    parent_joint = maps(r).parent_joint.get         # r.parent_joint without its lookup of the maps per link
    for head, m in ctx.body_mass.items():
        pj = parent_joint(head)
        if pj is None or pj.type == "fixed" or m > 0:
            continue
        geo = _has_geometry(ctx, head)
        if geo and pj.name in virtual and not any(r.links[n].collisions for n in geo):
            # a kinematic model's joint drawn for show: no body to weigh, but Gazebo still drops it
            yield Finding(f"link {head} moves (joint {pj.name}, {pj.type}) and has a visual but no mass: a virtual "
                          f"joint ({', '.join(virtual[pj.name])} mimic it), not a physical body, but Gazebo's "
                          "URDF→SDF conversion drops a massless moving link with its joint", r.links[head].loc,
                          {"link": head, "joint": pj.name, "virtual": True, "mimicked_by": list(virtual[pj.name])},
                          severity="warning")
            continue
        if geo:
            yield Finding(f"link {head} moves (joint {pj.name}, {pj.type}) and has geometry but no mass"
                          + (f" (nor do the links fixed to it: {', '.join(g for g in geo if g != head)})"
                             if len(geo) > 1 or geo[0] != head else ""),
                          r.links[head].loc, {"link": head, "joint": pj.name}, fix=mass_fix(ctx, r.links[head]))


@rule("I002", "massless-moving-frame", "warning",
      bad=_inertial("<!-- no inertial, no geometry -->", "wrist_virtual") + "\n"
          + _inertial(_FINGER_BOX + "\n" + _inertia(0.02, 6.667e-06, 6.667e-06, 1.333e-06), "hand")
          .replace('"base_link"', '"wrist_virtual"'),
      message="link wrist_virtual (joint wrist_virtual_joint, revolute) has no mass and no geometry; converting "
              "to SDF drops it with its children (hand)",
      good=_inertial(_inertia(0.001, 1e-06, 1e-06, 1e-06), "wrist_virtual") + "\n"
           + _inertial(_FINGER_BOX + "\n" + _inertia(0.02, 6.667e-06, 6.667e-06, 1.333e-06), "hand")
           .replace('"base_link"', '"wrist_virtual"'))
def massless_moving_frame(ctx):
    """A massless link without geometry on a moving joint: SDF conversion drops it and its subtree.

    Pinocchio accepts it as long as links further down carry mass, but Gazebo's
    URDF→SDF converter removes a massless link whose parent joint is not fixed, with
    every link below it (sdformat #199), and MuJoCo refuses it. Fix: give it a small
    mass and inertia (for instance 1 g and 1e-6 kg·m²), or merge it into its child.
    """
    r = ctx.robot
    parent_joint = maps(r).parent_joint.get
    for head, m in ctx.body_mass.items():
        pj = parent_joint(head)
        if pj is None or pj.type == "fixed" or m > 0 or _has_geometry(ctx, head):
            continue
        below = [j.child for j in r.child_joints(head)]
        yield Finding(f"link {head} (joint {pj.name}, {pj.type}) has no mass and no geometry"
                      + (f"; converting to SDF drops it with its children ({', '.join(below[:4])})" if below else ""),
                      r.links[head].loc, {"link": head, "joint": pj.name, "children": below})


@rule("I003", "mass-positive", "error",
      bad=_inertial(_inertia(-1, 0.001, 0.001, 0.001), "arm", "fixed"),
      message="link arm has mass -1 kg",
      good=_inertial(_inertia(1, 0.001, 0.001, 0.001), "arm", "fixed"))
def mass_positive(ctx):
    """A declared mass must not be negative (and an inertial with mass 0 but a tensor is contradictory).

    Negative mass passes Pinocchio silently and breaks every simulator. Fix: the real mass.
    """
    for link in ctx.robot.links.values():
        i = link.inertial
        if i is None:
            continue
        if i.mass < 0:
            yield Finding(f"link {link.name} has mass {i.mass:g} kg", i.loc or link.loc, {"link": link.name, "mass": i.mass})
        elif i.mass == 0 and any((i.ixx, i.iyy, i.izz)):
            yield Finding(f"link {link.name} has mass 0 but inertia {i.ixx:g}/{i.iyy:g}/{i.izz:g}",
                          i.loc or link.loc, {"link": link.name}, severity="warning")


@rule("I004", "inertia-positive-definite", "error",
      bad=_inertial(_inertia(0.001, 9e-08, 3.5e-08, 1e-08, ixz=6.3e-08), "antenna", "fixed"),
      message="link antenna: inertia not positive definite, principal moments -2.463e-08/3.5e-08/1.246e-07",
      good=_inertial(_inertia(0.001, 9e-08, 9e-08, 1e-08), "antenna", "fixed"),
      fix=FixInfo("sometimes", "unsafe", "when the link's geometry can be measured, the tensor becomes the solid "
                  "body's at the declared mass (as I006). Unsafe: it assumes a uniform density."))
def positive_definite(ctx):
    """An inertia tensor must be positive definite (all principal moments > 0).

    A negative principal moment is physically impossible: sdformat reports "invalid
    inertia", MuJoCo refuses it, Pinocchio accepts it silently and integrates nonsense.
    A zero moment (point mass) is a warning: MuJoCo refuses moving bodies with
    inertia below mjMINVAL. Fix: the solid-body values (`--inertia --suggest`).
    """
    moments = principal(ctx)
    kinds: dict = {}            # id(moments) -> "negative", "zero" or None: links share their moments (principal)
    for link in ctx.robot.links.values():
        i = link.inertial
        if i is None or i.mass <= 0:
            continue
        ev = moments[link.name]
        kind = kinds.get(id(ev), False)
        if kind is False:
            kind = kinds[id(ev)] = _definiteness(i, ev)
        if kind == "negative":
            yield Finding(f"link {link.name}: inertia not positive definite, principal moments "
                          + "/".join(f"{e:.4g}" for e in ev), i.loc or link.loc,
                          {"link": link.name, "principal": list(ev)}, fix=geometry_fix(ctx, link))
        elif kind == "zero":
            if ctx.moving(link.name):         # (0, 0, c) is no rod: I005 reports it
                yield Finding(f"link {link.name} ({i.mass:g} kg) has a zero principal moment of inertia "
                              f"({'/'.join(f'{e:.3g}' for e in ev)}): a point mass or a rod", i.loc or link.loc,
                              {"link": link.name, "principal": list(ev)}, severity="warning")


def _definiteness(i, ev) -> str | None:
    """"negative" for principal moments ``ev`` (of inertial ``i``, mass > 0) with a clearly negative
    one, "zero" for a zero one that is no triangle violation (I005's), else None."""
    scale = max(max(abs(e) for e in ev), 1e-300)
    if min(ev) < -1e-9 * scale and -min(ev) > ZERO_MOMENT:
        return "negative"
    if min(ev) <= max(1e-12 * scale, ZERO_MOMENT) and triangle_gap(i, ev) is None:
        return "zero"
    return None


@rule("I005", "inertia-triangle", "error",
      bad=_inertial(_inertia(0.05, 0.002, 0, 0)),
      message="link finger: impossible inertia, principal moments 0 + 0 = 0 < 0.002 (triangle inequality)",
      good=_inertial(_inertia(0.05, 0.002, 0.002, 0.0001)),
      fix=FixInfo("sometimes", "unsafe", "when the link's geometry can be measured, the tensor becomes the solid "
                  "body's at the declared mass (as I006); otherwise, for a diagonal tensor, the two smaller "
                  "moments are raised to half the largest (a flat plate's proportions, the least change that "
                  "satisfies A + B ≥ C). Unsafe: both are estimates."))
def triangle(ctx):
    """The principal moments must satisfy the triangle inequality: A + B ≥ C.

    For any real body the sum of two principal moments is at least the third; a tensor
    that violates it cannot exist (sdformat "invalid inertia", MuJoCo "A + B >= C",
    unstable ODE contacts in Gazebo). Moments within round-off of zero count as 0: a
    finger with ixx 0.002 and iyy = izz = 0 (0 + 0 < 0.002), or six equal entries
    (principal moments 0, 0, 3·ixx), are impossible too, not point masses or rods. Fix:
    the solid-body values for the link's shape (`check --inertia --suggest`).
    """
    moments = principal(ctx)
    gaps: dict = {}             # id(moments) -> their gap: links share their moments (principal)
    for link in ctx.robot.links.values():
        i = link.inertial
        if i is None or i.mass <= 0:
            continue
        ev = moments[link.name]
        gap = gaps.get(id(ev), False)
        if gap is False:
            gap = gaps[id(ev)] = triangle_gap(i, ev)
        if gap is not None:
            a, b, c = gap
            yield Finding(f"link {link.name}: impossible inertia, principal moments {a:.4g} + {b:.4g} = {a + b:.4g} "
                          f"< {c:.4g} (triangle inequality)", i.loc or link.loc,
                          {"link": link.name, "principal": [a, b, c], "declared": _decl(i)},
                          fix=geometry_fix(ctx, link) or _rebalanced(i))


DEFAULT_DENSITY = 1000.0   # kg/m³: plastic parts, when the robot gives no density of its own


def geometry_fix(ctx, link) -> Fix | None:
    """The solid body's tensor at the declared mass, when the link's geometry can be measured."""
    s = solids(ctx).get(link.name)
    if s is None or s.props is None:
        return None
    _com, t = s.framed()        # (within ulps of in_inertial_frame's: the fix writes 4 digits)
    flat = [abs(v) for row in t for v in row]
    lim = 1e-6 * max(flat)              # rotation round-off is not a product of inertia (in_inertial_frame)
    t = [[0.0 if abs(v) < lim else v for v in row] for row in t]
    return tensor_fix(link.inertial, t, f"inertia of {link.name} from its {s.source} geometry")


def _rebalanced(i) -> Fix | None:
    """A diagonal tensor breaking A + B >= C: the two smaller moments raised to half the largest."""
    if i.ixy or i.ixz or i.iyz:
        return None
    vals = {"ixx": i.ixx, "iyy": i.iyy, "izz": i.izz}
    big = max(vals, key=vals.get)
    half = float(f"{vals[big] / 2:.4g}")
    edits = tuple(SetValue(i, k, half) for k, v in vals.items() if k != big and v < half)
    return Fix(edits, "unsafe", f"the two smaller moments raised to {half:g}") if edits else None


def robot_density(ctx) -> float:
    """The median density of the links whose mass and geometry are both known."""
    d = sorted(s.link.inertial.mass / s.props.volume for s in solids(ctx).values()
               if s.props is not None and s.props.volume > 0 and not s.marker)
    return d[len(d) // 2] if d else DEFAULT_DENSITY


def mass_fix(ctx, link) -> Fix | None:
    """I001's fix: an estimated mass (see the rule) and its solid-body inertia."""
    s = Solid(ctx, link)
    if s.props is None or s.props.volume <= 0:
        return None
    density = robot_density(ctx)
    mass = float(f"{density * s.props.volume:.3g}")
    t = [[v * mass for v in row] for row in s.props.inertia]     # props are per kg (Solid measures at 1 kg)
    title = f"mass {mass:g} kg ({density:.0f} kg/m³ × {s.props.volume:.3g} m³) and its inertia"
    i = link.inertial
    if i is None:
        com = " ".join(f"{float(f'{c:.4g}') + 0.0:g}" for c in s.props.com)
        line = inertia_line(t)
        return Fix((InsertInto(link, f'<inertial>\n  <origin xyz="{com}" rpy="0 0 0"/>\n  <mass value="{mass:g}"/>\n'
                                     f'  {line}\n</inertial>'),), "unsafe", title)
    if any(i.origin.rpy):
        return None
    return Fix((SetValue(i, "mass", mass),) + tensor_fix(i, t, title).edits, "unsafe", title)


@rule("I009", "placeholder-inertia", "warning",
      bad=_inertial(_inertia(0.001, 0.01, 0.01, 0.01), "screen", "fixed") + "\n"
          + _inertial(_inertia(0.1, 0.01, 0.01, 0.01), "plate", "fixed"),
      message="the same inertia 0.01/0.01/0.01 is used by 3 links with masses 0.001–1 kg (1000×): a placeholder "
              "(base_link, screen, plate)",
      good=_inertial(_inertia(0.001, 1e-07, 1e-07, 2e-07), "screen", "fixed") + "\n"
           + _inertial(_inertia(0.1, 0.0005, 0.0005, 0.001), "plate", "fixed"))
def placeholder(ctx):
    """One inertia tensor reused for links of very different mass: a placeholder.

    Inertia scales with mass × size²; the same numbers on a 0.1 g screen and a 100 g
    plate cannot both be right (usually a `default_inertia` macro). Fix: compute each
    link's tensor from its geometry (`check --inertia --suggest`).
    """
    groups = defaultdict(list)
    rounded: dict = {}          # tensor -> its key: a model repeats its tensors (that is what this rule finds)
    for link in ctx.robot.links.values():
        i = link.inertial
        if i is None or i.mass <= 0 or not any((i.ixx, i.iyy, i.izz)):
            continue
        raw = (i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz)
        key = rounded.get(raw)
        if key is None:
            key = rounded[raw] = tuple(float(f"{v:.6g}") for v in raw)
        groups[key].append(link)
    for key, links in groups.items():
        masses = [l.mass for l in links]
        if len(links) >= 3 and max(masses) >= 10 * min(masses):
            ixx, _, _, iyy, _, izz = key
            names = [l.name for l in links]
            yield Finding(f"the same inertia {ixx:g}/{iyy:g}/{izz:g} is used by {len(links)} links with masses "
                          f"{min(masses):g}–{max(masses):g} kg ({max(masses) / min(masses):.0f}×): a placeholder "
                          f"({', '.join(names[:5])}{', ...' if len(names) > 5 else ''})",
                          links[0].inertial.loc or links[0].loc,
                          {"tensor": {"ixx": ixx, "iyy": iyy, "izz": izz}, "links": names,
                           "mass_min": min(masses), "mass_max": max(masses)})


def principal(ctx) -> dict:
    """link -> principal moments (ascending) of every link with a positive mass, computed once for
    I004, I005 and P003."""
    def build():
        # links repeat their tensors (a macro's copies), which the loader reads into the same value
        # objects: one eigenproblem per distinct six, the moments shared (read them, never change them)
        same: dict = {}
        out = {}
        for link in ctx.robot.links.values():
            i = link.inertial
            if i is not None and i.mass > 0:
                key = (id(i.ixx), id(i.ixy), id(i.ixz), id(i.iyy), id(i.iyz), id(i.izz))
                m = same.get(key)
                if m is None:
                    m = same[key] = (principal_moments(i), i)    # (the inertial keeps the key's objects alive)
                out[link.name] = m[0]
        return out
    return ctx.fact("principal", build)


def triangle_gap(i, moments=None):
    """The principal moments (a, b, c), ascending, when they break A + B ≥ C; else None
    (``moments``: principal_moments(i), when the caller has them).

    Moments within round-off of zero count as 0, so ixx = 0.002 with iyy = izz = 0 (0 + 0 < 0.002)
    and a tensor whose six entries are equal (principal moments 0, 0, 3·ixx) are violations, as
    convert treats them. A point mass (every moment ~0) and a clearly negative moment (I004's
    error) are not reported here.
    """
    if i is None or i.mass <= 0:
        return None
    a, b, c = sorted(float(e) for e in (principal_moments(i) if moments is None else moments))
    if c <= ZERO_MOMENT:
        return None
    noise = NOISE * c
    if a < -noise and -a > ZERO_MOMENT:
        return None
    a, b = (0.0 if abs(x) <= noise else x for x in (a, b))
    return (a, b, c) if a + b < c * (1 - TRIANGLE_TOL) else None


def _decl(i) -> dict:
    return {k: getattr(i, k) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
