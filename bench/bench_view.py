"""Benchmark of ``render`` and ``view`` (targets: issues 15 and 28), with the real headless Chromium
(software WebGL: no GPU).

    .venv/bin/python bench/bench_view.py [--repeat 5] [--json] [--only usable]

* ``render``: the whole command (``myrabot-desc render -o ...``), a fresh process each time,
  iso view and ``--view all`` (target: 1.5 s).
* ``view`` first frame: a fresh ``myrabot-desc view --port 0`` process; a headless Chromium that is
  already running opens the printed URL; the time from the process start to the first screenshot
  showing the robot (target: 3 s). The URL being printed (server up) is timed too.
* sliders usable: a viewer is started (check running in the background, as ``view`` does), the
  browser opens the page, and from that moment the first joint's slider is dragged as soon as it
  exists, again every 0.1 s, until the server has the new value: the time from opening the page
  to a slider that works. The bundled MYRAbot (target 4 s) and the largest example-robot-data
  humanoid, the Unitree G1 with hands (53 links, 43 joints, 826,000 triangles; target 12 s).
* slider to new pose on screen: the page's own ``arti1`` slider is dragged (Selenium); timed are
  the drag reaching the server and the new poses sent back (server side), and the first screenshot
  that differs (an upper bound: it includes one screenshot's cost, measured alone as well)
  (target: 100 ms).
"""

from __future__ import annotations

import argparse
import io
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "myrabot_desc"]


def stats(xs):
    return {"median": round(statistics.median(xs), 3), "best": round(min(xs), 3), "runs": len(xs)}


def bench_render(repeat):
    out = {}
    with tempfile.TemporaryDirectory() as d:
        for label, args in (("iso", []), ("all", ["--view", "all"])):
            walls, cpus = [], []
            for _ in range(repeat):
                r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
                t0 = time.perf_counter()
                subprocess.run([*CLI, "render", "-o", os.path.join(d, "r.png"), *args], check=True,
                               capture_output=True, cwd=ROOT)
                walls.append(time.perf_counter() - t0)
                r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpus.append(r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime)
            out[label] = stats(walls)
            out[label]["cpu_median"] = round(statistics.median(cpus), 3)   # less sensitive to a busy machine
    return out


def _browser(tmp):
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    o = Options()
    o.binary_location = shutil.which("chromium")
    for a in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--disable-sync",
              "--window-size=1280,800", f"--user-data-dir={tmp}"):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=o)
    d.get("about:blank")
    return d


def _shot(d):
    import numpy as np
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(d.get_screenshot_as_png())).convert("RGB")).astype(int)


def _robot_pixels(img):
    import numpy as np

    region = img[:, : int(img.shape[1] * 0.6)]
    return int((np.abs(region - 255).sum(axis=2) > 40).sum())


def bench_first_frame(repeat):
    urls, frames = [], []
    with tempfile.TemporaryDirectory() as tmp:
        d = _browser(tmp)
        try:
            for _ in range(repeat):
                t0 = time.perf_counter()
                p = subprocess.Popen([*CLI, "view", "--port", "0", "--no-watch"], stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, cwd=ROOT)
                try:
                    url = p.stdout.readline().strip()
                    urls.append(time.perf_counter() - t0)
                    d.get(url)
                    while _robot_pixels(_shot(d)) < 2000:
                        if time.perf_counter() - t0 > 60:
                            raise RuntimeError("no robot on screen after 60 s")
                    frames.append(time.perf_counter() - t0)
                    d.get("about:blank")
                finally:
                    p.terminate()
                    p.wait(timeout=20)
        finally:
            d.quit()
    return {"url_printed_s": stats(urls), "first_frame_s": stats(frames)}


def bench_slider(repeat):
    import numpy as np
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    sys.path.insert(0, str(ROOT / "tests" / "view"))
    from test_viewer_browser import dismiss_notifications, slider, solid

    from myrabot_desc.commands.common import ModelInputs as Inputs
    from myrabot_desc.view.server import Viewer

    v = Viewer(Inputs().load, port=0, findings=False)
    server, screen, shot_cost = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        d = _browser(tmp)
        try:
            d.get(v.url)
            while _robot_pixels(_shot(d)) < 2000:
                pass
            dismiss_notifications(d)
            for _ in range(3):
                t = time.perf_counter()
                _shot(d)
                shot_cost.append(time.perf_counter() - t)
            # the page's own frame rate: software WebGL in headless Chromium on this machine
            intervals = d.execute_async_script("""
                const done = arguments[arguments.length - 1]; const ts = [];
                function tick(t) { ts.push(t); if (ts.length < 40) requestAnimationFrame(tick);
                                   else done(ts.slice(1).map((x, i) => x - ts[i])); }
                requestAnimationFrame(tick);""")
            frame = statistics.median(intervals) / 1000
            thumb = slider(d, "arti1").find_element(By.CSS_SELECTOR, "[role=slider]")
            step = 18
            for i in range(repeat):
                before = _shot(d)
                stamp = v.placed_at         # the browser session's (read through the viewer; not set here)
                t0 = time.perf_counter()
                ActionChains(d, duration=0).click_and_hold(thumb).move_by_offset(step if i % 2 == 0 else -step, 0) \
                    .release().perform()
                t_sent = time.perf_counter()
                w = int(before.shape[1] * 0.6)
                ref = before[::2, :w:2]
                while True:
                    img = _shot(d)           # compared on the canvas, every other pixel: cheap
                    if solid(np.abs(img[::2, :w:2] - ref).sum(axis=2) > 60).sum() > 12:
                        break
                    if time.perf_counter() - t0 > 10:
                        raise RuntimeError("the pose did not change on screen")
                t_screen = time.perf_counter()
                # the callback stamps the time after the poses went out: the screen can show them first
                while v.placed_at == stamp and time.perf_counter() - t_screen < 2:
                    time.sleep(0.005)
                if v.placed_at != stamp:
                    server.append(v.placed_at - t0)
                screen.append(t_screen - t0)
                del t_sent
                time.sleep(0.3)
        finally:
            d.quit()
            v.stop()
    return {"drag_to_poses_sent_s": stats(server), "drag_to_screen_s_upper_bound": stats(screen),
            "one_screenshot_s": stats(shot_cost), "browser_frame_s": round(frame, 4)}


ERD = ("cmeel.prefix", "share", "example-robot-data", "robots")


def humanoid() -> Path | None:
    import sysconfig

    p = Path(sysconfig.get_paths()["purelib"]).joinpath(*ERD, "g1_description", "urdf",
                                                         "g1_29dof_with_hand_rev_1_0.urdf")
    return p if p.is_file() else None


def bench_usable(files, repeat):
    """Seconds from opening the page to a slider whose drag reaches the server, per robot."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    from myrabot_desc.commands.common import ModelInputs as Inputs
    from myrabot_desc.view.server import Viewer

    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        d = _browser(tmp)
        try:
            for label, f in files.items():
                times, loads = [], []
                for _ in range(repeat):
                    t_load = time.perf_counter()
                    v = Viewer(Inputs(files=[str(f)] if f else []).load, port=0)
                    loads.append(time.perf_counter() - t_load)
                    joint = next(iter(v.scene.joints))
                    try:
                        t0 = time.perf_counter()
                        d.get(v.url)
                        while True:
                            if time.perf_counter() - t0 > 120:
                                raise RuntimeError(f"{label}: no working slider after 120 s")
                            s = v.session
                            start = s.q.get(joint) if s is not None else None
                            # the panel's first slider is the first joint's
                            thumbs = d.find_elements(By.XPATH, "//*[@role='slider']")
                            if thumbs and s is not None:
                                try:
                                    ActionChains(d, duration=0).click_and_hold(thumbs[0]).move_by_offset(25, 0) \
                                        .release().perform()
                                except Exception:
                                    pass
                                end = time.perf_counter() + 0.1
                                while time.perf_counter() < end and s.q.get(joint) == start:
                                    time.sleep(0.005)
                                if s.q.get(joint) != start:
                                    times.append(time.perf_counter() - t0)
                                    break
                            else:
                                time.sleep(0.05)
                        d.get("about:blank")
                    finally:
                        v.stop()
                out[label] = stats(times)
                out[label]["model_load_s"] = round(statistics.median(loads), 3)
        finally:
            d.quit()
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--only", choices=["usable"], help="Only the sliders-usable figures.")
    a = ap.parse_args()
    browser = shutil.which("chromium") and shutil.which("chromedriver")
    if a.only == "usable":
        res = {}
    else:
        res = {"render": bench_render(a.repeat)}
        if browser:
            res["view"] = bench_first_frame(max(2, a.repeat // 2))
            res["slider"] = bench_slider(a.repeat)
    if browser:
        files = {"MYRAbot": None}
        if humanoid() is not None:
            files["G1 humanoid"] = humanoid()
        res["usable"] = bench_usable(files, max(3, a.repeat // 2 + 1))
    try:
        res["load_average"] = os.getloadavg()[0]
    except OSError:
        pass
    if a.json:
        print(json.dumps(res, indent=2))
        return
    for label, u in res.get("usable", {}).items():
        target = 4 if label == "MYRAbot" else 12
        print(f"view {label}: sliders usable {u['median']:.2f} s after the page opens (median of {u['runs']}, "
              f"best {u['best']:.2f} s; target {target} s); model loaded in {u['model_load_s']:.2f} s before that")
    if "render" not in res:
        print(f"load average during the run: {res.get('load_average', float('nan')):.1f} (2 cores)")
        return
    r = res["render"]
    print(f"render (whole command, target 1.5 s): iso {r['iso']['median']:.2f} s median "
          f"({r['iso']['best']:.2f} best, {r['iso']['cpu_median']:.2f} s CPU), --view all "
          f"{r['all']['median']:.2f} s ({r['all']['best']:.2f} best, {r['all']['cpu_median']:.2f} s CPU)")
    if "view" in res:
        f = res["view"]
        print(f"view (target 3 s): URL printed {f['url_printed_s']['median']:.2f} s, first frame in Chromium "
              f"{f['first_frame_s']['median']:.2f} s median ({f['first_frame_s']['best']:.2f} best)")
        s = res["slider"]
        print(f"slider (target 0.1 s): drag -> poses sent {s['drag_to_poses_sent_s']['median'] * 1000:.0f} ms, "
              f"drag -> new pose on screen <= {s['drag_to_screen_s_upper_bound']['median'] * 1000:.0f} ms "
              f"(one screenshot alone {s['one_screenshot_s']['median'] * 1000:.0f} ms; the page draws a frame every "
              f"{s['browser_frame_s'] * 1000:.0f} ms)")
    print(f"load average during the run: {res.get('load_average', float('nan')):.1f} (2 cores)")


if __name__ == "__main__":
    main()
