"""The physics facts the model derives: SRDF reading, self-collision (coal), gravity torque (numpy statics
against Pinocchio's generalized gravity) and the stands-on-legs decision, on real files."""

from __future__ import annotations

import math

import pytest

from helpers import CORPUS, ERD, corpus_model, corpus_robot, corpus_robots
from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.collisions import Scene, rigid_bodies, self_collisions
from myrabot_desc.model.legs import stance
from myrabot_desc.model.loader import load_robot
from myrabot_desc.model.srdf import load_srdf
from myrabot_desc.model.statics import gravity_needs, sample_values

np = pytest.importorskip("numpy")
pin = pytest.importorskip("pinocchio")


# ------------------------------------------------------------------ SRDF
def test_srdf_pairs_states_and_locations():
    s = load_srdf(ERD / "panda_description/srdf/panda.srdf")
    d = s.allows("panda_link5", "panda_hand")
    assert d is not None and d.reason == "Default" and d.loc.line == 38
    assert s.allows("panda_hand", "panda_link5") == d                 # either order
    assert s.allows("panda_link2", "panda_link5") is None
    st = s.state("default")
    assert st.joints["panda_joint4"] == pytest.approx(-2.35619) and st.group == "arm_and_hand"
    talos = load_srdf(ERD / "talos_data/srdf/talos.srdf").state("half_sitting")
    assert talos.joints["root_joint"][2] == pytest.approx(1.01927)   # 7 values: a free flyer's
    assert talos.joints["leg_left_4_joint"] == pytest.approx(0.859395)


def test_srdf_default_collisions_and_errors(tmp_path):
    f = tmp_path / "r.srdf"
    f.write_text('<robot name="r">\n<disable_default_collisions link="a"/>\n<enable_collisions link1="a" link2="b"/>\n'
                 '<group_state name="s" group="g"><joint name="j" value="0.5"/></group_state>\n</robot>\n')
    s = load_srdf(f)
    assert s.allows("a", "c").reason == "disable_default_collisions of a" and s.allows("a", "b") is None
    with pytest.raises(InputError, match="no group_state named 'up'.*it has: s"):
        s.state("up")
    f.write_text('<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x "y">]>\n<robot name="r"/>\n')
    with pytest.raises(InputError, match="DTDs and entity declarations are not allowed") as e:
        load_srdf(f)
    assert e.value.loc.line == 2
    f.write_text('<robot name="r">\n<group_state name="s"><joint name="j" value="high"/></group_state>\n</robot>\n')
    with pytest.raises(InputError, match="'high' is not a number") as e:
        load_srdf(f)
    assert e.value.loc.line == 2


# ------------------------------------------------------------------ self-collision
def _box_robot(tmp_path, gap: float):
    """Two boxes 10 cm wide on bodies two revolute joints apart, ``gap`` apart along x (negative: overlap)."""
    x = 0.1 + gap
    f = tmp_path / "r.urdf"
    f.write_text(f"""<robot name="r">
  <link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="m"/>
  <link name="b"><collision><origin xyz="{x} 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="m"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="m"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>""")
    return load_robot(f)


def test_overlap_depth_of_two_boxes_is_exact(tmp_path):
    o = self_collisions(_box_robot(tmp_path, -0.03))
    assert [(x.link_a, x.link_b) for x in o] == [("a", "b")]
    assert o[0].depth == pytest.approx(0.03, abs=1e-6) and not o[0].hull_only and o[0].loc_b.line == 4
    assert self_collisions(_box_robot(tmp_path, -0.0009)) == []       # 1 mm or less: parts touching
    assert self_collisions(_box_robot(tmp_path, 0.01)) == []


def test_parent_and_child_and_fixed_bodies_are_skipped():
    r = load_robot(ERD / "panda_description/urdf/panda.urdf")
    body = rigid_bodies(r)
    assert body["panda_hand"] == "panda_link7"                          # link8 and the hand are fixed to link7
    pairs = {(o.link_a, o.link_b): round(o.depth * 1000, 1) for o in self_collisions(r)}
    # the "41 mm" class: Franka's hand and fifth link at the rest pose (joint4 at its -0.0698 limit)
    assert pairs == {("panda_link5", "panda_hand"): 41.4, ("panda_link5", "panda_link7"): 5.7}


def test_concave_hull_overlap_is_told_from_a_real_one():
    """PR2's shoulder sits in its concave base: the hulls overlap by 256 mm, the triangles do not touch."""
    r = load_robot(ERD / "pr2_description/urdf/pr2.urdf")
    o = {(x.link_a, x.link_b): x for x in self_collisions(r)}
    base = o[("base_link", "r_shoulder_pan_link")]
    assert base.hull_only and round(base.depth * 1000) == 256
    assert not o[("r_shoulder_pan_link", "r_upper_arm_link")].hull_only


def test_check_reads_a_mesh_once_for_inertia_and_the_triangle_test(monkeypatch):
    """With meshes loaded (check --inertia), the touch test takes the loaded mesh's triangles: PR2's
    meshes are each read once, and the overlaps are those of reading the files again."""
    from myrabot_desc.model import collisions, meshes, shapes

    r = load_robot(ERD / "pr2_description/urdf/pr2.urdf")
    want = [(o.link_a, o.link_b, o.depth, o.hull_only) for o in self_collisions(r)]
    collisions._TRIANGLES.clear()
    shapes._MESHES.clear()
    shapes._CACHED[0] = 0
    reads = []
    real = meshes._read
    monkeypatch.setattr(meshes, "_read", lambda path, limit: reads.append(str(path)) or real(path, limit))
    got = [(o.link_a, o.link_b, o.depth, o.hull_only) for o in self_collisions(r, meshes=shapes.load_mesh)]
    assert got == want and any(h for *_, h in got)
    assert reads and len(reads) == len(set(reads))


def test_srdf_exclusions_mark_the_pairs_they_allow():
    r = load_robot(ERD / "panda_description/urdf/panda.urdf")
    o = Scene(r, True, load_srdf(ERD / "panda_description/srdf/panda.srdf")).overlaps(r.rest_pose())
    assert {(x.link_b, x.allowed.reason) for x in o} == {("panda_hand", "Default"), ("panda_link7", "Default")}


# ------------------------------------------------------------------ gravity torque
def _pinocchio_worst(robot):
    """The same sampling as model/statics.py, evaluated by Pinocchio's computeGeneralizedGravity."""
    m = robot.pinocchio()
    data = m.createData()
    rest = robot.rest_pose()
    slot = {m.names[i]: (m.joints[i].idx_q, m.joints[i].idx_v, m.joints[i].nq) for i in range(1, m.njoints)}

    def q_of(values):
        q = pin.neutral(m)
        full = dict(rest, **values)
        for j in robot.joints.values():
            if j.mimic is not None and j.mimic.joint in full:
                full[j.name] = j.mimic.offset + j.mimic.multiplier * full[j.mimic.joint]
        for name, x in full.items():
            if name in slot:
                iq, _, nq = slot[name]
                if nq == 1:
                    q[iq] = x
                else:
                    q[iq], q[iq + 1] = math.cos(x), math.sin(x)
        return q

    movers = [j for j in robot.joints.values() if j.type in ("revolute", "continuous", "prismatic")
              and j.mimic is None and j.name in slot]
    v = [slot[j.name][1] for j in movers]
    best = np.abs(pin.computeGeneralizedGravity(m, data, q_of({}))[v])
    for j in movers:
        for x in sample_values(j):
            best = np.maximum(best, np.abs(pin.computeGeneralizedGravity(m, data, q_of({j.name: x}))[v]))
    return dict(zip((j.name for j in movers), best))


@pytest.mark.parametrize("rel", ["pr2_description/urdf/pr2.urdf", "talos_data/robots/talos_reduced.urdf",
                                 "panda_description/urdf/panda.urdf", "tiago_description/robots/tiago.urdf",
                                 "simple_humanoid_description/urdf/simple_humanoid.urdf"])
def test_gravity_needs_equal_pinocchio(rel):
    r = load_robot(ERD / rel)
    ours = {n.joint: n.torque for n in gravity_needs(r)}
    theirs = _pinocchio_worst(r)
    assert set(ours) == set(theirs)
    assert max(abs(ours[k] - theirs[k]) for k in ours) < 1e-9


def test_pr2_shoulder_needs_52_newton_metres():
    n = {x.joint: x for x in gravity_needs(load_robot(ERD / "pr2_description/urdf/pr2.urdf"))}
    s = n["r_shoulder_lift_joint"]
    assert round(s.torque, 1) == 52.1 and s.effort == 30.0 and round(s.ratio, 2) == 1.74
    assert s.pose_joint == "r_shoulder_lift_joint"                     # its own range's arm-forward end


# ------------------------------------------------------------------ standing on legs
LEGGED = ["a1_description/urdf/a1.urdf", "anymal_c_simple_description/urdf/anymal.urdf", "go2_description/urdf/go2.urdf",
          "hyq_description/robots/hyq_no_sensors.urdf", "solo_description/robots/solo12.urdf",
          "talos_data/robots/talos_reduced.urdf", "romeo_description/urdf/romeo.urdf", "icub_description/robots/icub.urdf",
          "g1_description/urdf/g1_29dof_rev_1_0.urdf", "centauro_description/urdf/centauro.urdf"]
WELDED = ["panda_description/urdf/panda.urdf", "ur_description/urdf/ur5_robot.urdf", "baxter_description/urdf/baxter.urdf",
          "allegro_hand_description/urdf/allegro_left_hand.urdf", "talos_data/robots/talos_left_arm.urdf"]


@pytest.mark.parametrize("rel", LEGGED + WELDED)
def test_stands_on_legs(rel):
    r = load_robot(ERD / rel)
    s = stance(r)
    assert s.legged == (rel in LEGGED), s.why
    assert not D.is_mobile(r)


def test_stance_of_the_corpus_arms_and_bases():
    for rb in corpus_robots():
        if rb["kind"] not in ("arm", "mobile"):
            continue
        s = stance(corpus_model(rb))
        assert not s.legged, (rb["id"], s.why)
    assert "fixed to the 'world' link" in stance(corpus_model(corpus_robot("ur5e"))).why
    assert CORPUS.is_dir()


def _tree_urdf(n: int) -> str:
    """A chain of n links with a side branch on every third link; revolute, continuous and prismatic
    joints on tilted axes."""
    inertial = '<inertial><origin xyz="0.05 0.01 0"/><mass value="{m}"/><inertia ixx="1e-3" ixy="0" ixz="0" ' \
               'iyy="1e-3" iyz="0" izz="1e-3"/></inertial>'
    out = ['<robot name="t">', f'<link name="l0">{inertial.format(m=2)}</link>']
    kinds = ("revolute", "continuous", "prismatic")
    for i in range(1, n):
        parent = f"l{i - 1}" if i % 3 else f"l{max(0, i - 3)}"
        out.append(f'<link name="l{i}">{inertial.format(m=0.1 * i)}</link>')
        out.append(f'<joint name="j{i}" type="{kinds[i % 3]}"><parent link="{parent}"/><child link="l{i}"/>'
                   f'<origin xyz="0.1 0 0.05" rpy="0 {0.1 * i} 0"/><axis xyz="{i % 2} 1 {i % 5}"/>'
                   '<limit lower="-1" upper="1.2" effort="10" velocity="1"/></joint>')
    return "\n".join(out + ["</robot>"])


def test_gravity_needs_tree_form_equals_dense_form(tmp_path):
    """The subtree sums (linear in a wide tree) give the dense joint x link matrix's needs and poses."""
    from myrabot_desc.model.statics import _gravity_needs_dense

    f = tmp_path / "tree.urdf"
    f.write_text(_tree_urdf(40))
    r = load_robot(str(f))
    fast, dense = gravity_needs(r), _gravity_needs_dense(r)
    assert [n.joint for n in fast] == [n.joint for n in dense] and len(fast) == 39
    for a, b in zip(fast, dense):
        assert a.torque == pytest.approx(b.torque, rel=1e-9, abs=1e-12)
        assert a.at_rest == pytest.approx(b.at_rest, rel=1e-9, abs=1e-12)
        assert (a.pose_joint, a.pose_value) == (b.pose_joint, b.pose_value)
