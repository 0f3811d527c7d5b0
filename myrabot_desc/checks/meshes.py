"""M: mesh files (resolution always; contents only when meshes are loaded: --inertia or --meshes)."""

from __future__ import annotations

from myrabot_desc.checks.examples import tetrahedron_stl
from myrabot_desc.checks.rule import Finding, rule
from myrabot_desc.expand.packages import split_package_uri, unresolved_reason
from myrabot_desc.model.meshes import unreadable


def _shell(geometry: str, kind: str = "collision", name: str = "cover") -> str:
    """Example snippet: link `name` with one visual or collision, fixed to base_link."""
    return (f'<link name="{name}">\n  <{kind}><geometry>{geometry}</geometry></{kind}>\n</link>\n'
            f'<joint name="{name}_joint" type="fixed">\n  <parent link="base_link"/>\n  <child link="{name}"/>\n</joint>')




def _mesh_uses(ctx):
    """((link, 'visual'|'collision', item), ...) for every mesh geometry (one walk of the links for
    the M rules)."""
    def build():
        return tuple((link, kind, it) for link in ctx.robot.links.values()
                     for kind, items in (("collision", link.collisions), ("visual", link.visuals))
                     for it in items if it.geometry is not None and it.geometry.kind == "mesh")
    return ctx.fact("mesh_uses", build)


@rule("M001", "mesh-file-resolves", "error",
      bad=_shell('<mesh filename="package://missing_pkg/meshes/cover.stl"/>', "visual"),
      message="mesh package://missing_pkg/meshes/cover.stl (visual of cover) cannot be resolved: package "
              "'missing_pkg' is not found (give -p missing_pkg=PATH or --package-path)",
      good=_shell('<mesh filename="meshes/cover.stl"/>', "visual"),
      files={"meshes/cover.stl": tetrahedron_stl(0.1)}, note="meshes/cover.stl: a 0.1 m tetrahedron.")
def mesh_resolves(ctx):
    """Every mesh filename resolves to a file: `package://` to a known package, paths to existing files.

    An unresolved mesh is a missing body in every viewer and simulator (Pinocchio and
    MuJoCo refuse to load the geometry). Fix: pass the package with `-p NAME=PATH` or
    `--package-path`, correct the path, or ship the file (the message says which part failed).
    """

    r = ctx.robot
    reported = set()
    for link, kind, it in _mesh_uses(ctx):
        g = it.geometry
        if g.path is not None and g.path.is_file():
            continue
        if g.filename in reported:
            continue
        reported.add(g.filename)
        parts = split_package_uri(g.filename)
        if parts and parts[0] not in r.package_roots:
            why = f"package '{parts[0]}' is not found (give -p {parts[0]}=PATH or --package-path)"
        elif g.path is not None:
            why = f"no such file {g.path}"
        elif parts:
            why = f"no such file {r.package_roots[parts[0]] / parts[1]}"
        else:
            from pathlib import Path

            raw = g.filename[len("file://"):] if g.filename.startswith("file://") else g.filename
            p = Path(raw)
            if not p.is_absolute() and r.source is not None:
                p = r.source.parent / p
            # outside the roots: X006 from the model says so, the same words whether or not such a
            # file exists; M001 would only repeat it
            reason = unresolved_reason(g.filename, r.package_roots, r.source.parent if r.source else Path.cwd(),
                                       r.allow_roots)
            if reason == "outside the allowed folders":
                continue
            why = f"{p} is {reason}" if reason else f"no such file {p}"
        n = sum(1 for _l, _k, i in _mesh_uses(ctx) if i.geometry.filename == g.filename)
        yield Finding(f"mesh {g.filename} ({kind} of {link.name}{f', used {n}×' if n > 1 else ''}) cannot be "
                      f"resolved: {why}", it.loc or link.loc,
                      {"filename": g.filename, "link": link.name, "package": parts[0] if parts else None})


@rule("M005", "collision-mesh-readable", "error",
      bad=_shell('<mesh filename="meshes/cover.stl"/>'),
      message="collision mesh meshes/cover.stl of cover cannot be read: cover.stl: the STL header announces "
              "1651663207 triangles, over the 2000000 limit (MYRABOT_DESC_MAX_MESH_TRIANGLES)",
      good=_shell('<mesh filename="meshes/cover_ok.stl"/>'),
      files={"meshes/cover.stl": "garbage " * 23, "meshes/cover_ok.stl": tetrahedron_stl(0.1)},
      note="meshes/cover.stl: 184 bytes of text that are no mesh; meshes/cover_ok.stl: a 0.1 m tetrahedron.")
def collision_mesh_readable(ctx):
    """Every collision mesh that resolves is a mesh a reader can take (within the mesh limits).

    A collision mesh that is empty, truncated, not a mesh at all or over the limits gives the link
    no collision in any simulator (gz-sim and MuJoCo refuse or skip it), and `convert` refuses the
    model. Checked without loading the triangles (the header and structure of the file), so it
    runs on every check. Fix: re-export the mesh, or point at the right file.
    """
    seen: dict = {}
    for link, kind, it in _mesh_uses(ctx):
        g = it.geometry
        if kind != "collision" or g.path is None or not g.path.is_file():
            continue                    # M001 reports a mesh that does not resolve
        if g.path not in seen:
            seen[g.path] = unreadable(g.path)
            why = seen[g.path]
            if why:
                yield Finding(f"collision mesh {g.filename} of {link.name} cannot be read: {why}", it.loc or link.loc,
                              {"filename": g.filename, "link": link.name})


def _loaded(ctx, g, kind="collision"):
    """The loaded mesh, or None. --inertia loads collision meshes; --meshes loads visual ones too
    (visual meshes are the large, slow ones)."""
    if kind == "visual" and not ctx.opts.meshes:
        return None
    if not ctx.opts.load_meshes or g.path is None or not g.path.is_file():
        return None
    m = ctx.mesh(g)
    return None if m is None or isinstance(m, str) else m


@rule("M002", "mesh-scale", "warning", needs="meshes", options=("meshes",),
      bad=_shell('<mesh filename="meshes/arm.stl"/>', "visual", "arm"),
      message="mesh meshes/arm.stl (visual of arm) is 350 m across after scale 1 1 1: millimetres exported as metres?",
      good=_shell('<mesh filename="meshes/arm.stl" scale="0.001 0.001 0.001"/>', "visual", "arm"),
      files={"meshes/arm.stl": tetrahedron_stl(350)}, note="meshes/arm.stl: a tetrahedron 350 units across (mm).")
def mesh_scale(ctx):
    """After scale, a mesh's bounding box should lie between 1 mm and 10 m.

    CAD exports in millimetres without `scale="0.001 0.001 0.001"` give a robot a
    thousand times too large (and the inverse). Fix: the right `scale`, or re-export
    in metres.
    """
    seen = set()
    for link, kind, it in _mesh_uses(ctx):
        g = it.geometry
        m = _loaded(ctx, g, kind)
        key = (g.filename, tuple(g.scale))
        if m is None or key in seen:
            continue
        seen.add(key)
        ext = float(max(m.extents))
        if ext > 10 or ext < 0.001:
            guess = 0.001 if ext > 10 else 1000
            yield Finding(f"mesh {g.filename} ({kind} of {link.name}) is {ext:.3g} m across after scale "
                          f"{' '.join(f'{s:g}' for s in g.scale)}: " + ("millimetres exported as metres?" if ext > 10
                                                                       else "metres scaled as millimetres?"),
                          it.loc or link.loc, {"filename": g.filename, "extent": ext, "suggested_scale": guess})


@rule("M003", "mesh-watertight", "info", needs="meshes", options=("inertia",),
      bad=_shell('<mesh filename="meshes/cover.stl"/>'),
      message="collision mesh meshes/cover.stl of cover is not watertight (3 faces): its volume and inertia "
              "are undefined",
      good=_shell('<mesh filename="meshes/closed.stl"/>'),
      files={"meshes/cover.stl": tetrahedron_stl(0.1, open_=True), "meshes/closed.stl": tetrahedron_stl(0.1)},
      note="meshes/cover.stl: a 0.1 m tetrahedron with one face missing; meshes/closed.stl: the whole one.")
def mesh_watertight(ctx):
    """A collision mesh should be watertight (closed) to have a volume.

    Engines handle open collision meshes (often via the convex hull), but their volume,
    mass properties and inside/outside tests are undefined, so inertia cannot be checked
    against them. Fix: close the mesh (MeshLab: "Close holes") or use primitives.
    """
    seen = set()
    for link, kind, it in _mesh_uses(ctx):
        g = it.geometry
        if kind != "collision" or g.filename in seen:
            continue
        m = _loaded(ctx, g)
        if m is None:
            continue
        seen.add(g.filename)
        if not m.is_watertight:
            yield Finding(f"collision mesh {g.filename} of {link.name} is not watertight "
                          f"({m.n_faces} faces): its volume and inertia are undefined", it.loc or link.loc,
                          {"filename": g.filename, "link": link.name})


@rule("M004", "mesh-normals-outward", "warning", needs="meshes", options=("inertia",),
      bad=_shell('<mesh filename="meshes/inside_out.stl"/>'),
      message="mesh meshes/inside_out.stl (collision of cover) is inside out: volume -0.000167 m³",
      good=_shell('<mesh filename="meshes/closed.stl"/>'),
      files={"meshes/inside_out.stl": tetrahedron_stl(0.1, flipped=True), "meshes/closed.stl": tetrahedron_stl(0.1)},
      note="meshes/inside_out.stl: a 0.1 m tetrahedron wound inward; meshes/closed.stl: wound outward.")
def mesh_normals(ctx):
    """A closed mesh's faces should wind outward (positive volume).

    Inverted winding gives a negative volume and a negative mass in trimesh, renders
    inside out with back-face culling, and flips contact normals in some engines.
    Fix: flip the faces (MeshLab "Invert faces orientation", trimesh `mesh.invert()`).
    """
    seen = set()
    for link, kind, it in _mesh_uses(ctx):
        g = it.geometry
        if g.filename in seen:
            continue
        m = _loaded(ctx, g, kind)
        if m is None:
            continue
        seen.add(g.filename)
        if m.is_watertight and m.volume < 0:
            yield Finding(f"mesh {g.filename} ({kind} of {link.name}) is inside out: volume {m.volume:.3g} m³",
                          it.loc or link.loc, {"filename": g.filename, "volume": float(m.volume)})
