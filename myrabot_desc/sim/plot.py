"""The run drawn with Pillow: a top view (path, robot footprint, objects) and time series.

Left: the world seen from above, metres, equal scale; the base path (axle
midpoint), the robot's collision outline at evenly spaced times (start green,
end red), scene objects (table, cans) and the path of any moved object.
Right: one panel per unit (joint angles in degrees; speeds in m/s and rad/s).
"""

from __future__ import annotations

import math

W, H = 1400, 700
LEFT = 700
PALETTE = [(31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189), (140, 86, 75),
           (227, 119, 194), (127, 127, 127)]


def _font(size=13):
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:
        return ImageFont.load_default()


def render(res) -> bytes:
    import io

    from PIL import Image, ImageDraw

    img = Image.new("RGB", (W, H), "white")
    d = ImageDraw.Draw(img)
    _top_view(d, res, (10, 30, LEFT - 10, H - 40))
    _series(d, res, (LEFT + 60, 30, W - 20, H - 40))
    title = f"myrabot-desc sim {res.program} · {res.robot} · {res.duration:g} s · " \
            f"{'PASS' if res.passed else 'FAIL'}"
    d.text((10, 6), title, fill=(0, 0, 0), font=_font(15))
    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=False)
    return buf.getvalue()


def _label(v: float, step: float) -> str:
    dec = max(0, -math.floor(math.log10(step))) if step > 0 else 0
    v = round(v / step) * step
    return f"{v:.{dec}f}" if abs(v) > step * 1e-6 else "0"


def _nice_step(span: float) -> float:
    raw = span / 6
    p = 10 ** math.floor(math.log10(raw)) if raw > 0 else 1
    for m in (1, 2, 5, 10):
        if raw <= m * p:
            return m * p
    return 10 * p


def _top_view(d, res, box):
    import numpy as np

    x0, y0, x1, y1 = box
    b = res.base
    xs = [np.asarray(b.axle_x), np.asarray(b.x)]
    ys = [np.asarray(b.axle_y), np.asarray(b.y)]
    fp = np.array(res.outline()) if res.outline() else np.zeros((0, 2))
    n = len(b.t)
    idx = sorted(set(np.linspace(0, n - 1, 9).astype(int).tolist()))
    outlines = []
    for i in idx:
        if not len(fp):
            break
        c, s = math.cos(b.yaw[i]), math.sin(b.yaw[i])
        pts = np.column_stack([b.x[i] + c * fp[:, 0] - s * fp[:, 1], b.y[i] + s * fp[:, 0] + c * fp[:, 1]])
        outlines.append((i, pts))
        xs.append(pts[:, 0])
        ys.append(pts[:, 1])
    for obj in res.scene:
        for kind, data in obj.outline():
            pts = np.asarray(data[0] if kind == "circle" else data)
            if kind == "circle":
                (cx, cy), r = data
                xs.append(np.array([cx - r, cx + r]))
                ys.append(np.array([cy - r, cy + r]))
            else:
                xs.append(pts[:, 0])
                ys.append(pts[:, 1])
    for _, mx, my in res.moving:
        xs.append(np.asarray(mx))
        ys.append(np.asarray(my))
    ax = np.concatenate(xs)
    ay = np.concatenate(ys)
    lo_x, hi_x, lo_y, hi_y = ax.min(), ax.max(), ay.min(), ay.max()
    span = max(hi_x - lo_x, hi_y - lo_y, 0.2) * 1.1
    cx, cy = (lo_x + hi_x) / 2, (lo_y + hi_y) / 2
    scale = min(x1 - x0 - 50, y1 - y0 - 30) / span
    ox, oy = x0 + 50 + (x1 - x0 - 50) / 2, y0 + (y1 - y0 - 30) / 2

    def P(x, y):
        return (ox + (x - cx) * scale, oy - (y - cy) * scale)

    font = _font(11)
    step = _nice_step(span)
    gx = math.floor((cx - span / 2) / step) * step
    while gx <= cx + span / 2:
        px, _ = P(gx, 0)
        if x0 + 50 <= px <= x1:
            d.line([(px, y0), (px, y1 - 30)], fill=(232, 232, 232))
            d.text((px - 12, y1 - 26), _label(gx, step), fill=(90, 90, 90), font=font)
        gx += step
    gy = math.floor((cy - span / 2) / step) * step
    while gy <= cy + span / 2:
        _, py = P(0, gy)
        if y0 <= py <= y1 - 30:
            d.line([(x0 + 50, py), (x1, py)], fill=(232, 232, 232))
            d.text((x0 + 4, py - 6), _label(gy, step), fill=(90, 90, 90), font=font)
        gy += step
    d.text((x1 - 140, y1 - 12), "x (m), top view", fill=(90, 90, 90), font=font)
    for obj in res.scene:
        fill, edge = obj.colour()
        for kind, data in obj.outline():
            if kind == "circle":
                (ccx, ccy), r = data
                (ax_, ay_), (bx_, by_) = P(ccx - r, ccy + r), P(ccx + r, ccy - r)
                d.ellipse([ax_, ay_, bx_, by_], fill=fill, outline=edge)
            else:
                d.polygon([P(*p) for p in data], fill=fill, outline=edge)
    for k, (label, mx, my) in enumerate(res.moving):
        pts = _decimate(mx, my)
        d.line([P(*p) for p in pts], fill=(30, 30, 200) if label != "expected" else (160, 160, 160), width=2)
    for i, pts in outlines:
        colour = (40, 160, 40) if i == 0 else (200, 40, 40) if i == n - 1 else (150, 150, 150)
        d.polygon([P(*p) for p in pts], outline=colour)
        hx, hy = b.x[i] + 0.12 * math.cos(b.yaw[i]), b.y[i] + 0.12 * math.sin(b.yaw[i])
        d.line([P(b.x[i], b.y[i]), P(hx, hy)], fill=colour, width=2)
    d.line([P(*p) for p in _decimate(b.axle_x, b.axle_y)], fill=(0, 0, 0), width=2)
    legend = [((0, 0, 0), "base path (axle midpoint)"), ((40, 160, 40), "robot at start"),
              ((200, 40, 40), "robot at end")]
    for label, *_ in res.moving:
        legend.append(((160, 160, 160), "expected path") if label == "expected"
                      else ((30, 30, 200), f"{label} path"))
    ly = y0 + 2
    for colour, text in legend:
        d.line([(x0 + 60, ly + 7), (x0 + 80, ly + 7)], fill=colour, width=2)
        d.text((x0 + 86, ly), text, fill=(60, 60, 60), font=font)
        ly += 14


def _decimate(x, y, n=2000):
    import numpy as np

    x, y = np.asarray(x), np.asarray(y)
    k = max(1, len(x) // n)
    idx = np.r_[np.arange(0, len(x), k), len(x) - 1]
    return list(zip(x[idx].tolist(), y[idx].tolist()))


def _series(d, res, box):
    import numpy as np

    x0, y0, x1, y1 = box
    groups: dict[str, list] = {}
    for s in res.series:
        groups.setdefault(s.unit, []).append(s)
    if not groups:
        return
    font = _font(11)
    gap = 30
    hpan = (y1 - y0 - gap * (len(groups) - 1)) / len(groups)
    t = np.asarray(res.t)
    tmax = float(t[-1]) or 1.0
    colour_i = 0
    for gi, (unit, items) in enumerate(groups.items()):
        py0 = y0 + gi * (hpan + gap)
        py1 = py0 + hpan
        vals = np.concatenate([np.asarray(s.values, dtype=float) for s in items])
        lo, hi = float(vals.min()), float(vals.max())
        if hi - lo < 1e-9:
            lo, hi = lo - 1, hi + 1
        pad = (hi - lo) * 0.08
        lo, hi = lo - pad, hi + pad
        d.rectangle([x0, py0, x1, py1], outline=(120, 120, 120))

        def P(tt, v):
            return (x0 + tt / tmax * (x1 - x0), py1 - (v - lo) / (hi - lo) * (py1 - py0))

        step = _nice_step(hi - lo)
        g = math.ceil(lo / step) * step
        while g <= hi:
            _, py = P(0, g)
            d.line([(x0, py), (x1, py)], fill=(235, 235, 235))
            d.text((x0 - 55, py - 6), _label(g, step), fill=(90, 90, 90), font=font)
            g += step
        ts = _nice_step(tmax)
        g = 0.0
        while g <= tmax + 1e-9:
            px, _ = P(g, lo)
            d.text((px - 8, py1 + 3), _label(g, ts), fill=(90, 90, 90), font=font)
            g += ts
        d.text((x0 + 4, py0 + 2), unit, fill=(60, 60, 60), font=font)
        ly = py0 + 2
        for s in items:
            colour = PALETTE[colour_i % len(PALETTE)]
            colour_i += 1
            tt = np.asarray(s.t if s.t is not None else t, dtype=float)
            pts = _decimate(tt, np.asarray(s.values, dtype=float), n=1500)
            d.line([P(*p) for p in pts], fill=colour, width=2)
            d.text((x1 - 150, ly), s.label, fill=colour, font=font)
            ly += 14
    d.text((x1 - 60, y1 + 18), "time (s)", fill=(90, 90, 90), font=font)
