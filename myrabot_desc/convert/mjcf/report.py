"""What the MJCF conversion does with each element of the source, beyond what the body builder
records as it goes (dropped geometry, repaired inertias, mimic equalities, planar joints)."""

from __future__ import annotations

from myrabot_desc.convert.common import num
from myrabot_desc.convert.mjcf.gazebo_physics import (FRICTION_KEYS, MAX_FRICTION, SPRING_KEYS, joint_springs,
                                                      link_friction)
from myrabot_desc.model import drive as D
from myrabot_desc.model.gazebo_sdf import sdf_elements


def report_structure(robot, report, free: bool) -> None:
    """Fixed joints fused, joint types translated, the roots' base, transmissions."""
    for j in robot.joints.values():
        if j.type == "fixed":
            report.set("joint", j.name, "translated", f"fixed joint: '{j.child}' fused into its parent body")
            report.set("link", j.child, "translated", f"fused into the body of '{j.parent}' (fixed joint "
                                                       f"'{j.name}'); its geoms and mass kept there")
        elif j.type == "continuous":
            report.set("joint", j.name, "translated", "continuous -> unlimited hinge")
        elif j.type == "floating":
            report.set("joint", j.name, "translated", "floating -> free joint")
        if j.dynamics is not None and j.dynamics.friction:
            report.set("joint", j.name, "translated", f"friction {num(j.dynamics.friction)} -> frictionloss")
    for name in robot.roots:
        if free:
            report.set("link", name, "translated", "root: a body with a free joint (mobile base)")
        else:
            report.set("link", name, "translated", "root welded to the world (static: its mass has no effect)")
    for t in robot.transmissions:
        report.set("transmission", t.name or "?", "translated",
                   "read for the joints' interfaces; MuJoCo actuators written from the joint limits")


def report_gazebo(robot, report) -> None:
    """Gazebo's settings, plugins, sensors and SDF elements: translated or dropped."""
    springs, friction = joint_springs(robot), link_friction(robot)
    for g in robot.gazebo:
        for key in g.properties:
            if key in FRICTION_KEYS and g.reference in friction:
                mu = friction[g.reference]
                if mu <= MAX_FRICTION:
                    report.set("gazebo", f"{g.reference}/{key}", "translated", f"collision friction {num(mu)}"
                               + (" (over the floor's)" if mu < MAX_FRICTION else " (the floor's)"), g.loc)
                else:
                    report.set("gazebo", f"{g.reference}/{key}", "approximated",
                               f"mu {num(mu)}: the floor's friction {num(MAX_FRICTION)} (more makes MuJoCo's "
                               "contacts sink)", g.loc)
                continue
            if key in SPRING_KEYS and g.reference in springs:
                report.set("gazebo", f"{g.reference}/{key}", "translated",
                           "joint " + ("stiffness" if key == "springStiffness" else "springref"), g.loc)
                continue
            report.set("gazebo", f"{g.reference or 'model'}/{key}", "dropped", "Gazebo-only setting", g.loc)
        for p in g.plugins:
            drive = D.plugin_spec(p) is not None
            report.set("plugin", p.name or p.library or "?", "dropped",
                       "Gazebo drive plugin: its wheel joints get velocity actuators" if drive else
                       "Gazebo plugin: no MuJoCo equivalent", p.loc)
        for sn in g.sensors:
            report.set("sensor", sn.name or "?", "dropped", "Gazebo sensor: not converted to MuJoCo sensors", sn.loc)
            for p in sn.plugins:
                report.set("plugin", p.name or p.library or "?", "dropped", "a ROS sensor plugin", p.loc)
    for el in sdf_elements(robot):
        report.set(f"gazebo-{el.tag}", el.name or "?", "dropped",
                   "declared in a <gazebo> block (SDF): not part of the URDF tree MJCF is built from", el.loc)


def report_lift(robot, report, lift: float) -> None:
    report.set("link", robot.root or "root", "translated",
               f"root welded to the world {num(round(lift, 6))} m up, its lowest collision point on the floor")
