"""view in a real browser: Chromium (Selenium) drives the viewer of the bundled robot.

One viewer (in this process, so the server-side state can be read) and one browser for the module.
Skipped with the reason when Chromium or chromedriver is missing (`make install` installs Debian's).
"""

from __future__ import annotations

import io
import math
import shutil
import time

import numpy as np
import pytest

pytestmark = pytest.mark.browser

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
W, H = 1280, 800


def wait_for(cond, timeout=180.0, every=0.1, what="condition"):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = cond()
        if got is not None and got is not False and (not hasattr(got, "__len__") or isinstance(got, np.ndarray)
                                                     or len(got)):
            return got
        time.sleep(every)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")


@pytest.fixture(scope="module")
def viewer():
    from myrabot_desc.commands.common import ModelInputs as Inputs
    from myrabot_desc.view.server import Viewer

    v = Viewer(Inputs().load, port=0)
    wait_for(lambda: v.findings, what="the check findings")
    yield v
    v.stop()


@pytest.fixture(scope="module")
def browser(viewer, tmp_path_factory):
    if not CHROMIUM or not DRIVER:
        pytest.skip("no chromium/chromedriver installed (Debian: apt-get install chromium chromium-driver)")
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    o = Options()
    o.binary_location = CHROMIUM
    for a in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--disable-sync",
              f"--window-size={W},{H}", f"--user-data-dir={tmp_path_factory.mktemp('chrome')}"):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service(DRIVER), options=o)
    d.set_window_size(W, H)
    d.get(viewer.url)
    wait_for(lambda: viewer.server.get_clients(), what="the browser to connect")
    wait_for(lambda: robot_pixels(shot(d)) > 2000, timeout=300, what="the robot on the canvas")
    dismiss_notifications(d)
    yield d
    d.quit()


def dismiss_notifications(d):
    """Close viser's toasts (\"software WebGL\"): they fade out later and would count as changes."""
    from selenium.webdriver.common.by import By

    for b in d.find_elements(By.CSS_SELECTOR, ".mantine-Notification-closeButton"):
        try:
            b.click()
        except Exception:  # already gone
            pass
    wait_for(lambda: not d.find_elements(By.CSS_SELECTOR, ".mantine-Notification-root"), timeout=60,
             what="the notifications to close")
    time.sleep(0.5)


def shot(d):
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(d.get_screenshot_as_png())).convert("RGB")).astype(int)


def robot_pixels(img) -> int:
    """Pixels of the canvas area (left of the panel) that are not the white background."""
    region = img[:, : int(img.shape[1] * 0.6)]
    return int((np.abs(region - 255).sum(axis=2) > 40).sum())


def solid(mask):
    """Pixels whose four neighbours are set too: a moved part, not the one-pixel edge flicker of
    the software renderer's antialiasing."""
    out = np.zeros_like(mask)
    out[1:-1, 1:-1] = mask[1:-1, 1:-1] & mask[:-2, 1:-1] & mask[2:, 1:-1] & mask[1:-1, :-2] & mask[1:-1, 2:]
    return out


def settled(d, before):
    """A screenshot that differs from ``before`` and equals the next one (the pose finished drawing)."""
    a = shot(d)
    if solid(np.abs(a - before).sum(axis=2) > 60).sum() < 200:
        return None
    time.sleep(0.2)
    b = shot(d)
    return b if np.array_equal(a, b) else None


def magenta(img) -> int:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return int(((r > 180) & (g < 90) & (b > 140)).sum())


def bluer(img, before) -> int:
    """Canvas pixels that turned bluer: the translucent blue boxes over the robot and the background."""
    d = img - before
    return int(solid((d[..., 2] - d[..., 0] > 50))[:, : int(img.shape[1] * 0.6)].sum())


def to_pixel(viewer, p, img):
    """Screen pixel of world point p, from the browser's own camera (OpenCV convention)."""
    import viser.transforms as vtf

    cam = next(iter(viewer.server.get_clients().values())).camera
    R = vtf.SO3(np.asarray(cam.wxyz)).as_matrix()
    pc = R.T @ (np.asarray(p, dtype=float) - np.asarray(cam.position))
    h, w = img.shape[:2]
    f = (h / 2) / math.tan(cam.fov / 2)
    return w / 2 + f * pc[0] / pc[2], h / 2 + f * pc[1] / pc[2]


def slider(d, label):
    from selenium.webdriver.common.by import By

    return d.find_element(By.XPATH, f"//*[normalize-space(text())='{label}']/ancestor::div"
                                    f"[.//*[contains(@class,'mantine-Slider-root')]][1]"
                                    f"//*[contains(@class,'mantine-Slider-root')]")


def click_text(d, text, tag="*"):
    from selenium.webdriver.common.by import By

    el = d.find_element(By.XPATH, f"//{tag}[contains(normalize-space(.), \"{text}\") and not(.//{tag}"
                                  f"[contains(normalize-space(.), \"{text}\")])]")
    d.execute_script("arguments[0].scrollIntoView({block: 'center'});", el)
    el.click()
    return el


def test_first_frame_shows_the_robot(browser, viewer):
    img = shot(browser)
    assert robot_pixels(img) > 2000
    assert viewer.q.get("arti1") == 0.0


def test_slider_moves_the_arm(browser, viewer):
    from selenium.webdriver.common.action_chains import ActionChains

    before_img = shot(browser)
    from selenium.webdriver.common.by import By

    before = viewer.link_poses["antebrazo_link"].copy()
    base = viewer.link_poses["base_link"].copy()

    track = slider(browser, "arti1")
    thumb = track.find_element(By.CSS_SELECTOR, "[role=slider]")
    # drag the page's own slider from the middle to 80 % of its track (range +-2.62 rad)
    width = track.size["width"]
    ActionChains(browser).click_and_hold(thumb).move_by_offset(int(width * 0.3), 0).release().perform()
    # the drag may go out as several moves: wait for the value where the thumb was let go
    wait_for(lambda: abs(viewer.q["arti1"] - 0.6 * 2.62) < 0.35, what="arti1 to reach ~1.57 rad on the server")
    time.sleep(0.3)
    after = viewer.link_poses["antebrazo_link"]
    assert np.array_equal(viewer.link_poses["base_link"], base)      # only the arm moved
    moved = np.linalg.norm(after[:3, 3] - before[:3, 3])
    assert moved > 0.02                                  # the forearm swung by centimetres
    # the picture changed where the arm is, and not at the wheels; wait for it to settle
    img = wait_for(lambda: settled(browser, before_img), what="the browser to draw the new pose")
    changed = solid(np.abs(img - before_img).sum(axis=2) > 60)
    ys, xs = np.nonzero(changed)
    ax, ay = to_pixel(viewer, after[:3, 3], img)
    bx, by = to_pixel(viewer, before[:3, 3], img)
    # the change surrounds the forearm's old and new places
    canvas = xs < 0.6 * img.shape[1]                     # the panel's slider moved too
    near = (np.abs(xs - (ax + bx) / 2) < 150) & (np.abs(ys - (ay + by) / 2) < 150)
    assert near[canvas].mean() > 0.9, (near[canvas].mean(), (ax, ay), (bx, by))
    wx, wy = to_pixel(viewer, viewer.link_poses["left_wheel_link"][:3, 3], img)
    assert not changed[int(wy) - 10:int(wy) + 10, int(wx) - 10:int(wx) + 10].any()


def test_inertia_boxes_toggle(browser, viewer):
    before = shot(browser)
    click_text(browser, "inertia boxes", tag="label")
    wait_for(lambda: viewer.toggles["inertia"], what="the inertia toggle on the server")
    img = wait_for(lambda: (lambda im: im if bluer(im, before) > 3000 else None)(shot(browser)),
                   what="blue inertia boxes on the canvas")
    # the pillar's box (its inertia is ~3x too large for its mesh) shows around the pillar
    px, py = to_pixel(viewer, viewer.link_poses["e_pilar_link"][:3, 3], img)
    d = img - before
    ys, xs = np.nonzero(solid(d[..., 2] - d[..., 0] > 50)[:, : int(img.shape[1] * 0.6)])
    assert abs(np.median(xs) - px) < 150
    click_text(browser, "inertia boxes", tag="label")
    wait_for(lambda: not viewer.toggles["inertia"], what="the inertia toggle off")
    wait_for(lambda: (lambda im: im if bluer(im, before) < 500 else None)(shot(browser)),
             what="the inertia boxes to go")


def test_finding_click_highlights_its_link(browser, viewer):
    idx = next(i for i, (d, links) in enumerate(viewer.findings) if links == ["e_pilar_link"])
    d, _ = viewer.findings[idx]
    before = shot(browser)
    click_text(browser, f"{d.code} link e_pilar_link", tag="label")
    wait_for(lambda: viewer.highlighted == {"e_pilar_link"}, what="the highlight on the server")
    assert viewer.selected_finding == idx
    img = wait_for(lambda: (lambda im: im if magenta(im) > magenta(before) + 3000 else None)(shot(browser)),
                   what="the highlighted pillar on the canvas")
    px, py = to_pixel(viewer, viewer.link_poses["e_pilar_link"][:3, 3], img)
    ys, xs = np.nonzero((img[..., 0] > 180) & (img[..., 1] < 90) & (img[..., 2] > 140))
    assert abs(np.median(xs) - px) < 120 and abs(np.median(ys) - py) < 250
    # the detail names the file:line of the finding
    from selenium.webdriver.common.by import By

    assert str(d.loc) in browser.find_element(By.TAG_NAME, "body").text
    # hovering the finding's box shows its whole text (the label is cut at 60 characters)
    from selenium.webdriver.common.action_chains import ActionChains

    text = f"{d.code} link e_pilar_link"
    label = browser.find_element(By.XPATH, f"//label[contains(normalize-space(.), \"{text}\")]")
    box = label.find_element(By.XPATH, "./ancestor::div[.//input[@type='checkbox']][1]//input[@type='checkbox']")
    ActionChains(browser).move_to_element(box).perform()
    tip = wait_for(lambda: [t for t in browser.find_elements(By.CSS_SELECTOR, "[role=tooltip]") if t.text],
                   what="the tooltip")
    assert d.message in tip[0].text


# ---------------------------------------------------------------- sessions and security
def _chrome(tmp_path_factory):
    if not CHROMIUM or not DRIVER:
        pytest.skip("no chromium/chromedriver installed (Debian: apt-get install chromium chromium-driver)")
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    o = Options()
    o.binary_location = CHROMIUM
    for a in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--disable-sync",
              f"--window-size={W},{H}", f"--user-data-dir={tmp_path_factory.mktemp('chrome')}"):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service(DRIVER), options=o)
    d.set_window_size(W, H)
    return d


def test_two_sessions_keep_separate_toggles_and_joints(browser, viewer, tmp_path_factory):
    """A second tab is a session of its own: switching an overlay on or moving a joint there changes
    nothing in the first tab (server state and pixels)."""
    first = viewer.session
    other = _chrome(tmp_path_factory)
    try:
        other.get(viewer.url)
        second = wait_for(lambda: viewer.session if viewer.session is not first and viewer.session.ready else None,
                          timeout=300, what="the second tab's session")
        assert len(viewer.sessions) == 2
        wait_for(lambda: robot_pixels(shot(other)) > 2000, timeout=300, what="the robot in the second tab")
        dismiss_notifications(other)
        before_first = shot(browser)
        before_second = shot(other)
        click_text(other, "inertia boxes", tag="label")
        wait_for(lambda: second.toggles["inertia"], what="the toggle in the second session")
        wait_for(lambda: (lambda im: im if bluer(im, before_second) > 3000 else None)(shot(other)),
                 what="blue boxes in the second tab")
        second.set_joints({"arti1": 1.2})
        time.sleep(1.0)
        assert first.toggles["inertia"] is False and first.q.get("arti1") != 1.2
        assert bluer(shot(browser), before_first) < 500        # the first tab shows no box
    finally:
        other.quit()
    wait_for(lambda: len(viewer.sessions) == 1, what="the second session to end with its tab")


EVIL = """<?xml version="1.0"?>
<robot name="evil&lt;iframe srcdoc=&quot;&lt;script&gt;parent.document.title='PWNED'&lt;/script&gt;&quot;&gt;&lt;/iframe&gt;">
  <link name="base">
    <visual><geometry><mesh filename="a`b&lt;img src=x onerror=&quot;document.title='PWNED3'&quot;&gt;.stl"/></geometry></visual>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="0.004" iyy="0.004" izz="0.007" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="arm"><visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></visual>
    <inertial><mass value="0.5"/><inertia ixx="0.0068" iyy="0.0068" izz="0.0002" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j&#10;```&#10;&lt;img src=x onerror=&quot;document.title='PWNED2'&quot;&gt;&#10;```" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_model_text_cannot_run_script_in_the_page(tmp_path, tmp_path_factory):
    """The three injection points of a hostile model (an <iframe srcdoc> in the robot name, a
    backtick and an <img onerror> in a mesh file name, a newline and a code fence in a joint name)
    reach the page as text: no element is made from them and no script runs."""
    from selenium.webdriver.common.by import By

    from myrabot_desc.commands.common import ModelInputs as Inputs
    from myrabot_desc.view.server import Viewer

    f = tmp_path / "evil.urdf"
    f.write_text(EVIL)
    v = Viewer(Inputs(files=[str(f)]).load, port=0)
    d = _chrome(tmp_path_factory)
    try:
        d.get(v.url)
        s = wait_for(lambda: v.session if v.session is not None and v.session.ready else None, timeout=300,
                     what="the session")
        wait_for(lambda: v.findings_ready, timeout=300, what="the findings")
        body = wait_for(lambda: (lambda t: t if "M001" in t else None)(d.find_element(By.TAG_NAME, "body").text),
                        timeout=300, what="the findings in the panel")
        click_text(d, "M001", tag="label")                    # its detail is Markdown with the mesh name
        wait_for(lambda: s.selected_finding is not None, what="the finding selected")
        time.sleep(1.5)
        body = d.find_element(By.TAG_NAME, "body").text
        assert "<iframe srcdoc=" in body                     # the robot name, shown as text
        assert "a`b<img src=x" in body                        # the mesh file name, shown as text
        assert "j\\n```\\n<img src=x" in body                 # the joint name, one visible line
        assert d.title != "PWNED" and "PWNED" not in d.title
        assert d.find_elements(By.TAG_NAME, "iframe") == []
        assert not [i for i in d.find_elements(By.TAG_NAME, "img") if (i.get_attribute("src") or "").endswith("/x")]
    finally:
        d.quit()
        v.stop()
