"""Make the pictures README.md shows (docs/img/*.png), with the commands the README names.

    .venv/bin/python tools/readme_images.py [--only render|view]

render: four `myrabot-desc render` commands. view: the viewer of the bundled robot in headless
Chromium (software WebGL), screenshots with the inertia boxes and the pillar's finding selected,
and with frames, the support polygon and the wheels.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"
CLI = [sys.executable, "-m", "myrabot_desc"]
ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"


def renders() -> None:
    wander = ROOT / "tests" / "fixtures" / "wander_bot"
    jobs = [
        ("myrabot.png", ["--view", "all"]),
        ("myrabot_inertia.png", ["--inertia", "--joint", "arti1=1.0", "--joint", "base=0.6", "--size", "900x900"]),
        ("tiago.png", [str(ERD / "tiago_description" / "robots" / "tiago.urdf"), "--view", "all"]),
        ("wander_bot.png", [str(wander / "urdf" / "robot.xacro"), "-p", f"wander_bot={wander}", "--view", "all",
                            "--frames"]),
    ]
    for name, args in jobs:
        subprocess.run([*CLI, "render", *args, "-o", str(IMG / name)], check=True, cwd=ROOT)


def views() -> None:
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By

    from myrabot_desc.commands.common import ModelInputs as Inputs
    from myrabot_desc.view.server import Viewer

    def shoot(path, panel_to=None):
        if panel_to:             # scroll the panel to a section
            el = d.find_element(By.XPATH, f"//*[normalize-space(text())='{panel_to}']")
            d.execute_script("arguments[0].scrollIntoView({block: 'start'});", el)
        time.sleep(8)
        d.save_screenshot(str(path))

    v = Viewer(Inputs().load, port=0)
    with tempfile.TemporaryDirectory() as tmp:
        o = Options()
        o.binary_location = shutil.which("chromium")
        for a in ("--headless", "--no-sandbox", "--disable-gpu", "--window-size=1400,900", f"--user-data-dir={tmp}",
                  "--hide-scrollbars"):
            o.add_argument(a)
        d = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=o)
        try:
            d.set_window_size(1400, 900)
            d.get(v.url)
            while v.session is None or not v.session.ready or not v.findings_ready:
                time.sleep(0.2)
            time.sleep(4)
            for b in d.find_elements(By.CSS_SELECTOR, ".mantine-Notification-closeButton"):
                b.click()
            s = v.session
            s.set_joints({"arti1": 0.6, "arti2": 0.6})
            s.set_toggle("inertia", True)
            i = next(k for k, (f, links) in enumerate(v.findings) if f.code == "I008" and links == ["e_pilar_link"])
            s.select_finding(i)
            shoot(IMG / "view_inertia.png", panel_to="Findings")
            s.set_toggle("inertia", False)
            s.select_finding(i)
            s.highlight([])
            for group in ("frames", "support", "wheels", "com"):
                s.set_toggle(group, True)
            s.overlay_text()
            shoot(IMG / "view_support.png", panel_to="Show")
        finally:
            d.quit()
            v.stop()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", choices=["render", "view"])
    a = ap.parse_args()
    if a.only in (None, "render"):
        renders()
    if a.only in (None, "view"):
        views()


if __name__ == "__main__":
    main()
