"""Per-link and per-joint ``<gazebo reference=...>`` properties in SDF terms.

Both spellings of the seed are accepted: ``<mu1>0.5</mu1>`` and ``<mu1 value="10"/>``
(the model's ``properties`` already reads either), ``fdir`` as well as ``fdir1``; values are the
model's typed ones (``GazeboBlock.values``: numbers, vectors, and flags as sdformat spells them,
model/gazebo.py). Several blocks for the same reference merge in document order (later wins).
"""

from __future__ import annotations

from myrabot_desc.convert.common import element_of, sub
from myrabot_desc.model.gazebo import preserved_joints

STEP = 0.001        # gz-sim's default physics step, for the Gazebo 0.x stopKp/stopKd conversion

# keys that map onto SDF elements; everything else is reported once
LINK_KEYS = {"material", "mu1", "mu2", "fdir1", "fdir", "kp", "kd", "maxVel", "minDepth", "maxContacts",
             "laserRetro", "selfCollide", "turnGravityOff", "gravity", "dampingFactor", "linearDamping",
             "angularDamping", "kinematic", "minDepth", "slip1", "slip2", "torsional"}
JOINT_KEYS = {"springReference", "springStiffness", "stopCfm", "stopErp", "stopKp", "stopKd", "erp", "cfm",
              "provideFeedback",
              "implicitSpringDamper", "cfmDamping", "fudgeFactor", "preserveFixedJoint",
              "disableFixedJointLumping"}
MODEL_KEYS = {"static", "selfCollide", "self_collide", "allow_auto_disable", "enable_wind"}
# Electric-era keys that have no SDF meaning (Gazebo 0.x rendering/physics tuning)
IGNORED_KEYS = {"genTexCoord", "laserFiducialId", "visual", "collision", "sensor", "plugin"}


class GazeboProps:
    """Properties and injected ``<visual>``/``<collision>`` blobs, by reference."""

    def __init__(self, robot, notes):
        self.by_ref: dict[str | None, dict[str, str]] = {}
        self.typed: dict[str | None, dict] = {}       # reference -> the typed values (GazeboBlock.values)
        self.blobs: dict[str | None, list] = {}       # reference -> [<visual>|<collision> node]
        self.locs: dict[str | None, object] = {}
        self.preserved = preserved_joints(robot)
        unknown: dict[str, object] = {}
        for block in robot.gazebo:
            ref = block.reference
            props = self.by_ref.setdefault(ref, {})
            props.update(block.properties)
            self.typed.setdefault(ref, {}).update(block.values)
            self.locs.setdefault(ref, block.loc)
            for child in block.node.elements:
                if child.tag in ("visual", "collision") and not child.ns:
                    self.blobs.setdefault(ref, []).append(child)
            known = MODEL_KEYS if ref is None else (LINK_KEYS if ref in robot.links else JOINT_KEYS)
            for key in block.properties:
                if key not in known and key not in IGNORED_KEYS:
                    unknown.setdefault(f"{key} ({ref or 'model'})", block.loc)
        self.unknown = unknown
        if unknown:
            names = ", ".join(sorted(unknown))
            notes.warn(f"gazebo properties with no SDF equivalent, not converted: {names}")

    def get(self, ref) -> dict[str, str]:
        """The properties of a reference as written (text)."""
        return self.by_ref.get(ref, {})

    def values(self, ref) -> dict:
        """The properties of a reference, typed (model/gazebo.py)."""
        return self.typed.get(ref, {})

    def blob_children(self, ref, kind: str) -> list:
        """Children of injected ``<visual>``/``<collision>`` nodes for this link."""
        out = []
        for n in self.blobs.get(ref, []):
            if n.tag == kind:
                out.extend(n.elements)
        return out

    # ------------------------------------------------------------ link level
    def apply_link(self, link_el, ref) -> None:
        p = self.values(ref)
        gravity_off = p.get("turnGravityOff")
        if gravity_off is not None:
            sub(link_el, "gravity", not gravity_off)
        elif p.get("gravity") is not None:
            sub(link_el, "gravity", p["gravity"])
        sc = p.get("selfCollide")
        if sc is not None:
            sub(link_el, "self_collide", sc)
        if p.get("kinematic") is not None:
            sub(link_el, "kinematic", p["kinematic"])
        lin = p.get("dampingFactor")
        lin = lin if lin is not None else p.get("linearDamping")
        ang = p.get("angularDamping")
        if lin is not None or ang is not None:
            vd = sub(link_el, "velocity_decay")
            if lin is not None:
                sub(vd, "linear", lin)
            if ang is not None:
                sub(vd, "angular", ang)

    # ------------------------------------------------------------ collisions
    def apply_collision(self, coll_el, ref) -> None:
        p = self.values(ref)
        laser = p.get("laserRetro")
        if laser is not None:
            sub(coll_el, "laser_retro", laser)
        mc = p.get("maxContacts")
        if mc is not None:
            sub(coll_el, "max_contacts", int(mc))
        mu1, mu2 = p.get("mu1"), p.get("mu2")
        fdir = p.get("fdir1") if self.get(ref).get("fdir1") else p.get("fdir")
        slip1, slip2 = p.get("slip1"), p.get("slip2")
        kp, kd = p.get("kp"), p.get("kd")
        max_vel, min_depth = p.get("maxVel"), p.get("minDepth")
        injected = self.blob_children(ref, "collision")
        if any(v is not None for v in (mu1, mu2, fdir, slip1, slip2, kp, kd, max_vel, min_depth)):
            surface = sub(coll_el, "surface")
            if any(v is not None for v in (mu1, mu2, fdir, slip1, slip2)):
                ode = sub(sub(surface, "friction"), "ode")
                for tag, v in (("mu", mu1), ("mu2", mu2), ("fdir1", fdir),
                               ("slip1", slip1), ("slip2", slip2)):
                    if v is not None:
                        sub(ode, tag, v)
            if any(v is not None for v in (kp, kd, max_vel, min_depth)):
                ode = sub(sub(surface, "contact"), "ode")
                for tag, v in (("kp", kp), ("kd", kd), ("max_vel", max_vel), ("min_depth", min_depth)):
                    if v is not None:
                        sub(ode, tag, v)
        for child in injected:
            _merge(coll_el, child)

    def apply_visual(self, vis_el, ref) -> None:
        for child in self.blob_children(ref, "visual"):
            if child.tag == "material":   # the resolved explicit material wins
                continue
            _merge(vis_el, child)

    # ------------------------------------------------------------ joints
    def apply_joint(self, joint_el, axis_el, ref) -> None:
        p = self.values(ref)
        if axis_el is not None:
            sr, ss = p.get("springReference"), p.get("springStiffness")
            if sr is not None or ss is not None:
                dyn = axis_el.find("dynamics")
                if dyn is None:
                    dyn = sub(axis_el, "dynamics")
                if sr is not None:
                    sub(dyn, "spring_reference", sr)
                if ss is not None:
                    sub(dyn, "spring_stiffness", ss)
        fb = p.get("provideFeedback")
        cfm, erp = p.get("stopCfm"), p.get("stopErp")
        kp, kd = p.get("stopKp"), p.get("stopKd")
        if (cfm is None and erp is None) and (kp is not None or kd is not None):
            # Gazebo 0.x stop stiffness/damping -> ODE erp/cfm at the default 1 ms step:
            # erp = h kp / (h kp + kd), cfm = 1 / (h kp + kd)
            h, kp, kd = STEP, kp or 0.0, kd or 0.0
            if h * kp + kd > 0:
                erp, cfm = h * kp / (h * kp + kd), 1.0 / (h * kp + kd)
        j_erp, j_cfm = p.get("erp"), p.get("cfm")
        isd = p.get("implicitSpringDamper")
        isd = isd if isd is not None else p.get("cfmDamping")
        fudge = p.get("fudgeFactor")
        if any(v is not None for v in (fb, cfm, erp, isd, fudge, j_erp, j_cfm)):
            phys = sub(joint_el, "physics")
            ode = sub(phys, "ode")
            if isd is not None:
                sub(ode, "implicit_spring_damper", isd)
            if fudge is not None:
                sub(ode, "fudge_factor", fudge)
            if j_cfm is not None:
                sub(ode, "cfm", j_cfm)
            if j_erp is not None:
                sub(ode, "erp", j_erp)
            if cfm is not None or erp is not None:
                lim = sub(ode, "limit")
                sub(lim, "cfm", cfm if cfm is not None else 0.0)
                sub(lim, "erp", erp if erp is not None else 0.2)
            if fb is not None:
                sub(phys, "provide_feedback", fb)

    def preserve_fixed(self, joint_name: str) -> bool:
        """Fixed-joint lumping is off for this joint (model/gazebo.preserved_joints)."""
        return joint_name in self.preserved


def _merge(target, child) -> None:
    """Deep-merge an injected SDF fragment (a model node): same-named children merge, leaves replace."""
    existing = target.find(f"{{{child.ns}}}{child.tag}" if child.ns else child.tag)
    if existing is None or not child.children:
        if existing is not None:
            target.remove(existing)
        el = element_of(child)
        el.tail = child.tail
        target.append(el)
        return
    for c in child.elements:
        _merge(existing, c)
