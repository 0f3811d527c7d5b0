"""A physics run drawn with matplotlib (Agg, no display): one lane per series against time (settle,
drive), or, for a sweep, each joint's gravity torque over its effort limit and the deepest
self-collision against its value. matplotlib is imported here only, when a plot is asked for."""

from __future__ import annotations

W_IN, H_IN, DPI = 12.0, 7.0, 100


def render(res) -> bytes:
    """The PNG bytes (same run -> same bytes: no date or version in the metadata)."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(W_IN, H_IN), dpi=DPI)
    FigureCanvasAgg(fig)
    if res.program == "sweep":
        _sweep(fig, res)
    else:
        _lanes(fig, res)
    fig.suptitle(f"myrabot-desc sim {res.program} · {res.robot} · {res.engine} · {'PASS' if res.passed else 'FAIL'}",
                 x=0.06, ha="left", fontsize=13)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})
    return buf.getvalue()


def _lanes(fig, res) -> None:
    joints = [n for n in res.series if n in res.joints]
    names = [n for n in res.series if n not in joints]
    lanes = names + (["joints"] if joints else [])
    axes = fig.subplots(len(lanes), 1, sharex=True, squeeze=False)[:, 0] if lanes else []
    fig.subplots_adjust(left=0.08, right=0.8, top=0.92, bottom=0.08, hspace=0.35)
    for ax, lane in zip(axes, lanes):
        if lane == "joints":
            for n in joints[:12]:
                ax.plot(res.t, res.series[n], lw=1, label=n)
            ax.set_ylabel("joints")
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
        else:
            ax.plot(res.t, res.series[lane], lw=1.2)
            ax.set_ylabel(lane, fontsize=8)
        ax.grid(alpha=0.3)
    if len(axes):
        axes[-1].set_xlabel("time (s)")


def _sweep(fig, res) -> None:
    rows = res.table
    joints = list(dict.fromkeys(r["joint"] for r in rows))
    ax1, ax2 = fig.subplots(2, 1, sharex=False)
    fig.subplots_adjust(left=0.08, right=0.78, top=0.92, bottom=0.08, hspace=0.3)
    for j in joints[:16]:
        mine = [r for r in rows if r["joint"] == j]
        xs = [r["value"] for r in mine]
        ax1.plot(xs, [r["worst_torque_ratio"] for r in mine], lw=1, label=j)
        ax2.plot(xs, [r["deepest_mm"] for r in mine], lw=1, label=j)
    ax1.axhline(1.0, color="#d62728", lw=0.8)
    ax1.set_ylabel("gravity torque / effort (worst joint)")
    ax2.set_ylabel("deepest self-collision (mm)")
    ax2.set_xlabel("joint value (rad or m)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    ax1.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
