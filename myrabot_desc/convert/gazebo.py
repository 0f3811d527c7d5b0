"""Per-link and per-joint ``<gazebo reference=...>`` properties in SDF terms.

Both spellings of the seed are accepted: ``<mu1>0.5</mu1>`` and ``<mu1 value="10"/>``
(the model's ``properties`` already reads either), ``fdir`` as well as ``fdir1``.
Several blocks for the same reference merge in document order (later wins).
"""

from __future__ import annotations

import copy

from myrabot_desc.convert.common import local, sub, to_bool, to_float, to_floats

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
        self.blobs: dict[str | None, list] = {}       # reference -> [<visual>|<collision> element]
        self.locs: dict[str | None, object] = {}
        unknown: dict[str, object] = {}
        for block in robot.gazebo:
            ref = block.reference
            props = self.by_ref.setdefault(ref, {})
            props.update(block.properties)
            self.locs.setdefault(ref, block.loc)
            for child in block.element:
                if local(child.tag) in ("visual", "collision") and not _ns(child):
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
        return self.by_ref.get(ref, {})

    def blob_children(self, ref, kind: str) -> list:
        """Children of injected ``<visual>``/``<collision>`` elements for this link."""
        out = []
        for el in self.blobs.get(ref, []):
            if local(el.tag) == kind:
                out.extend(c for c in el if isinstance(c.tag, str))
        return out

    # ------------------------------------------------------------ link level
    def apply_link(self, link_el, ref) -> None:
        p = self.get(ref)
        gravity_off = to_bool(p.get("turnGravityOff"))
        if gravity_off is not None:
            sub(link_el, "gravity", not gravity_off)
        elif p.get("gravity") is not None and to_bool(p.get("gravity")) is not None:
            sub(link_el, "gravity", to_bool(p["gravity"]))
        sc = to_bool(p.get("selfCollide"))
        if sc is not None:
            sub(link_el, "self_collide", sc)
        if to_bool(p.get("kinematic")) is not None:
            sub(link_el, "kinematic", to_bool(p["kinematic"]))
        lin = to_float(p.get("dampingFactor"), to_float(p.get("linearDamping")))
        ang = to_float(p.get("angularDamping"))
        if lin is not None or ang is not None:
            vd = sub(link_el, "velocity_decay")
            if lin is not None:
                sub(vd, "linear", lin)
            if ang is not None:
                sub(vd, "angular", ang)

    # ------------------------------------------------------------ collisions
    def apply_collision(self, coll_el, ref) -> None:
        p = self.get(ref)
        laser = to_float(p.get("laserRetro"))
        if laser is not None:
            sub(coll_el, "laser_retro", laser)
        mc = to_float(p.get("maxContacts"))
        if mc is not None:
            sub(coll_el, "max_contacts", int(mc))
        mu1, mu2 = to_float(p.get("mu1")), to_float(p.get("mu2"))
        fdir = to_floats(p.get("fdir1") or p.get("fdir"))
        slip1, slip2 = to_float(p.get("slip1")), to_float(p.get("slip2"))
        kp, kd = to_float(p.get("kp")), to_float(p.get("kd"))
        max_vel, min_depth = to_float(p.get("maxVel")), to_float(p.get("minDepth"))
        injected = self.blob_children(ref, "collision")
        if any(v is not None for v in (mu1, mu2, fdir, slip1, slip2, kp, kd, max_vel, min_depth)):
            surface = sub(coll_el, "surface")
            if any(v is not None for v in (mu1, mu2, fdir, slip1, slip2)):
                ode = sub(sub(surface, "friction"), "ode")
                for tag, v in (("mu", mu1), ("mu2", mu2), ("fdir1", fdir if fdir and len(fdir) == 3 else None),
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
            if local(child.tag) == "material":   # the resolved explicit material wins
                continue
            _merge(vis_el, child)

    # ------------------------------------------------------------ joints
    def apply_joint(self, joint_el, axis_el, ref) -> None:
        p = self.get(ref)
        if axis_el is not None:
            sr, ss = to_float(p.get("springReference")), to_float(p.get("springStiffness"))
            if sr is not None or ss is not None:
                dyn = axis_el.find("dynamics")
                if dyn is None:
                    dyn = sub(axis_el, "dynamics")
                if sr is not None:
                    sub(dyn, "spring_reference", sr)
                if ss is not None:
                    sub(dyn, "spring_stiffness", ss)
        fb = to_bool(p.get("provideFeedback"))
        cfm, erp = to_float(p.get("stopCfm")), to_float(p.get("stopErp"))
        kp, kd = to_float(p.get("stopKp")), to_float(p.get("stopKd"))
        if (cfm is None and erp is None) and (kp is not None or kd is not None):
            # Gazebo 0.x stop stiffness/damping -> ODE erp/cfm at the default 1 ms step:
            # erp = h kp / (h kp + kd), cfm = 1 / (h kp + kd)
            h, kp, kd = STEP, kp or 0.0, kd or 0.0
            if h * kp + kd > 0:
                erp, cfm = h * kp / (h * kp + kd), 1.0 / (h * kp + kd)
        j_erp, j_cfm = to_float(p.get("erp")), to_float(p.get("cfm"))
        isd = to_bool(p.get("implicitSpringDamper"), to_bool(p.get("cfmDamping")))
        fudge = to_float(p.get("fudgeFactor"))
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
        p = self.get(joint_name)
        return bool(to_bool(p.get("preserveFixedJoint")) or to_bool(p.get("disableFixedJointLumping")))


def _ns(el) -> bool:
    return isinstance(el.tag, str) and el.tag.startswith("{")


def _merge(target, child) -> None:
    """Deep-merge an injected SDF fragment: same-named children merge, leaves replace."""
    existing = target.find(child.tag)
    if existing is None or len(child) == 0:
        if existing is not None:
            target.remove(existing)
        target.append(copy.deepcopy(child))
        return
    for c in child:
        if isinstance(c.tag, str):
            _merge(existing, c)
