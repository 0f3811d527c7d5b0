"""What the viewer adds to a viser scene: the parts, frames, centres of mass, inertia boxes, the
ground with the support polygon, the drive wheels; and which links a finding is about.

Each node goes into a toggle group (``Viewer._nodes[group]``); link-attached nodes sit under the
link's node ``/robot/<link>`` so that moving a link moves them. Numbers come from the model's
facts: kinematics, ``view.facts`` (inertia boxes, support), ``sim.diffdrive`` (both wheel sets).
"""

from __future__ import annotations

import math
import re

from myrabot_desc.errors import InputError
from myrabot_desc.model.kinematics import center_of_mass
from myrabot_desc.sim.diffdrive import find_drive
from myrabot_desc.view.facts import inertia_box, support

WHEEL_URDF_RGB = (20, 170, 60)
WHEEL_PLUGIN_RGB = (230, 0, 160)


def node_name(link: str) -> str:
    """A viser scene path segment for a link name (slashes would nest)."""
    return link.replace("/", "_") or "_"


def _rgb(rgba) -> tuple[int, int, int]:
    return tuple(int(round(max(0.0, min(1.0, c)) * 255)) for c in rgba[:3])


def _wxyz(R):
    import viser.transforms as vtf

    return tuple(float(c) for c in vtf.SO3.from_matrix(R).wxyz)


def size_of(viewer) -> float:
    """The robot's diagonal (m): scales axes, spheres and labels."""
    import numpy as np

    v = viewer.scene.world_vertices()
    return float(np.linalg.norm(np.ptp(v, axis=0))) if len(v) else 1.0


def add_links(viewer, sc) -> None:
    """A frame node per link (placed by ``_place``); every part and overlay of the link sits under it."""
    T = viewer.scene.transforms(viewer.q)
    viewer._diag = size_of(viewer)
    for link in viewer.robot.links:
        if link in T:
            viewer._link_nodes[link] = sc.add_frame(f"/robot/{node_name(link)}", show_axes=False)


def add_parts(viewer, sc, parts) -> None:
    for p in parts:
        if p.link not in viewer._link_nodes:
            continue
        rgb = _rgb(p.rgba)
        alpha = float(p.rgba[3]) if len(p.rgba) > 3 else 1.0
        h = sc.add_mesh_simple(f"/robot/{node_name(p.link)}/{p.layer}{p.index}", p.vertices, p.faces, color=rgb,
                               opacity=alpha if alpha < 0.999 else None, flat_shading=p.kind in ("box", "mesh"),
                               position=tuple(p.local[:3, 3]), wxyz=_wxyz(p.local[:3, :3]),
                               side="double" if p.layer == "collision" else "front", cast_shadow=False,
                               receive_shadow=False)
        viewer._nodes[p.layer].append(h)
        if p.layer == "visual":
            viewer._visuals.setdefault(p.link, []).append((h, rgb))


def add_group(viewer, sc, group: str) -> None:
    """The nodes of one overlay toggle group (built when it is first switched on)."""
    diag = viewer._diag
    nodes = viewer._nodes[group]
    if group in ("frames", "names", "com", "inertia"):
        for link in viewer._link_nodes:
            base = f"/robot/{node_name(link)}"
            L = 0.05 * diag
            if group == "frames":
                nodes.append(sc.add_frame(f"{base}/axes", axes_length=L, axes_radius=L / 25, origin_radius=L / 12))
                continue
            if group == "names":            # a label's text is plain text in the page
                nodes.append(sc.add_label(f"{base}/name", link, font_screen_scale=0.7))
                continue
            box = inertia_box(viewer.robot.links[link].inertial)
            if box is None:
                continue
            if group == "com":
                nodes.append(sc.add_icosphere(f"{base}/com", radius=0.006 * diag, color=(20, 20, 20), subdivisions=1,
                                              position=tuple(box.pose[:3, 3])))
            else:
                nodes.append(sc.add_box(f"{base}/inertia", color=(40, 90, 255) if box.valid else (255, 30, 30),
                                        dimensions=tuple(max(s, 1e-5) for s in box.size), opacity=0.45,
                                        position=tuple(box.pose[:3, 3]), wxyz=_wxyz(box.pose[:3, :3])))
        if group == "com":
            viewer._robot_com = sc.add_icosphere("/overlays/com", radius=0.015 * diag, color=(255, 0, 200),
                                                 subdivisions=2)
            nodes.append(viewer._robot_com)
            viewer._com_label = sc.add_label("/overlays/com/label", "centre of mass", font_screen_scale=0.8,
                                             anchor="bottom-right")
            nodes.append(viewer._com_label)
    elif group == "support":
        viewer._support_nodes = {}
        nodes.append(sc.add_grid("/overlays/ground", width=max(2 * diag, 1.0), height=max(2 * diag, 1.0),
                                 cell_size=0.05, section_size=0.25, plane_opacity=0.15))
    elif group == "wheels":
        _add_wheels(viewer, sc)


def drive_of(robot):
    """(the drive as the URDF and its plugin see it, or None; the numbers as text)."""
    try:
        drive = find_drive(robot, wheels="urdf")
    except (InputError, KeyError, ValueError):
        return None, None
    u = drive.urdf
    text = f"URDF: radius {u.radius:.4g} m, separation {u.separation:.4g} m"
    p = drive.plugin
    if p is not None:
        text += f"\nplugin {p.name}: radius {p.radius:.4g} m, separation {p.separation:.4g} m"
    return drive, text


def _circle(centre, axis, radius, n=48):
    """(n, 2, 3) segments of a circle about ``axis``."""
    import numpy as np

    a = np.asarray(axis, dtype=float)
    a = a / (np.linalg.norm(a) or 1.0)
    u = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(a, u)
    t = np.linspace(0, 2 * math.pi, n + 1)
    pts = np.asarray(centre, dtype=float) + radius * (np.outer(np.cos(t), u) + np.outer(np.sin(t), v))
    return np.stack([pts[:-1], pts[1:]], axis=1)


def _add_wheels(viewer, sc) -> None:
    """The URDF's wheels (green, on the wheel links) and the plugin's belief (magenta, root frame);
    their numbers go to the panel (``Session.overlay_text``), a short label stays by the wheels."""
    import numpy as np

    drive = viewer.drive
    if drive is None:
        return
    u = drive.urdf
    T0 = viewer.scene.transforms({})
    thick = 0.004 * viewer._diag
    for w in (u.left, u.right):
        j = viewer.robot.joints[w.joint]
        seg = _circle((0, 0, 0), j.axis, w.radius)
        viewer._nodes["wheels"].append(sc.add_line_segments(f"/robot/{node_name(w.link)}/wheel_urdf", seg,
                                                            WHEEL_URDF_RGB, thickness=thick))
    p = drive.plugin
    label = "wheels: URDF (green)"
    if p is not None:
        lw, rw = np.array(T0[u.left.link][:3, 3]), np.array(T0[u.right.link][:3, 3])
        lateral = lw - rw
        lateral[2] = 0.0
        lateral /= np.linalg.norm(lateral) or 1.0
        mid = (lw + rw) / 2
        for side in (1, -1):
            c = mid + side * lateral * p.separation / 2
            viewer._nodes["wheels"].append(sc.add_line_segments(f"/overlays/wheel_plugin_{side}",
                                                                _circle(c, lateral, p.radius), WHEEL_PLUGIN_RGB,
                                                                thickness=thick))
        label += ", plugin (magenta)"
    top = max(T0[u.left.link][2, 3], T0[u.right.link][2, 3]) + 2 * u.radius
    viewer._nodes["wheels"].append(sc.add_label("/overlays/wheel_label", label, font_screen_scale=0.8,
                                                anchor="top-right",
                                                position=tuple(float(c) for c in T0[u.left.link][:2, 3]) + (float(top),)))


def update_dynamic(viewer, T) -> None:
    """What moves with the joints besides the links: the robot's centre of mass and the support."""
    import numpy as np

    mass, com = center_of_mass(viewer.robot, viewer.q)
    viewer.com = (mass, com)
    if mass > 0 and getattr(viewer, "_robot_com", None) is not None and "com" in viewer._built:
        viewer._robot_com.position = tuple(float(c) for c in com)
    if not viewer.toggles.get("support") or "support" not in viewer._built:
        for h in getattr(viewer, "_support_nodes", {}).values():
            h.remove()
        viewer._support_nodes = {}
        viewer.support = None
        _panel(viewer)
        return

    s = support(viewer.robot, viewer.q)
    viewer.support = s
    sc = viewer.server.scene
    if s is None:
        _panel(viewer)
        return
    z = s.ground_z + 0.0005
    ground = viewer._nodes["support"][0]
    ground.position = (float(s.com[0]), float(s.com[1]), float(s.ground_z))
    thick = 0.004 * viewer._diag
    poly = np.array([[x, y, z] for x, y in s.polygon]) if s.polygon else np.zeros((0, 3))
    inside = s.margin > 0
    nodes = viewer._support_nodes
    if len(poly) >= 2:
        seg = np.stack([poly, np.roll(poly, -1, axis=0)], axis=1)
        nodes["polygon"] = sc.add_line_segments("/overlays/support/polygon", seg, (0, 150, 255), thickness=thick)
    pts = np.vstack(list(s.contacts.values())) if s.contacts else np.zeros((0, 3))
    if len(pts):
        nodes["contacts"] = sc.add_point_cloud("/overlays/support/contacts", pts.astype(np.float32),
                                               colors=(0, 90, 200), point_size=0.012 * viewer._diag)
    proj = (float(s.com[0]), float(s.com[1]), z)
    nodes["com"] = sc.add_icosphere("/overlays/support/com_ground", radius=0.01 * viewer._diag,
                                    color=(0, 190, 0) if inside else (255, 0, 0), position=proj)
    drop = np.array([[s.com, proj]], dtype=float)
    nodes["drop"] = sc.add_line_segments("/overlays/support/drop", drop, (120, 120, 120), thickness=thick / 2)
    # short, anchored at its right end so it grows away from the panel (right); the numbers are in the panel
    nodes["label"] = sc.add_label("/overlays/support/label", f"COM {'inside' if inside else 'OUTSIDE'}",
                                  position=proj, font_screen_scale=0.8, anchor="top-right")
    _panel(viewer)


def _panel(viewer) -> None:
    if hasattr(viewer, "overlay_text"):
        viewer.overlay_text()


def finding_links(robot, d) -> list[str]:
    """The links a diagnostic is about: its data (link, joint, sensor, plugin), else link names in its text."""
    found: list[str] = []

    def add(name):
        if isinstance(name, str) and name in robot.links and name not in found:
            found.append(name)

    data = d.data or {}
    for key in ("link", "links", "child", "parent", "body"):
        v = data.get(key)
        for n in (v if isinstance(v, (list, tuple)) else [v]):
            add(n)
    for key in ("joint", "joints"):
        v = data.get(key)
        for n in (v if isinstance(v, (list, tuple)) else [v]):
            j = robot.joints.get(n) if isinstance(n, str) else None
            if j is not None:
                add(j.child)
    sensor = data.get("sensor")
    if isinstance(sensor, str):
        for s in robot.sensors():
            if s.name == sensor:
                add(s.reference)
    if not found:
        for tok in re.findall(r"[A-Za-z0-9_./-]+", d.message):
            add(tok)
            j = robot.joints.get(tok)
            if j is not None:
                add(j.child)
    return found
