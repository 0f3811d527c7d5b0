"""The run drawn with matplotlib (Agg, no display): a top view and the time series in lanes.

Left: the world seen from above, metres on both axes at equal scale; the base path (axle
midpoint), the robot's footprint polygon (its collision outline, convex) at evenly spaced times
(start green, end red), scene objects (table, cans) and the path of any moved object.
Right: one lane per arm joint (degrees), then one lane per other unit (speeds in m/s and rad/s,
pointing errors), sharing the time axis; legends sit outside the data.

matplotlib is imported here only, when a plot is asked for, and only its object API (no pyplot,
no GUI backend).
"""

from __future__ import annotations

import math

W_IN, H_IN, DPI = 14.0, 7.0, 100          # 1400 x 700 pixels
START, END, MIDDLE = "#2ca02c", "#d62728", "#9a9a9a"
MOVES = 0.005                              # m: a path shorter than this is not drawn in the legend
QUANTITY = {"m/s": "speed", "rad/s": "turn rate", "deg": "angle", "rad": "angle", "m": "distance",
            "mm": "distance", "N": "force", "N·m": "torque"}


def render(res) -> bytes:
    """The PNG bytes (same run -> same bytes: no date or version in the metadata)."""
    import io

    buf = io.BytesIO()
    figure(res).savefig(buf, format="png", metadata={"Software": None})
    return buf.getvalue()


def figure(res):
    """The matplotlib Figure: the top view first, then the lanes top to bottom."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(W_IN, H_IN), dpi=DPI)
    FigureCanvasAgg(fig)
    outer = fig.add_gridspec(1, 2, width_ratios=[1.0, 1.15], left=0.06, right=0.88, top=0.91, bottom=0.17,
                             wspace=0.22)
    _top_view(fig.add_subplot(outer[0]), res)
    _lanes(fig, outer[1], res)
    fig.suptitle(f"myrabot-desc sim {res.program} · {res.robot} · {res.duration:g} s · "
                 f"{'PASS' if res.passed else 'FAIL'}", x=0.06, ha="left", fontsize=13)
    return fig


def _decimate(x, y, n=2000):
    import numpy as np

    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    k = max(1, len(x) // n)
    idx = np.r_[np.arange(0, len(x), k), len(x) - 1]
    return x[idx], y[idx]


def _rgb(c):
    return tuple(v / 255 for v in c)


def _top_view(ax, res) -> None:
    import numpy as np
    from matplotlib.patches import Circle, Polygon

    b = res.base
    fp = np.asarray(res.outline() or [], dtype=float).reshape(-1, 2)
    named: set = set()
    for obj in res.scene:                   # the table and the cans, each kind once in the legend
        fill, edge = obj.colour()
        label = None if obj.model in named else obj.model
        named.add(obj.model)
        for kind, data in obj.outline():
            if kind == "circle":
                (cx, cy), r = data
                ax.add_patch(Circle((cx, cy), r, facecolor=_rgb(fill), edgecolor=_rgb(edge), lw=1, zorder=1,
                                    label=label))
            else:
                ax.add_patch(Polygon(np.asarray(data), closed=True, facecolor=_rgb(fill), edgecolor=_rgb(edge),
                                     lw=1, zorder=1, label=label))
            label = None
    for label, mx, my in res.moving:
        x, y = _decimate(mx, my)
        seen = len(x) > 1 and float(np.hypot(np.ptp(x), np.ptp(y))) > MOVES
        ax.plot(x, y, color="#999999" if label == "expected" else "#1f3cc8", lw=1.5, zorder=2,
                label=None if not seen else "expected path" if label == "expected" else f"{label} path")
    n = len(b.t)
    # a base that stays put is one footprint: no start/end pair or path in the legend that no one can see
    still = n < 2 or (float(np.hypot(np.ptp(b.axle_x), np.ptp(b.axle_y))) <= MOVES
                      and float(np.ptp(np.unwrap(b.yaw))) < 0.01)
    idx = sorted(set(np.linspace(0, n - 1, 9).astype(int).tolist()))
    reach = 0.12
    if len(fp):
        reach = float(np.max(np.hypot(fp[:, 0], fp[:, 1]))) * 0.8
    if still:
        idx = idx[-1:]
    for i in idx:
        colour = START if i == 0 else END if i == n - 1 else MIDDLE
        c, s = math.cos(b.yaw[i]), math.sin(b.yaw[i])
        label = "robot at start" if i == 0 else "robot at end" if i == n - 1 else None
        if still:
            colour, label = "#333333", "robot (the base does not move)"
        if len(fp):
            pts = np.column_stack([b.x[i] + c * fp[:, 0] - s * fp[:, 1], b.y[i] + s * fp[:, 0] + c * fp[:, 1]])
            ax.add_patch(Polygon(pts, closed=True, fill=False, edgecolor=colour, lw=1.4 if label else 0.8,
                                 zorder=3, label=label))
        ax.plot([b.x[i], b.x[i] + reach * c], [b.y[i], b.y[i] + reach * s], color=colour, lw=1.4, zorder=3)
    x, y = _decimate(b.axle_x, b.axle_y)
    ax.plot(x, y, color="black", lw=1.8, zorder=4, label=None if still else "base path (axle midpoint)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.08)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("top view", fontsize=11, loc="left")
    ax.grid(True, color="#e6e6e6", lw=0.8)
    ax.set_axisbelow(True)
    # below the axes, never over the path
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize=8, frameon=False)


def _lanes(fig, spec, res) -> None:
    """One lane per arm joint (its own scale), then one per other unit."""
    import numpy as np

    lanes: list[tuple[str, list]] = []
    by_unit: dict[str, list] = {}
    for s in res.series:
        if s.group == "joints" and s.unit == "deg" and s.t is None:
            lanes.append((f"{s.label}\n(deg)", [s]))
        else:
            by_unit.setdefault(s.unit, []).append(s)
    for unit, items in by_unit.items():
        unit = unit.split(" (")[0]             # 'deg (error)': the label says what it is
        # an axis names its quantity and unit: "speed (m/s)", not "m/s"
        what = QUANTITY.get(unit, "value") if len(items) > 1 else items[0].label
        lanes.append((f"{what}\n({unit})", items))
    if not lanes:
        return
    sub = spec.subgridspec(len(lanes), 1, hspace=0.12)
    t = np.asarray(res.t, dtype=float)
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"]
    first = None
    k = 0
    for i, (ylabel, items) in enumerate(lanes):
        ax = fig.add_subplot(sub[i], sharex=first)
        first = first or ax
        for s in items:
            tt = np.asarray(s.t if s.t is not None else t, dtype=float)
            x, y = _decimate(tt, s.values, n=1500)
            ax.plot(x, y, color=colours[k % len(colours)], lw=1.3, label=s.label)
            k += 1
        ax.set_ylabel(ylabel, fontsize=9)
        ax.tick_params(labelsize=8)
        ax.grid(True, color="#ececec", lw=0.8)
        ax.margins(x=0, y=0.15)
        if len(items) > 1:
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False, borderaxespad=0)
        if i < len(lanes) - 1:
            ax.tick_params(labelbottom=False)
        else:
            ax.set_xlabel("time (s)")
        ax.set_xlim(0, float(t[-1]) if len(t) and t[-1] > 0 else 1.0)
