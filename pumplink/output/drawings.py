"""The linkage drawing (to scale, dimensioned) and its animation over one revolution.

Renderers only: every position, path and length comes from :mod:`pumplink.studies.drawing`.  matplotlib
through the one loader :func:`pumplink.output.charts.pyplot`.
"""

from __future__ import annotations

import math
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from pumplink.errors import SpecError
from pumplink.output.charts import check_path, fit_text, pyplot, save
from pumplink.output.formats import atomic_write, check_output

MM_PER_INCH = 25.4
#: The drawing sheet: A4 landscape [mm], the drawing area on it (left, bottom, width, height) [mm]
#: and the side panel.
SHEET_MM = (297.0, 210.0)
AREA_MM = (8.0, 8.0, 205.0, 194.0)
PANEL_MM = (218.0, 8.0, 72.0, 194.0)
#: Drawing scales offered, 1:n (the largest that fits is used).
SCALES = (1, 2, 2.5, 5, 10, 20, 25, 50, 100, 200, 500)
#: Colour, line style and short key of each pose, in the order of ``Drawing.poses``.
POSE_STYLE = (("C0", "-", "extended"), ("C3", "-", "folded"), ("C2", "--", "peak"))
ANIMATION_SUFFIXES = (".gif",)


def drawing_scale(extent, area_mm=AREA_MM) -> float:
    """The largest standard scale 1:n at which ``extent`` (xmin, xmax, ymin, ymax) [m] fits."""
    w, h = (extent[1] - extent[0]) * 1000.0, (extent[3] - extent[2]) * 1000.0
    for n in SCALES:
        if w / n <= area_mm[2] and h / n <= area_mm[3]:
            return float(n)
    raise SpecError(f"the linkage ({w:.0f} x {h:.0f} mm) does not fit an A4 sheet even at 1:{SCALES[-1]}")


def _axes_mm(fig, rect_mm):
    W, H = SHEET_MM
    left, bottom, w, h = rect_mm
    return fig.add_axes((left / W, bottom / H, w / W, h / H))


#: The mean width of a label's character [em]: a label longer than its dimension line on paper
#: is written beyond the line's end.
LABEL_CHAR_WIDTH = 0.6


def _paper_pt(ax, length) -> float:
    """A length in data units [m] as drawn on the figure [pt]."""
    fig = ax.figure
    box = ax.get_position()
    span = ax.get_xlim()[1] - ax.get_xlim()[0]
    return float(length) / span * box.width * fig.get_figwidth() * 72.0


def _dimension(ax, dim, fs=6.5):
    s, e = np.asarray(dim.start, float), np.asarray(dim.end, float)
    if dim.kind == "horizontal":
        p0, p1 = np.array([s[0], dim.line]), np.array([e[0], dim.line])
    elif dim.kind == "vertical":
        p0, p1 = np.array([dim.line, s[1]]), np.array([dim.line, e[1]])
    else:
        u = (e - s) / np.hypot(*(e - s))
        n = np.array([-u[1], u[0]])
        p0, p1 = s + dim.line * n, e + dim.line * n
    for a, b in ((s, p0), (e, p1)):
        if np.hypot(*(b - a)) > 0:
            ax.plot([a[0], b[0]], [a[1], b[1]], color="0.55", lw=0.4, zorder=1)
    ax.annotate(
        "",
        xy=p1,
        xytext=p0,
        arrowprops=dict(arrowstyle="<|-|>", lw=0.5, color="0.25", mutation_scale=6, shrinkA=0, shrinkB=0),
        zorder=2,
    )
    d = p1 - p0
    ang = math.degrees(math.atan2(d[1], d[0]))
    if ang > 90.0:
        ang -= 180.0
    elif ang <= -90.0:
        ang += 180.0
    mid, ha = 0.5 * (p0 + p1), "center"
    text = f"{dim.label} = {dim.value * 1000:.1f} mm"
    if not np.any(s) and len(text) * LABEL_CHAR_WIDTH * fs > _paper_pt(ax, np.hypot(*d)):
        # a length from the axle (the crank, the wheel's radius) whose label is longer than its
        # line: written beyond the line's end, clear of the axle where the other labels are
        mid, ha = p1, ("left" if d[0] >= 0 else "right")
    ax.annotate(
        text,
        mid,
        xytext=(-1.8 * math.sin(math.radians(ang)), 1.8 * math.cos(math.radians(ang))),
        textcoords="offset points",
        rotation=ang,
        rotation_mode="anchor",
        ha=ha,
        va="bottom",
        fontsize=fs,
        color="0.15",
        zorder=6,
        bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.8),
    )


def _pose(ax, pose, colour, ls, key, lw=2.2, alpha=1.0, gid=True):
    o2, a, b, o4, p = pose.joints
    lines = []
    for name, (u, v), w in (("crank", (o2, a), lw * 1.3), ("coupler", (a, b), lw), ("handle", (o4, p), lw)):
        (ln,) = ax.plot([u[0], v[0]], [u[1], v[1]], color=colour, ls=ls, lw=w, alpha=alpha, zorder=4)
        if gid:
            ln.set_gid(f"{key}-{name}")
        lines.append(ln)
    (j,) = ax.plot(
        pose.joints[:4, 0],
        pose.joints[:4, 1],
        "o",
        ms=3.5,
        mfc="white",
        mec=colour,
        mew=1,
        zorder=5,
        alpha=alpha,
    )
    return lines + [j]


def _static(ax, dr, plt, dims=True):
    """What every view shows: ground, stand, wheel, pivots, paths, the poses, the rotation sense."""
    x0, x1, y0, y1 = dr.extent
    rw, b = dr.wheel_radius, dr.stand_width
    o4 = dr.poses[0].joint("O4")
    if dr.axle_height is not None:
        g = -dr.axle_height
        ax.plot([x0, x1], [g, g], color="k", lw=1.2, zorder=2)
        step = (x1 - x0) / 60
        for x in np.arange(x0, x1, step):
            ax.plot([x, x - step], [g, g - step], color="k", lw=0.4, zorder=2)
        ax.text(x0 + 2 * step, g + 0.5 * step, "ground", fontsize=7, va="bottom")
    for x in (-b / 2, b / 2):  # the stand's posts, up to the axle
        ax.plot([x, x], [dr.stand_bottom, 0.0], color="0.45", lw=2.5, solid_capstyle="butt", zorder=2)
    ax.plot([-b / 2, b / 2], [0.0, 0.0], color="0.45", lw=2.5, zorder=2)
    ax.add_patch(plt.Circle((0, 0), rw, fill=False, color="0.35", lw=1.0, zorder=2))
    ax.plot([-1.15 * rw, 1.15 * rw], [0, 0], color="0.5", lw=0.4, ls="-.", zorder=1)
    ax.plot([0, 0], [-1.15 * rw, 1.15 * rw], color="0.5", lw=0.4, ls="-.", zorder=1)
    ax.plot([o4[0], 0.0], [o4[1], 0.0], color="0.5", lw=0.6, ls="-.", zorder=1)  # the frame O2-O4
    tri = 0.035 * rw / 0.25
    ax.add_patch(
        plt.Polygon(
            [[o4[0], o4[1]], [o4[0] - tri, o4[1] - 1.5 * tri], [o4[0] + tri, o4[1] - 1.5 * tri]],
            closed=True,
            fc="0.8",
            ec="0.3",
            lw=0.8,
            zorder=3,
        )
    )
    ax.plot(dr.coupler_path[:, 0], dr.coupler_path[:, 1], color="0.5", lw=0.6, ls=":", zorder=1)
    (gp,) = ax.plot(dr.grip_path[:, 0], dr.grip_path[:, 1], color="C1", lw=1.2, ls=":", zorder=3)
    gp.set_gid("grip-path")
    # The swing Δθ at O4, symmetric about the vertical.
    h = float(np.hypot(*(dr.poses[0].joint("P") - o4)))
    r = 0.3 * h
    half = math.degrees(dr.swing) / 2
    from matplotlib.patches import Arc

    ax.add_patch(Arc(o4, 2 * r, 2 * r, theta1=90 - half, theta2=90 + half, color="C1", lw=0.8, zorder=3))
    ax.plot([o4[0], o4[0]], [o4[1], o4[1] + 1.1 * r], color="C1", lw=0.5, ls="--", zorder=3)
    ax.text(
        o4[0],
        o4[1] + 1.12 * r,
        f"Δθ = {math.degrees(dr.swing):g}°",
        color="C1",
        fontsize=7,
        ha="center",
        va="bottom",
    )
    # The rotation sense: an arrow on an arc outside the wheel, counter-clockwise for rotation +1.
    t = np.radians(np.linspace(20, 70, 30)) if dr.rotation > 0 else np.radians(np.linspace(70, 20, 30))
    rr = 1.12 * rw
    ax.plot(rr * np.cos(t[:-1]), rr * np.sin(t[:-1]), color="k", lw=0.9, zorder=3)
    ax.annotate(
        "",
        xy=(rr * np.cos(t[-1]), rr * np.sin(t[-1])),
        xytext=(rr * np.cos(t[-3]), rr * np.sin(t[-3])),
        arrowprops=dict(arrowstyle="-|>", color="k", lw=0.9, mutation_scale=8),
    )
    ax.text(rr * 1.04 * math.cos(math.radians(45)), rr * 1.04 * math.sin(math.radians(45)), "ω", fontsize=9)


def linkage_drawing(dr, path) -> tuple[Path, float]:
    """The linkage on an A4 landscape sheet, to scale, at its dead centres (and peak position).

    Parameters
    ----------
    dr : :class:`pumplink.studies.drawing.Drawing`.
    path : output file (.png, .svg, .pdf).

    Returns
    -------
    The path and the scale n of 1:n.
    """
    path = check_path(path)
    plt = pyplot()
    n = drawing_scale(dr.extent)
    W, H = SHEET_MM
    fig = plt.figure(figsize=(W / MM_PER_INCH, H / MM_PER_INCH))
    ax = _axes_mm(fig, AREA_MM)
    # 1 m of linkage = 1000/n mm of paper: the limits span the area's size times n.
    x0, x1, y0, y1 = dr.extent
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    hw, hh = AREA_MM[2] * n / 2000.0, AREA_MM[3] * n / 2000.0
    ax.set_xlim(cx - hw, cx + hw)
    ax.set_ylim(cy - hh, cy + hh)
    ax.set_axis_off()
    fig.patches.append(
        plt.Rectangle((4 / W, 4 / H), 1 - 8 / W, 1 - 8 / H, transform=fig.transFigure, fill=False, lw=0.8)
    )
    _static(ax, dr, plt)
    for pose, (colour, ls, key) in zip(dr.poses, POSE_STYLE):
        _pose(ax, pose, colour, ls, key)
    ext = dr.poses[0]
    for name in ("O2", "A", "B", "O4", "P"):
        x, y = ext.joint(name)
        at = dict(xytext=(4, 3))
        if name == "O2":  # above the axle, on the wheel's centre line, where no link is drawn
            at = dict(xytext=(2, 5), ha="left", va="bottom")
        elif name == "A":  # beyond the crank pin, away from the axle (a short crank's labels met)
            u = ext.joint("A") / max(float(np.hypot(*ext.joint("A"))), 1e-12)
            at = dict(xytext=(6 * u[0], 6 * u[1] + 2), ha="left" if u[0] >= 0 else "right", va="bottom")
        ax.annotate(name, (x, y), textcoords="offset points", fontsize=7, color="C0", zorder=7, **at)
    for dim in dr.dimensions:
        _dimension(ax, dim)

    panel = _axes_mm(fig, PANEL_MM)
    panel.set_axis_off()
    panel.set(xlim=(0, 1), ylim=(0, 1))
    # the name: wrapped (at most three lines; a longer one loses its middle) inside the page border
    title = panel.text(0.0, 0.98, "", fontsize=11, weight="bold", va="top")
    fit_text(title, dr.name, lambda name: name, PANEL_MM[2] / W, lines=3)
    top = title.get_window_extent(fig.canvas.get_renderer()).transformed(panel.transAxes.inverted()).y0
    lines = [
        (f"scale 1:{n:g} on A4 (print at 100 %)", 8, "normal"),
        ("", 6, "normal"),
    ]
    for pose, (colour, ls, _) in zip(dr.poses, POSE_STYLE):
        entry = f"{'—' if ls == '-' else '- -'} {pose.label}, θ2 = {math.degrees(pose.crank_angle):.2f}°"
        lines += [(t, 7.5, colour) for t in textwrap.wrap(entry, 46, subsequent_indent="   ")]
    lines += [
        ("··· grip path (one revolution)", 7.5, "C1"),
        ("", 6, "normal"),
        ("the wheel turns counter-clockwise (ω)", 7.5, "normal"),
        ("O2 axle, A crank pin, B coupler-rocker", 7.5, "normal"),
        ("joint, O4 rocker pivot, P grip", 7.5, "normal"),
        (
            "ground: axle height not given"
            if dr.axle_height is None
            else f"ground {dr.axle_height * 1000:.0f} mm below the axle",
            7.5,
            "normal",
        ),
        ("", 6, "normal"),
        ("links (joint centres):", 8, "bold"),
    ]
    for p in dr.parts:
        lines.append((f"{p.name}: {p.centre_distance * 1000:.1f} mm", 7.5, "normal"))
    handle = dr.parts[-1]
    lines.append((f"grip at H = {handle.end * 1000:.1f} mm from O4", 7.5, "normal"))
    y = top - 0.015
    for text, size, style in lines:
        colour = style if style.startswith("C") else "k"
        weight = "bold" if style == "bold" else "normal"
        panel.text(0.0, y, text, fontsize=size, color=colour, weight=weight, va="top")
        y -= 0.045 if text else 0.02
    panel.text(0.0, 0.0, "pumplink draw", fontsize=6, color="0.5", va="bottom")
    save(fig, path, dpi=150)
    plt.close(fig)
    return path, n


def check_animation_path(path) -> Path:
    """Validate an animation path's extension before any work is done."""
    path = Path(path)
    if path.suffix.lower() not in ANIMATION_SUFFIXES:
        raise SpecError(
            f"--animate {path}: unknown animation type '{path.suffix}'; use a file ending in .gif"
        )
    return check_output(path, "--animate")


def arrow_lengths(force, cap: float) -> np.ndarray:
    """The force arrow's signed length in newtons at each frame: the force, at most ``cap``
    (an infinite or NaN force, at a dead centre, drawn at ``cap`` pointing +x)."""
    f = np.asarray(force, float)
    finite = np.isfinite(f)
    shown = np.where(finite, np.minimum(np.abs(f), cap), cap)
    return np.where(finite & (f < 0), -shown, shown)


def animation(dr, mo, path, fps: int = 12) -> Path:
    """One revolution of the linkage, one frame per crank step, with the operator's force at the grip.

    The arrow's length is the force: the force limit is drawn as 30 % of the handle length;
    forces beyond three times the limit (the quasi-static force near a dead centre) are drawn at
    that length and marked.  The frames nearest the dead centres say so.

    Parameters
    ----------
    dr : :class:`pumplink.studies.drawing.Drawing` (the static scene).
    mo : :class:`pumplink.studies.drawing.Motion` (the frames).
    path : output .gif (Pillow, through matplotlib's PillowWriter).
    """
    path = check_animation_path(path)
    plt = pyplot()
    try:
        from matplotlib.animation import FuncAnimation, PillowWriter
    except ImportError:  # pragma: no cover - matplotlib always ships it
        raise SpecError(
            "the animation needs matplotlib's PillowWriter; pip install 'pumplink[plot]'"
        ) from None
    try:
        import PIL  # noqa: F401
    except ImportError:
        raise SpecError(
            "the GIF animation needs Pillow, which is not installed; pip install pillow"
        ) from None
    h = float(np.hypot(*(dr.poses[0].joint("P") - dr.poses[0].joint("O4"))))
    per_newton = 0.3 * h / mo.force_limit  # [m/N]
    cap = 3.0 * mo.force_limit
    lengths = arrow_lengths(mo.force, cap) * per_newton
    tips = mo.joints[:, 4, 0] + lengths
    x0, x1, y0, y1 = dr.extent
    # wide enough for the arrow at every frame, its head too (the longest arrows point out of the
    # grip's path at the dead centres, the frame's edges)
    pad = 0.04 * (max(x1, tips.max()) - min(x0, tips.min()))
    x0, x1 = min(x0, float(tips.min()) - pad), max(x1, float(tips.max()) + pad)
    fig = plt.figure(figsize=(6.4, 6.4 * (y1 - y0) / (x1 - x0) + 0.5), dpi=80)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96 * (y1 - y0) / ((y1 - y0) + 0.5 * (x1 - x0) / 6.4)))
    ax.set(xlim=(x0, x1), ylim=(y0, y1))
    ax.set_aspect("equal")
    ax.set_axis_off()
    _static(ax, dr, plt)
    for pose, (_, _, key) in zip(dr.poses[:2], POSE_STYLE):
        _pose(ax, pose, "0.75", "-", key, lw=1.2, gid=False)
        x, y = pose.joint("P")
        ax.text(x, y, f" {key} dead centre", fontsize=7, color="0.45", ha="center", va="bottom")
    moving = _pose(ax, dr.poses[0], "C0", "-", "frame", gid=False)
    (arrow,) = ax.plot([], [], color="C3", lw=2.5, zorder=8, gid="force-arrow")
    (head,) = ax.plot([], [], marker=">", color="C3", ms=8, zorder=8, gid="force-arrow-head")
    text = fig.text(0.02, 0.99, "", fontsize=9, va="top", family="monospace")
    fig.text(0.98, 0.99, f"model: {mo.model}", fontsize=8, va="top", ha="right", color="0.3")

    def frame(k):
        js = mo.joints[k]
        o2, a, b, o4, p = js
        for ln, (u, v) in zip(moving[:3], ((o2, a), (a, b), (o4, p))):
            ln.set_data([u[0], v[0]], [u[1], v[1]])
        moving[3].set_data(js[:4, 0], js[:4, 1])
        f = float(mo.force[k])
        dead = mo.dead_centre[k]
        length = float(lengths[k])
        arrow.set_data([p[0], p[0] + length], [p[1], p[1]])
        head.set_data([p[0] + length], [p[1]])
        head.set_marker(">" if length >= 0 else "<")
        fs = (
            "∞ (dead centre)"
            if not math.isfinite(f)
            else f"{f:+7.1f} N" + (" (beyond 3x limit)" if abs(f) > cap else "")
        )
        label = f"θ2 = {math.degrees(mo.crank_angle[k]):6.1f}°   F = {fs}"
        if dead:
            label += f"\n{dead.upper()} DEAD CENTRE"
        text.set_text(label)
        return [*moving, arrow, head, text]

    anim = FuncAnimation(fig, frame, frames=len(mo.crank_angle), blit=False)
    try:  # Pillow wants a file name: render in a private folder, then write atomically
        with tempfile.TemporaryDirectory() as tmp:
            gif = Path(tmp) / "animation.gif"
            anim.save(gif, writer=PillowWriter(fps=fps))
            with atomic_write(path, binary=True) as f:
                f.write(gif.read_bytes())
    finally:
        plt.close(fig)
    return path
