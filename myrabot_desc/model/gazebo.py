"""The ``<gazebo>`` extension properties, typed as their reader takes them.

A ``<gazebo reference="LINK|JOINT">`` (or model-level) block's childless children are
properties: ``<mu1>0.5</mu1>`` or ``<mu1 value="0.5"/>``. sdformat's URDF parser
(``src/parser_urdf.cc``, the code ``gz sdf -p`` and Gazebo run) reads the numbers with
``std::stod``, ``fdir1`` as three numbers, and its flags (``selfCollide``, ``static``,
``provideFeedback``, ``implicitSpringDamper``/``cfmDamping``, ``preserveFixedJoint``,
``disableFixedJointLumping``, ``turnGravityOff``) with its own spellings (model/values.EXTENSION);
the properties it does not know (``gravity``, ``kinematic``, ``self_collide``...) it copies into
the SDF, where sdformat's Param reads them (model/values.SDF).

``typed(props)`` gives every property's value: a float, a tuple, a bool, or the text for names
that are text (``material``) or unknown; None for a number or vector that cannot be read.
"""

from myrabot_desc.model import values as V
from myrabot_desc.records import Struct

NUMBERS = frozenset({
    "mu1", "mu2", "kp", "kd", "maxVel", "minDepth", "maxContacts", "laserRetro", "dampingFactor",
    "linearDamping", "angularDamping", "slip1", "slip2", "springReference", "springStiffness", "stopCfm",
    "stopErp", "stopKp", "stopKd", "erp", "cfm", "fudgeFactor"})
VECTORS = {"fdir1": 3, "fdir": 3}
# flags sdformat's URDF parser reads itself (true/yes/1), and the one it reads the other way round
EXTENSION_FLAGS = frozenset({"selfCollide", "static", "provideFeedback", "implicitSpringDamper", "cfmDamping",
                             "preserveFixedJoint", "disableFixedJointLumping"})
INVERTED_FLAGS = frozenset({"turnGravityOff"})
# flags it copies into the SDF as they are (read by sdformat's Param: true/1, false/0)
SDF_FLAGS = frozenset({"gravity", "kinematic", "self_collide", "allow_auto_disable", "enable_wind"})
# elements of a link's <gazebo> block that SDF has under <link> (sdformat's converter copies them there)
EMITTERS = ("light", "projector")


class Emitter(Struct):
    """A ``<light>`` or ``<projector>`` in a ``<gazebo reference="LINK">`` block."""

    kind: str                       # 'light' | 'projector'
    name: str | None
    reference: str                  # the link whose block holds it
    pose: tuple | None              # x y z roll pitch yaw as written (None: no <pose>, or unreadable)
    relative_to: str | None         # the <pose relative_to=...> frame, if any
    node: object                       # the element (model Node), copied as written
    loc: object = None


def emitters(robot) -> list[Emitter]:
    """Every light and projector of the links' ``<gazebo>`` blocks, in document order."""

    def build():
        out = []
        for g in robot.gazebo:
            if g.reference is None or g.reference not in robot.links:
                continue
            for c in g.node.elements:
                if c.ns or c.tag not in EMITTERS:
                    continue
                pose = c.child("pose")
                out.append(Emitter(c.tag, c.get("name"), g.reference, c.vector("pose", n=6),
                                   pose.get("relative_to") if pose is not None else None, c, c.loc or g.loc))
        return tuple(out)
    return list(robot.derive("gazebo.emitters", build))


def velocity_decay(block) -> tuple[float | None, float | None]:
    """(linear, angular) velocity decay one ``<gazebo reference>`` block sets: ``dampingFactor``
    sets both (sdformat's parser_urdf.cc writes it as linear and angular), ``linearDamping`` /
    ``angularDamping`` each one, a ``<velocity_decay>`` element (copied by sdformat as written)
    its ``<linear>``/``<angular>``; a later one wins. None where none is given."""
    v = block.values
    lin = ang = v.get("dampingFactor")
    if v.get("linearDamping") is not None:
        lin = v["linearDamping"]
    if v.get("angularDamping") is not None:
        ang = v["angularDamping"]
    for c in block.node.elements:
        if not c.ns and c.tag == "velocity_decay":
            if c.number("linear") is not None:
                lin = c.number("linear")
            if c.number("angular") is not None:
                ang = c.number("angular")
    return lin, ang


def typed(name: str, text: str | None):
    """One property's value (see the module doc)."""
    if text is None:
        return None
    if name in NUMBERS:
        return V.number(text)
    if name in VECTORS:
        return V.vector(text, VECTORS[name])
    if name in EXTENSION_FLAGS:
        return V.extension_flag(text)
    if name in INVERTED_FLAGS:
        return V.extension_flag(text, inverted=True)
    if name in SDF_FLAGS:
        return V.boolean(text)
    return text


def typed_properties(props: dict[str, str]) -> dict:
    return {k: typed(k, v) for k, v in props.items()}


def preserved_joints(robot) -> set[str]:
    """Fixed joints whose lumping is off (``preserveFixedJoint`` or the older
    ``disableFixedJointLumping``): the SDF keeps them, and the massless link behind one is not
    carried into its parent. The one answer check's S004 and convert's lumping share."""

    def build():
        out = set()
        for g in robot.gazebo:
            v = g.values
            if g.reference is not None and (v.get("preserveFixedJoint") or v.get("disableFixedJointLumping")):
                out.add(g.reference)
        return frozenset(out)
    return set(robot.derive("gazebo.preserved_joints", build))
