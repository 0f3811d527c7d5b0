"""Where a physics run starts: the joint values, and which source gave them.

In order: ``--pose FILE`` (YAML read by expand/yaml_load.py: ``joint: value`` pairs, at the top or
under ``initial_positions``/``joints``/``pose``, as ros2_control's ``initial_positions.yaml`` writes
them); an SRDF reference configuration (``--srdf FILE --state NAME``, a ``<group_state>``); the
package's own initial positions, as its ros2_control block carries them into the URDF
(``<state_interface name="position"><param name="initial_value">``, which the packages fill from
their ``initial_positions.yaml``); else ``Robot.rest_pose`` (every joint at 0, or its nearer limit).
"""

from __future__ import annotations

import math

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.yaml_load import load_path
from myrabot_desc.model import values as V
from myrabot_desc.model.srdf import load_srdf
from myrabot_desc.records import Struct
from myrabot_desc.safety import display, limit

MOVING = ("revolute", "continuous", "prismatic")


class Start(Struct):
    q: dict                  # joint -> value (every moving, non-mimic joint)
    source: str              # what gave it, in words
    kind: str                # "pose-file" | "srdf" | "initial-positions" | "rest"
    notes: tuple = ()        # values clamped into range, names the model does not have


def _rest_note() -> str:
    return "the rest pose (every joint at 0, or at its nearer limit when 0 is outside its range)"


def initial_positions(robot) -> dict:
    """joint -> the ``initial_value`` of its ros2_control ``position`` state interface."""
    out = {}
    for block in robot.ros2_control:
        if block.node is None:
            continue
        for j in block.node.all("joint"):
            name = j.get("name")
            for si in j.all("state_interface") if name else ():
                if si.get("name") != "position":
                    continue
                for p in si.all("param"):
                    if p.get("name") == "initial_value":
                        v = V.number(p.value)
                        if v is not None:
                            out[name] = v
    return out


def _from_yaml(path) -> dict:
    data = load_path(path, limit("max_input_bytes"), None, display(path))
    if isinstance(data, dict):
        for key in ("initial_positions", "joints", "pose"):
            if isinstance(data.get(key), dict):
                data = data[key]
                break
    if not isinstance(data, dict) or not data:
        raise InputError("a pose file holds joint: value pairs (at the top, or under initial_positions, "
                         "joints or pose)", Loc(display(path)))
    out = {}
    for name, value in data.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(f"joint '{name}': {value!r} is not a number", Loc(display(path)))
        out[str(name)] = float(value)
    return out


def start_pose(robot, pose_file=None, srdf=None, state=None) -> Start:
    """The start pose and its source (see the module docstring)."""
    notes = []
    given, source, kind = {}, None, None
    if pose_file:
        given, source, kind = _from_yaml(pose_file), f"--pose {display(pose_file)}", "pose-file"
        unknown = sorted(n for n in given if n not in robot.joints)
        if unknown:
            raise InputError(f"joint(s) {', '.join(unknown[:5])} of the pose are not in the model",
                             Loc(display(pose_file)))
    elif state:
        if not srdf:
            raise InputError("--state NAME names a group_state of the SRDF given with --srdf FILE")
        doc = srdf if hasattr(srdf, "states") else load_srdf(srdf)
        st = doc.state(state)
        foreign = []
        for name, value in st.joints.items():
            j = robot.joints.get(name)
            if j is None or j.type not in MOVING or isinstance(value, tuple):
                foreign.append(name)
                continue
            given[name] = value
        if foreign:
            more = ", ..." if len(foreign) > 6 else ""
            notes.append(f"SRDF state '{state}' also sets {', '.join(foreign[:6])}{more}: not a moving joint of "
                         "this model (a floating root_joint, joints of another variant), left out")
        source, kind = f"SRDF state '{state}' ({st.loc.file}:{st.loc.line})", "srdf"
    else:
        init = initial_positions(robot)
        if init:
            given = {n: v for n, v in init.items() if n in robot.joints}
            source, kind = "the package's initial positions (ros2_control initial_value)", "initial-positions"
    q = robot.rest_pose()
    for name, value in given.items():
        j = robot.joints[name]
        if j.mimic is not None or j.type not in MOVING:
            continue
        lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None and j.type != "continuous" else (None, None)
        if lo is not None and hi is not None and lo <= hi and not (lo - 1e-9 <= value <= hi + 1e-9):
            clamped = min(max(value, lo), hi)
            notes.append(f"joint '{name}' at {value:g} is outside its range [{lo:g}, {hi:g}]: {clamped:g} used")
            value = clamped
        q[name] = value
    if source is None:
        return Start(q, _rest_note(), "rest", tuple(notes))
    missing = sum(1 for n in q if n not in given)
    if missing:
        source += f"; {missing} joint(s) it does not name at the rest pose"
    return Start(q, source, kind, tuple(notes))
