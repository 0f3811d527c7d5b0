"""T: unknown URDF elements and attributes (typos such as <gaezebo>, fricction=, <box rpy>).

URDF parsers ignore what they do not know, so a typo silently removes a feature.
We walk the URDF tree against the URDF schema plus the extensions that real models
use (PyBullet's <contact>, ros2_control, Aldebaran limit extras, ...). <gazebo>,
<transmission>, <ros2_control> and URDF <sensor> bodies are free-form and not walked.

These rules (T005, T006, T007) judge the XML itself: what the typed model cannot hold because
no reader keeps it (an element or attribute nobody knows, a ``<ros>`` block where nobody reads
it). So they, and only they outside model/, read the robot's raw XML (``Robot.root_element``,
``Context.loc_of``); tests/model/test_raw_xml.py holds every other module to the typed model.
"""

from __future__ import annotations

import functools

from myrabot_desc.checks.rule import Finding, Fix, FixInfo, RemoveAttribute, RenameAttribute, RenameTag, rule

# element -> (allowed attributes, allowed children); None = anything (free-form body)
SCHEMA: dict[str, tuple[set[str], set[str] | None]] = {
    "robot": ({"name", "version"}, {"link", "joint", "material", "transmission", "gazebo", "sensor",
                                    "ros2_control", "mujoco", "klampt", "webots"}),
    "link": ({"name", "type"}, {"inertial", "visual", "collision", "contact", "collision_checking",
                                "self_filter", "velocity_decay"}),
    "inertial": (set(), {"origin", "mass", "inertia"}),
    "origin": ({"xyz", "rpy"}, set()),
    "mass": ({"value"}, set()),
    "inertia": ({"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}, set()),
    "visual": ({"name"}, {"origin", "geometry", "material"}),
    "collision": ({"name"}, {"origin", "geometry", "verbose", "material"}),
    "geometry": ({"name"}, {"box", "cylinder", "sphere", "mesh", "capsule"}),
    "box": ({"size"}, set()),
    "cylinder": ({"radius", "length"}, set()),
    "sphere": ({"radius"}, set()),
    "capsule": ({"radius", "length"}, set()),
    "mesh": ({"filename", "scale"}, set()),
    "material": ({"name"}, {"color", "texture"}),
    "color": ({"rgba"}, set()),
    "texture": ({"filename"}, set()),
    "joint": ({"name", "type", "dont_collapse"}, {"origin", "parent", "child", "axis", "calibration", "dynamics",
                                                   "limit", "mimic", "safety_controller"}),
    "parent": ({"link"}, set()),
    "child": ({"link"}, set()),
    "axis": ({"xyz"}, set()),
    "calibration": ({"rising", "falling", "reference_position"}, set()),
    "dynamics": ({"damping", "friction", "spring_stiffness", "spring_reference",
                  "D", "K", "mu_coulomb", "mu_viscous"}, set()),
    "limit": ({"lower", "upper", "effort", "velocity", "command_effort", "current", "gear_velocity"}, set()),
    "mimic": ({"joint", "multiplier", "offset"}, set()),
    "safety_controller": ({"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}, set()),
    # extensions used by real models, accepted as they are
    "contact": (set(), None), "collision_checking": (set(), None), "self_filter": (set(), None),
    "velocity_decay": (set(), None), "verbose": ({"value"}, set()),
    "transmission": (set(), None), "gazebo": (set(), None), "sensor": (set(), None),
    "ros2_control": (set(), None), "mujoco": (set(), None), "klampt": (set(), None), "webots": (set(), None),
}

# Where a misplaced thing belongs, for a better hint than a spelling match.
BELONGS = {
    ("box", "rpy"): "rpy is not an attribute of <box>; put the rotation on the <origin> of the <visual>/<collision>",
    ("box", "xyz"): "xyz is not an attribute of <box>; put the offset on the <origin> of the <visual>/<collision>",
    ("cylinder", "rpy"): "rpy belongs on the <origin> of the <visual>/<collision>",
    ("sphere", "rpy"): "rpy belongs on the <origin> of the <visual>/<collision>",
    ("mesh", "rpy"): "rpy belongs on the <origin> of the <visual>/<collision>",
    ("link", "origin"): "a <link> has no <origin>; put it on the <joint>, <visual>, <collision> or <inertial>",
    ("link", "gravity"): "link properties for Gazebo go in <gazebo reference=\"LINK\">",
    ("link", "kinematic"): "link properties for Gazebo go in <gazebo reference=\"LINK\">",
    ("link", "self_collide"): "link properties for Gazebo go in <gazebo reference=\"LINK\">",
    ("link", "selfCollide"): "link properties for Gazebo go in <gazebo reference=\"LINK\">",
    ("link", "mu1"): "friction for Gazebo goes in <gazebo reference=\"LINK\">",
    ("link", "mu2"): "friction for Gazebo goes in <gazebo reference=\"LINK\">",
}


def local(tag) -> str | None:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else None


def suggest(word: str, choices) -> str | None:
    m = _close(word, tuple(sorted(choices)), 1, 0.6)
    return m[0] if m else None


def only_candidate(word: str, choices) -> str | None:
    """The one known name ``word`` is a near miss of, or None when there are none or several."""
    m = _close(word, tuple(sorted(choices)), 2, 0.75)
    return m[0] if len(m) == 1 else None


@functools.lru_cache(maxsize=256)
def _close(word: str, choices: tuple, n: int, cutoff: float) -> tuple:
    """``difflib.get_close_matches(word, choices, n, cutoff)``, the same list, kept by content: a
    misspelt name is looked up against the same names again (both sides of a ``diff``, every file
    of a ``check -r`` of one robot's variants). The full ratio, a few hundred microseconds a name,
    is taken best bound first and only while a name could still enter the best ``n``: the ratio is
    at most the quick ratio (matching blocks are some of the characters in common), so once a
    name's (quick ratio, name) is below the ``n``-th (ratio, name) kept, no later one can enter."""
    import difflib      # a near miss is rare: most runs never ask

    s = difflib.SequenceMatcher()
    s.set_seq2(word)
    ranked = []
    for x in choices:
        s.set_seq1(x)
        if s.real_quick_ratio() >= cutoff:
            q = s.quick_ratio()
            if q >= cutoff:
                ranked.append((q, x))
    ranked.sort(reverse=True)
    best: list = []
    for q, x in ranked:
        if len(best) >= n and (q, x) < best[-1]:
            break
        s.set_seq1(x)
        r = s.ratio()
        if r >= cutoff:
            best.append((r, x))
            best.sort(reverse=True)
            del best[n:]
    return tuple(x for _r, x in best)


def _walk(ctx) -> list:
    """(element, parent_tag, problem) for unknown children and attributes; one walk for T005 and T006."""
    return ctx.fact("urdf_syntax.walk", lambda: _problems(ctx.robot.root_element))


_FREE = (None, None)


def _problems(root) -> list:
    """(element, parent tag, problem) of the tree under ``root``, by the SCHEMA's known paths.

    Recursive by element, with a leaf (an element SCHEMA gives no children) judged in its parent's
    loop: most elements are leaves, and each call or stack entry is a good part of the cost of
    one (a 20,000-link tree has 260,000 elements)."""
    out = []
    add = out.append
    schema = SCHEMA.get

    def attributes(el, tag, attrs):
        for a in el.keys():
            if a not in attrs and not a.startswith("{"):     # namespaced attributes are extensions
                add((el, tag, ("attribute", a)))

    def walk(el, tag, attrs, children):
        keys = el.keys()
        if keys and not attrs.issuperset(keys):    # the usual case is all known: one set test
            attributes(el, tag, attrs)
        for c in el:
            ct = c.tag
            if ct in children:                 # a comment's tag is a function: never in the set
                c_attrs, c_children = schema(ct, _FREE)
                if c_children:
                    walk(c, ct, c_attrs, c_children)
                elif c_children is not None:   # a leaf: its attributes, and any child is unknown
                    keys = c.keys()
                    if keys and not c_attrs.issuperset(keys):
                        attributes(c, ct, c_attrs)
                    if len(c):
                        for g in c:
                            gt = g.tag
                            if isinstance(gt, str) and not gt.startswith("{"):
                                add((g, ct, ("element", gt)))
                # None: a free-form body (keeps its own attributes and children)
            elif isinstance(ct, str) and not ct.startswith("{"):   # comments; namespaced elements: extensions
                add((c, tag, ("element", ct)))

    tag = local(root.tag)
    attrs, children = schema(tag, _FREE)
    if children is not None:
        walk(root, tag, attrs, children)
    return out


@rule("T005", "unknown-element", "warning",
      bad='<gaezebo reference="base_link">\n  <material>Gazebo/White</material>\n</gaezebo>',
      message='unknown element <gaezebo> in <robot name="example">: URDF parsers ignore it; did you mean <gazebo>?',
      good='<gazebo reference="base_link">\n  <material>Gazebo/White</material>\n</gazebo>',
      fix=FixInfo("sometimes", "unsafe", "a misspelt element is renamed to the one element its parent accepts that "
                  "it is a near miss of (start and end tag), when there is exactly one. Unsafe: parsers ignored "
                  "the element; after the fix they read it."))
def unknown_element(ctx):
    """An element URDF does not know (a typo like <gaezebo>): parsers skip it silently.

    Example: `<gaezebo><material>Gazebo/White</material></gaezebo>` at robot level; the
    material never reaches Gazebo. Fix: correct the spelling (did-you-mean is given) or
    move the element where it belongs. Extensions in an XML namespace are not reported.
    """
    import re

    unexpanded = {m for d in ctx.robot.build_warnings if d.code == "X002"
                  for m in re.findall(r"<([\w.-]+)>", d.message)}
    for el, parent, (kind, name) in _walk(ctx):
        if kind != "element" or (parent == "robot" and name == "ros") or name in unexpanded:
            continue                                   # <ros>: T007; unexpanded macro calls: X002
        allowed = SCHEMA[parent][1] or set()
        hint = BELONGS.get((parent, name))
        guess = suggest(name, allowed)
        msg = f"unknown element <{name}> in <{parent}{_named(el.getparent())}>: URDF parsers ignore it"
        if hint:
            msg += f"; {hint}"
        elif guess:
            msg += f"; did you mean <{guess}>?"
        one = None if hint else only_candidate(name, allowed)
        yield Finding(msg, ctx.loc_of(el), {"element": name, "parent": parent, "suggestion": guess},
                      fix=Fix((RenameTag(el, one),), "unsafe", f"<{name}> renamed <{one}>") if one else None)


@rule("T006", "unknown-attribute", "warning",
      bad='<link name="plate">\n  <visual><geometry><box size="0.3 0.24 0.01" rpy="0 0 0.1"/></geometry></visual>\n'
          '</link>\n<joint name="plate_joint" type="fixed"><parent link="base_link"/><child link="plate"/></joint>',
      message='unknown attribute rpy="0 0 0.1" on <box>: URDF parsers ignore it; rpy is not an attribute of <box>; '
              'put the rotation on the <origin> of the <visual>/<collision>',
      good='<link name="plate">\n  <visual>\n    <origin xyz="0 0 0" rpy="0 0 0.1"/>\n'
           '    <geometry><box size="0.3 0.24 0.01"/></geometry>\n  </visual>\n'
           '</link>\n<joint name="plate_joint" type="fixed"><parent link="base_link"/><child link="plate"/></joint>',
      fix=FixInfo("always", "safe", "an attribute that is a near miss of exactly one attribute of its element is "
                  "renamed to it (unsafe: parsers then read the value); any other unknown attribute is removed "
                  "(safe: no parser reads it). A value that belongs elsewhere (rpy on a <box>) is removed, not moved: "
                  "put it where the message says by hand if you meant it."))
def unknown_attribute(ctx):
    """An attribute URDF does not know (fricction=, <box rpy=...>): parsers ignore it.

    Example: `<dynamics damping="0.1" fricction="0.5"/>` leaves the joint without friction;
    `<box size="0.3 0.24 0.1" rpy="0 0 0"/>` has no effect. Fix: the spelling given as
    did-you-mean, or move the value to the element where it belongs (rpy goes on <origin>).
    """
    for el, tag, (kind, name) in _walk(ctx):
        if kind != "attribute":
            continue
        allowed = SCHEMA[tag][0]
        hint = BELONGS.get((tag, name))
        guess = suggest(name, allowed)
        msg = f"unknown attribute {name}=\"{el.get(name)}\" on <{tag}{_named(el)}>: URDF parsers ignore it"
        if hint:
            msg += f"; {hint}"
        elif guess:
            msg += f"; did you mean {guess}=?"
        one = None if hint else only_candidate(name, allowed)
        fix = (Fix((RenameAttribute(el, name, one),), "unsafe", f"{name}= renamed {one}=") if one and one not in el.attrib
               else Fix((RemoveAttribute(el, name),), "safe", f"{name}= removed"))
        yield Finding(msg, ctx.loc_of(el), {"attribute": name, "element": tag, "suggestion": guess}, fix=fix)


@rule("T007", "ros2-block-outside-plugin", "warning",
      bad='<ros>\n  <namespace>/</namespace>\n  <argument>/cmd_vel:=cmd_vel</argument>\n</ros>',
      message="ROS 2 <ros> block at robot level (<namespace>/, <argument>/cmd_vel:=cmd_vel) is read by no one; "
              "it belongs inside a ROS 2 gazebo_ros <plugin>",
      good='<gazebo>\n  <plugin name="imu" filename="libgazebo_ros_imu_sensor.so">\n'
           '    <ros>\n      <namespace>/</namespace>\n      <remapping>~/out:=imu</remapping>\n    </ros>\n'
           '  </plugin>\n</gazebo>')
def ros_block(ctx):
    """A ROS 2 `<ros>` block directly under `<robot>`: it only means something inside a ROS 2 plugin.

    gazebo_ros (ROS 2) plugins read `<ros><namespace>/<remapping>` from inside their own
    `<plugin>`; at robot level nobody reads it, so the namespace and remappings are lost
    (and in a ROS 1 setup `<ros>` is never read at all). Fix: move it into the `<plugin>`
    it configures, or delete it (ROS 1: use `robotNamespace` and launch-file remaps).
    """
    for el in ctx.robot.root_element.iterchildren("{*}ros"):     # <ros> in any namespace or none
        inner = ", ".join(f"<{local(c.tag)}>{(c.text or '').strip()}" for c in el if isinstance(c.tag, str))
        yield Finding(f"ROS 2 <ros> block at robot level ({inner}) is read by no one; it belongs inside "
                      "a ROS 2 gazebo_ros <plugin>", ctx.loc_of(el), {"content": inner})


def _named(el) -> str:
    if el is None:
        return ""
    n = el.get("name") or el.get("reference")
    return f" name=\"{n}\"" if n else ""
