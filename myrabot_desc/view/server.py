"""``myrabot-desc view``: the robot in a local web viewer (viser), with joint sliders and diagnosis overlays.

The model, its scene (``view.scene``) and ``check``'s findings are the server's, read once per
(re)load. Everything a person changes in the page is their own: each browser tab is a
:class:`Session` with its own joint values, toggles and highlighted finding, drawn into that
client's own scene and panel (viser's per-client API), so one tab's sliders never move another's
robot. A session is built in steps so that the page is usable early: the panel (sliders first),
then the visual geometry in batches, each mesh decimated for the browser above a triangle budget
(``view.decimate``; the PNG and the checks keep the full meshes); an overlay (frames, names,
inertia boxes...) is built the first time it is switched on. With ``--watch`` the model is reloaded
when one of its files changes, and every session keeps its joint values and toggles.

Model text (robot, link and joint names, mesh file names, finding messages) is untrusted: it
reaches the page only as plain text or escaped Markdown (``view.text``). The server answers only
requests from its own page (``view.guard``: foreign ``Origin``/``Host`` refused, malformed
websocket frames ignored).
"""

from __future__ import annotations

import threading
import time

from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.errors import InputError
from myrabot_desc.model.kinematics import require_tree
from myrabot_desc.view import guard, overlays
from myrabot_desc.view.decimate import browser_parts
from myrabot_desc.view.overlays import finding_links
from myrabot_desc.view.scene import build_scene
from myrabot_desc.view.text import md, md_code, md_code_block, visible

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
BATCH_TRIANGLES = 60_000        # visual geometry goes out in batches of about this many triangles


class Viewer:
    """The server, the loaded model (robot, scene, findings) and the browser sessions.

    ``sessions`` maps a client id to its :class:`Session`. With ``shared=True`` there is one
    session drawn into the server's scene, seen by every client (a library user driving the view
    from Python; the tests without a browser). Attributes a session has (``q``, ``toggles``,
    ``link_poses``, ``set_joints``...) read through to the newest session.
    """

    def __init__(self, load, host: str = "127.0.0.1", port: int = 8080, findings: bool = True, label: str = "",
                 shared: bool = False):
        import contextlib
        import io

        self._load = load                       # () -> Robot (raises InputError)
        first = self._read()                    # a bad file stops here, before a server runs
        import viser

        guard.install()
        # viser's banner repeats the address `view` prints once: kept off both streams
        with contextlib.redirect_stdout(io.StringIO()):
            self.server = viser.ViserServer(host=host, port=port, label=label or "myrabot-desc view", verbose=False)
        guard.quiet_loop(self.server)
        # No share button: it would open a tunnel to a public relay; this viewer stays on this machine.
        self.server.gui.configure_theme(show_share_button=False, control_width="large", show_logo=False)
        self.server.scene.set_up_direction("+z")
        self.lock = threading.RLock()
        self.initial_q: dict[str, float] = {}   # what a new session starts from (--joint)
        self.initial_toggles = {k: v[1] for k, v in TOGGLES.items()}
        self.findings: list = []
        self.findings_failure: str | None = None
        self.findings_ready = False
        self.error: str | None = None
        self.with_findings = findings
        self.generation = 0                     # bumped by every (re)load, once the sessions are rebuilt
        self.model_id = 0                       # bumped when a (re)load starts: a stale build stops
        self.sessions: dict = {}
        self._newest = None
        self._stop = threading.Event()
        self.robot = None
        self.scene = None
        self.reload(first)
        if shared:
            self._newest = self.sessions[None] = Session(self, self.server)
            self._newest.build()
        else:
            self.server.on_client_connect(self._connect)
            self.server.on_client_disconnect(self._disconnect)

    # ------------------------------------------------------------ sessions
    def _connect(self, client) -> None:
        s = Session(self, client, client.client_id)
        with self.lock:
            self.sessions[client.client_id] = s
            self._newest = s
        try:
            s.build()
        except Exception:  # the client went away while its scene was being sent
            if self.sessions.get(client.client_id) is s:
                self._disconnect(client)

    def _disconnect(self, client) -> None:
        with self.lock:
            s = self.sessions.pop(client.client_id, None)
            if s is not None and s is self._newest:
                self._newest = next(reversed(self.sessions.values()), None)

    @property
    def session(self):
        """The newest session (None before a browser connects)."""
        return self._newest

    def __getattr__(self, name):
        # q, toggles, link_poses, set_joints... of the newest session (see the class doc)
        if name.startswith("__") or name in ("_newest", "sessions"):
            raise AttributeError(name)
        s = self.__dict__.get("_newest")
        if s is None:
            raise AttributeError(f"{name} (no browser session yet)")
        return getattr(s, name)

    def set_joints(self, values: dict[str, float]) -> None:
        """Joint values for every session, and for the sessions to come (``view --joint``)."""
        with self.lock:
            self.initial_q.update(self.scene.clamp(values))
            sessions = list(self.sessions.values())
        for s in sessions:
            s.set_joints(values)

    def set_toggle(self, name: str, on: bool) -> None:
        with self.lock:
            self.initial_toggles[name] = bool(on)
            sessions = list(self.sessions.values())
        for s in sessions:
            s.set_toggle(name, on)

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
        """(Re)load the model and rebuild every session; on a load error keep what is shown."""

        try:
            robot, scene = loaded or self._read()
        except InputError as exc:
            self.error = str(exc).splitlines()[0]
            for s in list(self.sessions.values()):
                s.status(f"**reload failed**, showing the previous model:\n\n{md_code(self.error)}")
            return False
        with self.lock:
            self.robot, self.scene, self.error = robot, scene, None
            self.browser_parts = browser_parts(scene.parts)
            self.drive, self.wheel_text = overlays.drive_of(robot)
            self.findings, self.findings_failure, self.findings_ready = [], None, False
            self.initial_q = scene.clamp(self.initial_q)
            self._frame_camera()
            self.model_id += 1
            model_id = self.model_id
            sessions = list(self.sessions.values())
        for s in sessions:
            s.build()
        with self.lock:
            self.generation += 1                # after the build: a reader of generation sees the new scene
        if self.with_findings:
            threading.Thread(target=self._run_checks, args=(model_id,), daemon=True).start()
        return True

    def _frame_camera(self) -> None:
        """The first view: the robot in the middle of the part of the canvas the panel leaves free."""
        import numpy as np

        v = self.scene.world_vertices(self.scene.pose(self.initial_q))
        if not len(v):
            return
        lo, hi = v.min(axis=0), v.max(axis=0)
        centre, size = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) or 1.0
        view = np.array([1.0, -0.8, 0.5])
        cam = self.server.initial_camera
        position = centre + view * size * 0.75
        # the panel covers the right of the canvas: look a little right of the robot so that it
        # sits left of the middle, in the free part
        right = np.cross(-view, [0.0, 0.0, 1.0])
        right /= np.linalg.norm(right)
        shift = right * size * 0.18
        cam.look_at = tuple(float(c) for c in centre + shift)
        cam.position = tuple(float(c) for c in position + shift)

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

    # ------------------------------------------------------------ findings
    def _run_checks(self, model_id: int) -> None:
        # let the first page get its sliders and geometry before the check takes the interpreter
        for _ in range(40):
            with self.lock:
                busy = any(not s.ready for s in self.sessions.values())
            if not busy or self._stop.is_set():
                break
            time.sleep(0.1)
        robot = self.robot
        try:
            diags, _ = check_robot(robot, CheckOptions(inertia=True))
        except Exception as exc:  # a check that fails must not take the viewer down
            diags, failure = [], f"check failed: {type(exc).__name__}: {exc}"
        else:
            failure = None
        with self.lock:
            if model_id != self.model_id:
                return
            self.findings = [(d, finding_links(robot, d)) for d in diags]
            self.findings_failure, self.findings_ready = failure, True
            sessions = list(self.sessions.values())
        for s in sessions:
            s.show_findings()


class Session:
    """One browser tab's view: its joint values, toggles, highlight, and the scene and panel nodes
    it was sent. ``target`` is what it draws into: a viser client (its own scene and panel) or
    the server (shared by every client)."""

    def __init__(self, viewer: Viewer, target, client_id=None):
        self.viewer = viewer
        self.server = target                    # .scene, .gui, .atomic(): overlays draw through it
        self.client_id = client_id
        self.lock = threading.RLock()
        self.q: dict[str, float] = dict(viewer.initial_q)
        self.toggles = dict(viewer.initial_toggles)
        self.highlighted: set[str] = set()
        self.selected_finding = None
        self.link_poses: dict = {}
        self.placed_at = 0.0
        self.ready = False                      # the visual geometry went out
        self.model_id = -1                      # of the model last built
        self._quiet = False                     # set_joints moving the sliders: no callback per slider
        self._nodes: dict[str, list] = {}       # group -> scene handles
        self._built: set[str] = set()           # groups whose nodes exist
        self._link_nodes: dict = {}
        self._visuals: dict[str, list] = {}     # link -> [(handle, rgb)]
        self._sliders: dict = {}
        self._gui: dict = {}
        self._findings_shown = -1

    # the model is the viewer's
    robot = property(lambda self: self.viewer.robot)
    scene = property(lambda self: self.viewer.scene)
    findings = property(lambda self: self.viewer.findings)
    drive = property(lambda self: self.viewer.drive)
    wheel_text = property(lambda self: self.viewer.wheel_text)
    error = property(lambda self: self.viewer.error)

    # ------------------------------------------------------------ building
    def build(self) -> None:
        """Send the panel, then the visual geometry in batches, then the overlays that are on."""
        v = self.viewer
        with self.lock:
            self.ready = False
            self.model_id = v.model_id
            self.q = self.scene.clamp(self.q) or dict(v.initial_q)
            self.highlighted, self.selected_finding = set(), None
            sc, gui = self.server.scene, self.server.gui
            sc.reset()
            gui.reset()
            gui.configure_theme(show_share_button=False, control_width="large", show_logo=False)
            sc.set_up_direction("+z")
            # No image-based lighting: with software WebGL (no GPU) viser's environment map keeps
            # the page busy for seconds per object (the sliders did not answer for 15 s); plain
            # lights instead, without shadows
            sc.configure_environment_map(None)
            sc.configure_default_lights(enabled=True, cast_shadow=False)
            sc.add_light_hemisphere("/lights/sky", sky_color=(255, 255, 255), ground_color=(120, 110, 100),
                                    intensity=1.6)
            self._nodes = {k: [] for k in TOGGLES}
            self._built = set()
            self._link_nodes, self._visuals, self._findings_shown = {}, {}, -1
            self.link_poses = {}
            with self.server.atomic():
                self._build_gui(gui)
                overlays.add_links(self, sc)
                self._place()
        self._send_layer("visual")
        with self.lock:
            self.ready = True
            for group, on in self.toggles.items():
                if on and group != "visual":
                    self._ensure(group)
            self._apply_toggles()
        if v.findings_ready:
            self.show_findings()

    def _send_layer(self, layer: str) -> None:
        """The parts of one layer in batches of about BATCH_TRIANGLES triangles (the page draws
        and answers between batches)."""
        parts = [p for p in self.viewer.browser_parts if p.layer == layer]
        batch, count = [], 0
        for p in parts + [None]:
            if p is not None:
                batch.append(p)
                count += len(p.faces)
            if batch and (p is None or count >= BATCH_TRIANGLES):
                with self.lock, self.server.atomic():
                    if self.model_id != self.viewer.model_id:
                        return                  # a reload started over
                    overlays.add_parts(self, self.server.scene, batch)
                    if layer in self._nodes and not self.toggles.get(layer, False):
                        for h in self._nodes[layer][-len(batch):]:
                            h.visible = False
                batch, count = [], 0
        self._built.add(layer)

    def _ensure(self, group: str) -> None:
        """Build a toggle group's nodes the first time it is switched on."""
        if group in self._built:
            return
        if group in ("visual", "collision"):
            self._send_layer(group)
            return
        with self.lock, self.server.atomic():
            overlays.add_group(self, self.server.scene, group)
            self._built.add(group)
            if group in ("com", "support"):
                overlays.update_dynamic(self, self.link_poses)

    def _place(self) -> None:
        """Send the link poses for the current joint values (and what depends on them)."""
        import numpy as np
        import viser.transforms as vtf

        T = self.scene.transforms(self.q)
        prev = self.link_poses
        for link, handle in self._link_nodes.items():
            M = T.get(link)
            if M is None or (link in prev and np.array_equal(prev[link], M)):
                continue                                  # only the links that moved go out
            handle.position = tuple(M[:3, 3])
            handle.wxyz = tuple(vtf.SO3.from_matrix(M[:3, :3]).wxyz)
        self.link_poses = T
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
        with self.lock:
            self.toggles[name] = bool(on)
            if on:
                self._ensure(name)
            with self.server.atomic():
                for h in self._nodes.get(name, ()):
                    h.visible = bool(on)
                if name in ("support", "com"):
                    overlays.update_dynamic(self, self.link_poses)
                box = self._gui.get(f"toggle_{name}")
                if box is not None and box.value != bool(on):
                    self._quiet = True
                    try:
                        box.value = bool(on)
                    finally:
                        self._quiet = False

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

        self._gui = {}
        self._sliders = {}
        r = self.robot
        gui.add_markdown(f"**{md(r.name)}** · {len(r.links)} links · {len(self.scene.joints)} movable joints")
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
            # the rest pose is the model's (every joint at 0, or at its nearer limit): the pose render,
            # MJCF's home and convert's controllers start from
            rest = gui.add_button("rest pose",
                                  hint="every joint at 0, or at its nearer limit when 0 is outside its range")
            rand = gui.add_button("random")

            @rest.on_click
            def _(_):
                self.set_joints(self.scene.rest())

            @rand.on_click
            def _(_):
                self.set_joints({n: random.uniform(rg.lower, rg.upper) for n, rg in self.scene.joints.items()})

            self._gui["values"] = gui.add_markdown(self._values_text())
        with gui.add_folder("Show"):
            for key, (label, _) in TOGGLES.items():
                if key == "wheels" and self.drive is None:
                    continue
                cb = gui.add_checkbox(label, initial_value=self.toggles[key])
                cb.on_update(self._toggle_cb(key))
                self._gui[f"toggle_{key}"] = cb
            # the numbers of the overlays, where the panel cannot hide them
            self._gui["overlay_text"] = gui.add_markdown("", visible=False)
        with gui.add_folder("Findings") as folder:
            self._gui["findings_folder"] = folder
            self._gui["findings_head"] = gui.add_markdown("running `check --inertia`..." if self.viewer.with_findings
                                                          else "findings off (--no-check)")
            self._gui["finding_detail"] = gui.add_markdown("", visible=False)
            self._gui["finding_buttons"] = []

    def overlay_text(self) -> None:
        """The support and wheel numbers in the panel (the 3D labels may sit behind it)."""
        lines = []
        if self.toggles.get("com") and getattr(self, "com", None) and self.com[0] > 0:
            m, c = self.com
            lines.append(f"centre of mass {m:.3g} kg at ({c[0]:.3f}, {c[1]:.3f}, {c[2]:.3f}) m")
        s = getattr(self, "support", None)
        if self.toggles.get("support") and s is not None:
            lines.append(f"centre of mass {'inside' if s.margin > 0 else '**OUTSIDE**'} the support polygon "
                         f"({s.margin * 1000:.0f} mm from its edge)")
        if self.toggles.get("wheels") and self.wheel_text:
            lines += [md(t) for t in self.wheel_text.splitlines()]
        h = self._gui.get("overlay_text")
        if h is not None:
            h.content = "\n\n".join(lines)
            h.visible = bool(lines)

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
            if not self._quiet:
                self.set_toggle(key, bool(event.target.value))
                self.overlay_text()

        return cb

    def _values_text(self) -> str:
        if not self.scene.joints:
            return "no movable joints"
        # in fenced blocks whose fence no name can close, each name on one line (visible escapes)
        args = " ".join(f"{visible(n)}:={self.q.get(n, 0.0):.4g}" for n in self.scene.joints)
        yaml = "\n".join(f"  {visible(n)}: {self.q.get(n, 0.0):.6g}" for n in self.scene.joints)

        return (md_code_block(args) + "\nYAML (`render --pose`):\n"
                + md_code_block(f"joints:\n{yaml}", "yaml"))

    def _status_text(self) -> str:
        lines = [md_code(p) for p in self.scene.problems[:10]]
        if self.error:
            lines.insert(0, f"**reload failed**: {md_code(self.error)}")
        return "\n\n".join(lines)

    def status(self, text: str) -> None:
        h = self._gui.get("status")
        if h is not None:
            h.content = text
            h.visible = True

    # ------------------------------------------------------------ findings
    def show_findings(self) -> None:
        v = self.viewer
        with self.lock:
            if not v.findings_ready or self._findings_shown == v.model_id or "findings_head" not in self._gui:
                return
            self._findings_shown = v.model_id
            gui = self.server.gui
            counts = {s: sum(1 for d, _ in v.findings if d.severity == s) for s in ("error", "warning", "info")}
            head = md(v.findings_failure) if v.findings_failure else (
                f"{counts['error']} errors, {counts['warning']} warnings, {counts['info']} info "
                "— tick one to highlight its links; hover its box for the whole text")
            self._gui["findings_head"].content = head
            with self.server.atomic(), self._gui["findings_folder"]:
                for i, (d, links) in enumerate(v.findings[:MAX_FINDINGS]):
                    mark = {"error": "E", "warning": "W", "info": "i"}.get(d.severity, "?")
                    text = f"{mark} {d.code} {d.message}"
                    label = text if len(text) <= 60 else text[:57] + "..."
                    # a checkbox, not a button: viser shows a checkbox's hint on hover (a button's
                    # it ignores), and the hint holds the whole text; label and hint are plain text
                    b = gui.add_checkbox(label, initial_value=False,
                                         hint=f"{d.loc}: {d.severity}: {d.code} {d.message}")
                    b.on_update(self._finding_cb(i))
                    self._gui["finding_buttons"].append(b)

    def _finding_cb(self, i: int):
        def cb(event):
            if self._quiet:
                return
            if event.target.value:
                self.select_finding(i)
            elif self.selected_finding == i:
                self.selected_finding = None
                self.highlight([])
                self._gui["finding_detail"].visible = False

        return cb

    def select_finding(self, i: int) -> None:
        d, links = self.viewer.findings[i]
        self.selected_finding = i
        self._quiet = True                       # one finding ticked at a time
        try:
            for k, box in enumerate(self._gui.get("finding_buttons", ())):
                if box.value != (k == i):
                    box.value = k == i
        finally:
            self._quiet = False
        self.highlight(links)
        detail = self._gui["finding_detail"]
        where = md_code(str(d.loc)) if d.loc else "(no location)"
        shown = ", ".join(md_code(n) for n in links) if links else "no link named"
        detail.content = f"**{d.severity} {d.code}** {md(d.message)}\n\n{where}\n\nhighlighted: {shown}"
        detail.visible = True
