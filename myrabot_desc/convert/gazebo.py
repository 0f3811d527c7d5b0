"""Per-link and per-joint ``<gazebo reference=...>`` properties in SDF terms.

Both spellings of the seed are accepted: ``<mu1>0.5</mu1>`` and ``<mu1 value="10"/>``
(the model's ``properties`` already reads either), ``fdir`` as well as ``fdir1``; values are the
model's typed ones (``GazeboBlock.values``: numbers, vectors, and flags as sdformat spells them,
model/gazebo.py). Several blocks for the same reference merge in document order (later wins).
"""

from __future__ import annotations

from myrabot_desc.convert.common import comment, element_of, sub, xml_text
from myrabot_desc.model.plugins import node_kind
from myrabot_desc.model.gazebo import EMITTERS, preserved_joints, velocity_decay

STEP = 0.001        # gz-sim's default physics step, for the Gazebo 0.x stopKp/stopKd conversion

# keys that map onto SDF elements; everything else is reported once
LINK_KEYS = {"material", "mu1", "mu2", "fdir1", "fdir", "kp", "kd", "maxVel", "minDepth", "maxContacts",
             "laserRetro", "selfCollide", "turnGravityOff", "gravity", "dampingFactor", "linearDamping",
             "angularDamping", "kinematic", "minDepth", "slip1", "slip2", "torsional", "enable_wind"}
JOINT_KEYS = {"springReference", "springStiffness", "stopCfm", "stopErp", "stopKp", "stopKd", "erp", "cfm",
              "provideFeedback",
              "implicitSpringDamper", "cfmDamping", "fudgeFactor", "preserveFixedJoint",
              "disableFixedJointLumping"}
MODEL_KEYS = {"static", "selfCollide", "self_collide", "allow_auto_disable", "enable_wind"}
# Electric-era keys that have no SDF meaning (Gazebo 0.x rendering/physics tuning)
IGNORED_KEYS = {"genTexCoord", "laserFiducialId", "visual", "collision", "sensor", "plugin"}
# elements with children that a link's block carries into the SDF (sdf.py places the emitters)
LINK_ELEMENTS = {"visual", "collision", "sensor", "plugin", "velocity_decay", *EMITTERS}


class GazeboProps:
    """Properties and injected ``<visual>``/``<collision>`` blobs, by reference."""

    def __init__(self, robot, notes):
        self.by_ref: dict[str | None, dict[str, str]] = {}
        self.typed: dict[str | None, dict] = {}       # reference -> the typed values (GazeboBlock.values)
        self.blobs: dict[str | None, list] = {}       # reference -> [<visual>|<collision> node]
        self.locs: dict[str | None, object] = {}
        self.decay: dict[str | None, list] = {}       # reference -> [linear, angular] velocity decay
        self.preserved = preserved_joints(robot)
        unknown: dict[str, object] = {}
        self.dropped: list[tuple[str, str, object]] = []  # (reference, element with its name, loc), each one
        self._dropped_labels: set[tuple[str, str]] = set()  # its (reference, label) pairs
        self.commented: list[tuple[str, object]] = []     # (plugin name, node) of classic plugins in blobs
        for block in robot.gazebo:
            ref = block.reference
            props = self.by_ref.setdefault(ref, {})
            props.update(block.properties)
            self.typed.setdefault(ref, {}).update(block.values)
            self.locs.setdefault(ref, block.loc)
            is_link = ref is not None and ref in robot.links
            if is_link:
                decay = self.decay.setdefault(ref, [None, None])
                for k, v in enumerate(velocity_decay(block)):
                    if v is not None:
                        decay[k] = v
            for child in block.node.elements:
                if child.tag in ("visual", "collision") and not child.ns:
                    self.blobs.setdefault(ref, []).append(child)
                elif is_link and child.elements and not child.ns and child.tag not in LINK_ELEMENTS:
                    self._drop(ref, child, block.loc)
            known = MODEL_KEYS if ref is None else (LINK_KEYS if is_link else JOINT_KEYS)
            for child in block.node.elements:
                key = child.tag
                if child.elements or child.ns or key not in block.properties:
                    continue
                if key not in known and key not in IGNORED_KEYS and not (is_link and key in EMITTERS):
                    unknown.setdefault(f"{key} ({ref or 'model'})", block.loc)
                    self._drop(ref, child, block.loc)
        self.unknown = unknown
        if self.dropped:
            names = ", ".join(f"{label} ({ref})" for ref, label, _ in self.dropped)
            notes.warn(f"gazebo elements with no SDF equivalent, not converted: {names}")

    def _drop(self, ref, child, loc) -> None:
        name = child.get("name")
        ref = ref or "model"
        label = base = f"{child.tag} '{name}'" if name else child.tag
        k = 2
        while (ref, label) in self._dropped_labels:
            label, k = f"{base} #{k}", k + 1
        self._dropped_labels.add((ref, label))
        self.dropped.append((ref, label, child.loc or loc))

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
        if ref not in self.typed and ref not in self.decay:
            return          # no <gazebo> block names it (most links): nothing to write
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
        if p.get("enable_wind") is not None:
            sub(link_el, "enable_wind", p["enable_wind"])
        lin, ang = self.decay.get(ref, (None, None))
        if lin is not None or ang is not None:
            vd = sub(link_el, "velocity_decay")
            if lin is not None:
                sub(vd, "linear", lin)
            if ang is not None:
                sub(vd, "angular", ang)

    # ------------------------------------------------------------ collisions
    def apply_collision(self, coll_el, ref) -> None:
        if ref not in self.typed and ref not in self.by_ref and ref not in self.blobs:
            return
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
            if not self._classic_plugin(coll_el, child):
                _merge(coll_el, child)

    def apply_visual(self, vis_el, ref) -> None:
        if ref not in self.blobs:
            return
        for child in self.blob_children(ref, "visual"):
            if child.tag == "material":   # the resolved explicit material wins
                continue
            if not self._classic_plugin(vis_el, child):
                _merge(vis_el, child)

    def _classic_plugin(self, target, child) -> bool:
        """A Gazebo classic plugin in an injected <visual>/<collision> (gazebo_ros_video...): kept
        as an XML comment, as model-level classic plugins are; True when it was one."""
        if child.ns or child.tag != "plugin" or node_kind(child) == "gz":
            return False
        comment(target, f"not converted (no gz-sim equivalent known): {xml_text(child)}")
        if not any(n is child for _, n in self.commented):
            self.commented.append((child.get("name") or child.get("filename") or "?", child))
        return True

    # ------------------------------------------------------------ joints
    def apply_joint(self, joint_el, axis_el, ref) -> None:
        if ref not in self.typed:
            return
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
    if existing is not None and not child.elements and not (child.text or "").strip() and not child.attrs \
            and len(existing):
        return      # an empty <ode/> adds nothing to what the properties wrote (minDepth, kp...)
    if existing is None or not child.children:
        if existing is not None:
            target.remove(existing)
        el = element_of(child)
        el.tail = child.tail
        target.append(el)
        return
    for c in child.elements:
        _merge(existing, c)
