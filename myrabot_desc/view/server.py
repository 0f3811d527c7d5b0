"""``myrabot-desc view``: the robot in a local web viewer (viser), with joint sliders and diagnosis overlays.

One viser scene holds the whole model: a node per link placed by our kinematics, the visual and
collision parts under it (``view.scene``), and the overlays (``view.overlays``): link frames with
names, centres of mass, equivalent inertia boxes, the ground with the contacts and support
polygon, and the drive plugin's wheels against the URDF's. The GUI has a slider per movable joint,
zero / random buttons, the values as ``NAME:=VALUE`` and YAML, the toggles, and ``check``'s
findings: clicking one paints its links. With ``--watch`` the model is reloaded when one of its
files changes, keeping the joint values and toggles.
"""

from __future__ import annotations

import threading
import time

from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.errors import InputError
from myrabot_desc.model.kinematics import require_tree
from myrabot_desc.view import overlays
from myrabot_desc.view.overlays import finding_links
from myrabot_desc.view.scene import build_scene

HIGHLIGHT = (255, 0, 200)
TOGGLES = {            # name -> (label, default)
    "visual": ("visual geometry", True),
    "collision": ("collision geometry", False),
    "frames": ("link frames (TF)", False),
    "names": ("frame names", False),
    "com": ("centres of mass", False),
    "inertia": ("inertia boxes", False),
    "support": ("ground, contacts, support polygon", False),
    "wheels": ("wheels: plugin vs URDF", False),
}
MAX_FINDINGS = 100


class Viewer:
    """The server, the loaded model and the viewer's state (joint values, toggles, highlight).

    ``q`` and ``link_poses`` are what the browser was last sent; tests read them.
    """

    def __init__(self, load, host: str = "127.0.0.1", port: int = 8080, findings: bool = True, label: str = ""):
        import contextlib
        import sys

        self._load = load                       # () -> Robot (raises InputError)
        first = self._read()                    # a bad file stops here, before a server runs
        import viser

        with contextlib.redirect_stdout(sys.stderr):    # viser's banner: stdout carries only our URL
            self.server = viser.ViserServer(host=host, port=port, label=label or "myrabot-desc view", verbose=False)
        # No share button: it would open a tunnel to a public relay; this viewer stays on this machine.
        self.server.gui.configure_theme(show_share_button=False, control_width="large", show_logo=False)
        self.server.scene.set_up_direction("+z")
        self.lock = threading.RLock()
        self.q: dict[str, float] = {}
        self.toggles = {k: v[1] for k, v in TOGGLES.items()}
        self.highlighted: set[str] = set()
        self.selected_finding = None
        self.link_poses: dict = {}
        self.findings: list = []
        self.error: str | None = None
        self.with_findings = findings
        self.generation = 0                     # bumped by every (re)load
        self.placed_at = 0.0
        self._sent_generation = -1
        self._quiet = False                     # set_joints moving the sliders: no callback per slider
        self._nodes: dict[str, list] = {}       # group -> scene handles
        self._link_nodes: dict = {}
        self._visuals: dict[str, list] = {}     # link -> [(handle, rgb)]
        self._sliders: dict = {}
        self._stop = threading.Event()
        self.robot = None
        self.scene = None
        self.reload(first)

    # ------------------------------------------------------------ URL
    @property
    def url(self) -> str:
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    # ------------------------------------------------------------ loading
    def _read(self):
        """(robot, scene) of the model, or InputError."""

        robot = self._load()
        require_tree(robot)
        return robot, build_scene(robot)

    def reload(self, loaded=None) -> bool:
        """(Re)load the model and rebuild scene and GUI; on a load error keep what is shown."""

        try:
            robot, scene = loaded or self._read()
        except InputError as exc:
            self.error = str(exc).splitlines()[0]
            self._status(f"**reload failed**, showing the previous model:\n\n`{self.error}`")
            return False
        with self.lock:
            self.robot, self.scene, self.error = robot, scene, None
            self.q = scene.clamp(self.q)
            self.highlighted = set()
            self.selected_finding = None
            self.findings = []
            self._build()
            self.generation += 1                # after the build: a reader of generation sees the new scene
        if self.with_findings:
            threading.Thread(target=self._run_checks, args=(self.generation,), daemon=True).start()
        return True

    def files(self) -> set[str]:
        """Files the loaded model was read from (xacro sources, meshes): what --watch polls."""
        r = self.robot
        out = {str(r.source)} if r.source else set()
        out |= {f for f in r.source_files() if f}
        for link in r.links.values():
            for item in (*link.visuals, *link.collisions):
                g = item.geometry
                if g is not None and g.kind == "mesh" and g.path is not None:
                    out.add(str(g.path))
        return out

    def watch(self, interval: float = 0.5) -> None:
        """Poll the model's files; reload when one changes (in a daemon thread)."""
        import os

        def stamp(files):
            out = {}
            for f in files:
                try:
                    st = os.stat(f)
                    out[f] = (st.st_mtime_ns, st.st_size)
                except OSError:
                    out[f] = None
            return out

        def loop():
            seen = stamp(self.files())
            while not self._stop.wait(interval):
                now = stamp(seen)
                if now != seen:
                    self.reload()
                    seen = stamp(self.files())

        threading.Thread(target=loop, daemon=True).start()

    def stop(self) -> None:
        self._stop.set()
        self.server.stop()

    # ------------------------------------------------------------ scene
    def _build(self) -> None:
        sc = self.server.scene
        gui = self.server.gui
        sc.reset()
        gui.reset()
        gui.configure_theme(show_share_button=False, control_width="large", show_logo=False)
        self.server.scene.set_up_direction("+z")
        self._nodes = {k: [] for k in TOGGLES}
        self._link_nodes, self._visuals = {}, {}
        self.link_poses = {}                    # new nodes: every link goes out
        with self.server.atomic():
            overlays.add_parts(self, sc)
            overlays.add_overlays(self, sc)
            self._build_gui(gui)
            self._place()
            self._apply_toggles()
        self._frame_camera()

    def _frame_camera(self) -> None:
        import numpy as np

        v = self.scene.world_vertices(self.q)
        if not len(v):
            return
        lo, hi = v.min(axis=0), v.max(axis=0)
        centre, size = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) or 1.0
        cam = self.server.initial_camera
        cam.look_at = tuple(centre)
        cam.position = tuple(centre + np.array([1.0, -0.8, 0.5]) * size * 0.65)

    def _place(self) -> None:
        """Send the link poses for the current joint values (and what depends on them)."""
        import numpy as np
        import viser.transforms as vtf

        T = self.scene.transforms(self.q)
        prev = self.link_poses if self._sent_generation == self.generation else {}
        for link, handle in self._link_nodes.items():
            M = T.get(link)
            if M is None or (link in prev and np.array_equal(prev[link], M)):
                continue                                  # only the links that moved go out
            handle.position = tuple(M[:3, 3])
            handle.wxyz = tuple(vtf.SO3.from_matrix(M[:3, :3]).wxyz)
        self.link_poses = T
        self._sent_generation = self.generation
        overlays.update_dynamic(self, T)
        if "values" in self._gui:
            self._gui["values"].content = self._values_text()

    def set_joints(self, values: dict[str, float]) -> None:
        """Set joint values (clamped to limits) and move the sliders and the robot."""
        with self.lock, self.server.atomic():
            self.q.update(self.scene.clamp(values))
            self._quiet = True
            try:
                for name in values:
                    s = self._sliders.get(name)
                    if s is not None and name in self.q and abs(s.value - self.q[name]) > 1e-12:
                        s.value = self.q[name]
            finally:
                self._quiet = False
            self._place()

    def _apply_toggles(self) -> None:
        for group, handles in self._nodes.items():
            on = self.toggles.get(group, False)
            for h in handles:
                h.visible = on

    def set_toggle(self, name: str, on: bool) -> None:
        with self.lock, self.server.atomic():
            self.toggles[name] = bool(on)
            for h in self._nodes.get(name, ()):
                h.visible = bool(on)
            if name in ("support", "com"):
                overlays.update_dynamic(self, self.link_poses)

    def highlight(self, links) -> None:
        """Paint the visual geometry of ``links`` (and only them) in the highlight colour."""
        with self.lock, self.server.atomic():
            new = {n for n in links if n in self._visuals}
            for link in self.highlighted | new:
                on = link in new
                for h, rgb in self._visuals.get(link, ()):
                    h.color = HIGHLIGHT if on else rgb
            self.highlighted = new

    # ------------------------------------------------------------ GUI
    def _build_gui(self, gui) -> None:
        import random

        self._gui: dict = {}
        self._sliders = {}
        r = self.robot
        gui.add_markdown(f"**{r.name}** · {len(r.links)} links · {len(self.scene.joints)} movable joints")
        self._gui["status"] = gui.add_markdown(self._status_text(), visible=bool(self.scene.problems or self.error))
        with gui.add_folder("Joints"):
            rest = self.scene.rest()
            for name, rng in self.scene.joints.items():
                step = 0.001 if rng.type == "prismatic" else 0.005
                v = min(max(self.q.get(name, rest[name]), rng.lower), rng.upper)
                self.q[name] = v
                s = gui.add_slider(name, min=round(rng.lower, 6), max=round(rng.upper, 6), step=step,
                                   initial_value=round(v, 6), hint=f"{rng.type} joint, "
                                   + ("m" if rng.type == "prismatic" else "rad"))
                s.on_update(self._slider_cb(name))
                self._sliders[name] = s
            zero = gui.add_button("zero")
            rand = gui.add_button("random")

            @zero.on_click
            def _(_):
                self.set_joints({n: (0.0 if rg.lower <= 0 <= rg.upper else rg.lower)
                                 for n, rg in self.scene.joints.items()})

            @rand.on_click
            def _(_):
                self.set_joints({n: random.uniform(rg.lower, rg.upper) for n, rg in self.scene.joints.items()})

            self._gui["values"] = gui.add_markdown(self._values_text())
        with gui.add_folder("Show"):
            for key, (label, _) in TOGGLES.items():
                if key == "wheels" and not self._nodes.get("wheels"):
                    continue
                cb = gui.add_checkbox(label, initial_value=self.toggles[key])
                cb.on_update(self._toggle_cb(key))
        with gui.add_folder("Findings") as folder:
            self._gui["findings_folder"] = folder
            self._gui["findings_head"] = gui.add_markdown("running `check --inertia`..." if self.with_findings
                                                          else "findings off (--no-check)")
            self._gui["finding_detail"] = gui.add_markdown("", visible=False)
            self._gui["finding_buttons"] = []

    def _slider_cb(self, name):
        def cb(event):
            if self._quiet:
                return
            with self.lock, self.server.atomic():
                self.q[name] = float(event.target.value)
                self._place()
            self.placed_at = time.perf_counter()     # when the poses went out (bench/bench_view.py)

        return cb

    def _toggle_cb(self, key):
        def cb(event):
            self.set_toggle(key, bool(event.target.value))

        return cb

    def _values_text(self) -> str:
        if not self.scene.joints:
            return "no movable joints"
        args = " ".join(f"{n}:={self.q.get(n, 0.0):.4g}" for n in self.scene.joints)
        yaml = "\n".join(f"  {n}: {self.q.get(n, 0.0):.6g}" for n in self.scene.joints)
        return f"```\n{args}\n```\nYAML (`render --pose`):\n```yaml\njoints:\n{yaml}\n```"

    def _status_text(self) -> str:
        lines = [f"`{p}`" for p in self.scene.problems[:10]]
        if self.error:
            lines.insert(0, f"**reload failed**: `{self.error}`")
        return "\n\n".join(lines)

    def _status(self, text: str) -> None:
        h = self._gui.get("status") if hasattr(self, "_gui") else None
        if h is not None:
            h.content = text
            h.visible = True

    # ------------------------------------------------------------ findings
    def _run_checks(self, generation: int) -> None:
        robot = self.robot
        try:
            diags, _ = check_robot(robot, CheckOptions(inertia=True))
        except Exception as exc:  # a check that fails must not take the viewer down
            diags, failure = [], f"check failed: {type(exc).__name__}: {exc}"
        else:
            failure = None
        with self.lock:
            if generation != self.generation:
                return
            self.findings = [(d, finding_links(robot, d)) for d in diags]
            self._show_findings(failure)

    def _show_findings(self, failure: str | None) -> None:
        gui = self.server.gui
        counts = {s: sum(1 for d, _ in self.findings if d.severity == s) for s in ("error", "warning", "info")}
        head = failure or (f"{counts['error']} errors, {counts['warning']} warnings, {counts['info']} info "
                           "— click one to highlight its links")
        self._gui["findings_head"].content = head
        with self.server.atomic(), self._gui["findings_folder"]:
            for i, (d, links) in enumerate(self.findings[:MAX_FINDINGS]):
                mark = {"error": "E", "warning": "W", "info": "i"}.get(d.severity, "?")
                text = f"{mark} {d.code} {d.message}"
                label = text if len(text) <= 60 else text[:57] + "..."
                b = gui.add_button(label, hint=f"{d.loc}: {d.severity}: {d.code} {d.message}",
                                   color={"error": "red", "warning": "yellow"}.get(d.severity))
                b.on_click(self._finding_cb(i))
                self._gui["finding_buttons"].append(b)

    def _finding_cb(self, i: int):
        def cb(_event):
            self.select_finding(i)

        return cb

    def select_finding(self, i: int) -> None:
        d, links = self.findings[i]
        self.selected_finding = i
        self.highlight(links)
        detail = self._gui["finding_detail"]
        where = f"`{d.loc}`" if d.loc else "(no location)"
        shown = ", ".join(f"`{n}`" for n in links) if links else "no link named"
        detail.content = f"**{d.severity} {d.code}** {d.message}\n\n{where}\n\nhighlighted: {shown}"
        detail.visible = True
