"""The 1:1 workshop template: every link as a bar with its holes, for drilling and for laser/CNC.

* PDF: printable pages (A4, A3 or US letter, landscape), links tiled over several pages when
  longer than the paper, alignment marks where tiles meet and at the page corners, a 100 mm
  scale bar on every page, the cut list on page 1.
* SVG: one canvas at 1:1 (for a vector editor or a cutter), no tiling.
* DXF: millimetres, one layer per link (ezdxf, optional extra ``pumplink[dxf]``).

Renderers only: hole centres, diameters and lengths come from :class:`pumplink.studies.drawing.Part`,
and each hole's tolerance from :func:`pumplink.studies.drawing.tolerance_marks`: the tolerance under
each hole, a red ring and "critical" round the holes that need more care than a hand-drilled hole
gets, the stand's tolerance in the note on the first page (docs/tolerance.md).
1 mm on the paper is 72 / 25.4 = 2.8346 pt in the PDF and SVG.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from pathlib import Path

from pumplink.errors import SpecError
from pumplink.output.charts import fit_text, pyplot, width_of
from pumplink.output.formats import atomic_write, check_output

MM_PER_INCH = 25.4
#: Paper sizes, landscape (width, height) [mm]: ISO 216 A4 and A3, US letter (8.5 x 11 in).
PAPERS = {"A4": (297.0, 210.0), "A3": (420.0, 297.0), "letter": (279.4, 215.9)}
TEMPLATE_SUFFIXES = (".pdf", ".svg", ".dxf")
DXF_HINT = "install it with: pip install 'pumplink[dxf]'"
#: Page layout [mm]: printer-safe margin, header, footer (scale bar), one row per bar, the
#: overlap of consecutive tiles of a long bar, the scale bar's length and height.
MARGIN = 10.0
HEADER = 12.0
FOOTER = 20.0
ROW = 52.0
OVERLAP = 20.0
SCALE_BAR = (100.0, 4.0)
CUT_LIST_HEIGHT = 40.0
DEFAULT_TUBE = "3/4-inch medium steel tube, 26.9 x 2.6 mm"
#: The colour of the critical holes' rings and words.
CRITICAL = "C3"
#: A joint that is welded, not drilled (:data:`pumplink.studies.drawing.HOLE_KINDS`): the word at
#: its centre mark and in the cut list, and what to do there, in the link's title.
WELDED = {"lug": "lug", "welded": "welded"}
WELDED_NOTE = {
    "lug": "weld a lug on for the Ø{d:g} pin, centred on the mark; do not drill the tube",
    "welded": "weld it to the axle, centred on the mark; do not drill",
}


def link_title(p, sep: str = ": ") -> str:
    """A link's title on the template: its name, ``sep`` and the distance between its joints'
    centres (of its holes where every joint is drilled)."""
    between = "hole centres" if all(p.drilled) else "centres"
    return f"{p.name}{sep}{p.centre_distance * 1000:.1f} mm between {between}"


def welded_note(p, lo: float = -math.inf, hi: float = math.inf) -> str:
    """What to do at the welded joints of link ``p`` between ``lo`` and ``hi`` [mm along the bar],
    or "" where there are none."""
    return "; ".join(
        f"{label}: {WELDED_NOTE[kind].format(d=p.hole_diameter * 1000)}"
        for h, label, kind in zip(p.holes, p.hole_labels, p.hole_kinds or ("hole",) * len(p.holes))
        if kind in WELDED and lo - 1e-6 <= h * 1000 <= hi + 1e-6
    )


def tolerance_text(t: float) -> str:
    """A hole's tolerance as printed on the template: ±0.5 mm, or what no workshop holds."""
    return f"±{t * 1000:g} mm" if math.isfinite(t) else "< ±0.1 mm"


def marks_note(marks) -> str:
    """The first page's line on the tolerances (``marks``: :class:`pumplink.studies.drawing.Marks`)."""
    if marks.reason is not None:
        return f"no tolerances: {marks.reason}"
    read = "anywhere within ±t" if marks.distribution == "uniform" else "t = 3 sigma"
    stand = tolerance_text(marks.stand) + (" (critical)" if marks.stand_critical else "")
    return (
        f"tolerances for {marks.target:.0%} of builds to pass ({read}; docs/tolerance.md): under each hole; "
        f"red rings: critical holes; axle and rocker pivot on the stand {stand}"
    )


@dataclass(frozen=True)
class Tile:
    """The piece ``[start, stop]`` [mm, along the bar from its first hole] of part ``part`` on
    one page row; ``index`` of ``count`` tiles of that part."""

    part: int
    start: float
    stop: float
    index: int
    count: int


def check_template_path(path) -> Path:
    """Validate the template path's extension before any work is done."""
    path = Path(path)
    if path.suffix.lower() not in TEMPLATE_SUFFIXES:
        raise SpecError(f"--out {path}: unknown template type '{path.suffix}'; use .pdf, .svg or .dxf")
    return check_output(path, "--out")


def _bar_mm(p) -> tuple[float, float]:
    """The bar's extent [mm] along its axis, first hole at 0."""
    edge = p.edge * 1000
    return -edge, -edge + p.cut_length * 1000


def tiles(parts, usable: float, overlap: float = OVERLAP) -> list[Tile]:
    """Cut each bar into tiles no longer than ``usable`` [mm], overlapping by ``overlap`` [mm]."""
    out = []
    for i, p in enumerate(parts):
        lo, hi = _bar_mm(p)
        length = hi - lo
        n = 1 if length <= usable else math.ceil((length - overlap) / (usable - overlap))
        step = usable - overlap
        for k in range(n):
            start = lo + k * step
            out.append(Tile(i, start, min(start + usable, hi), k, n))
    return out


def layout(parts, paper: str) -> list[list[Tile]]:
    """The tiles on each page, in rows from the top; page 1 leaves room for the cut list."""
    W, H = PAPERS[paper]
    usable = W - 2 * MARGIN - 10.0
    rows = H - 2 * MARGIN - HEADER - FOOTER
    pages: list[list[Tile]] = [[]]
    room = int((rows - CUT_LIST_HEIGHT) // ROW)
    for t in tiles(parts, usable):
        if len(pages[-1]) >= room:
            pages.append([])
            room = int(rows // ROW)
        pages[-1].append(t)
    return pages


def cut_list_rows(parts, tube_given: bool, bom=None) -> list[tuple[str, ...]]:
    """The cut list: link, holes, centre distance, cut length, stock, mass (text cells); the stock
    and the mass of the bill of materials where it is given (:class:`pumplink.studies.bom.Bom`: a
    size to buy, the crank a round bar), else the tube's mass per metre."""
    rows = [("link", "holes", "hole centres", "cut length", "stock" if bom is not None else "tube", "mass")]
    stock = {} if bom is None else {i.part.split(" ")[0]: i for i in bom.items}
    for p in parts:
        item = stock.get({"rocker-handle": "handle"}.get(p.key, p.key))
        tube = f"{p.mass_per_length:.2f} kg/m " + (
            "(linkage.mass_per_length)" if tube_given else DEFAULT_TUBE
        )
        if item is not None:
            tube = item.stock
        welded = [(WELDED[k], label) for k, label in zip(p.hole_kinds, p.hole_labels) if k in WELDED]
        holes = f"{sum(p.drilled)} x Ø{p.hole_diameter * 1000:g} mm" + "".join(
            f", {word} at {label}" for word, label in welded
        )
        rows.append(
            (
                p.name,
                holes,
                f"{p.centre_distance * 1000:.1f} mm",
                f"{p.cut_length * 1000:.0f} mm",
                tube,
                f"{(p.mass if item is None else item.mass):.2f} kg",
            )
        )
    return rows


def bom_note(bom) -> str:
    """The first page's note of what else to make or buy: the pins, bushes and lug of the bill of
    materials (``pumplink bom``), and where the ratchet goes."""
    rest = [i for i in bom.items if i.part not in ("coupler", "handle (rocker to grip)", "crank", "wheel")]
    pins = [i for i in rest if i.part.startswith("pin ")]
    words = []
    if pins:
        lengths = " / ".join(f"{i.length * 1000:.0f}" for i in pins)
        words.append(f"pins {'/'.join(i.part[4:] for i in pins)}: {pins[0].stock}, {lengths} mm")
    words += [f"{i.count} x {i.part}: {i.stock}, {i.length * 1000:.0f} mm" for i in rest
              if not i.part.startswith("pin ") and i.part != "ratchet"]  # fmt: skip
    if bom.ratchet_note is not None:
        words.append(bom.ratchet_note)
    return "also (pumplink bom): " + "; ".join(words)


def _scale_bar(ax, x, y):
    """A 100 mm bar in 10 mm steps; its outline is exactly SCALE_BAR [mm] (what the fitter measures)."""
    from matplotlib.patches import Rectangle

    L, h = SCALE_BAR
    for k in range(0, 10, 2):
        ax.add_patch(Rectangle((x + 10 * k, y), 10, h, fc="k", ec="none", lw=0))
    bar = Rectangle((x, y), L, h, fill=False, ec="k", lw=0.5)
    bar.set_gid("scale-bar")
    ax.add_patch(bar)
    ax.text(x, y + h + 1.0, "0", fontsize=6, ha="center", va="bottom")
    ax.text(x + L, y + h + 1.0, "100 mm", fontsize=6, ha="center", va="bottom")
    ax.text(
        x + L + 12,
        y + h / 2,
        "scale check: this bar must measure exactly 100 mm. If not, print again at 100 % "
        "('actual size', no 'fit to page').",
        fontsize=6.5,
        va="center",
    )


def _cross(ax, x, y, size=4.0, lw=0.4, gid=None, colour="k"):
    ax.plot([x - size, x + size], [y, y], color=colour, lw=lw)
    ax.plot([x, x], [y - size, y + size], color=colour, lw=lw)
    (pt,) = ax.plot([x], [y], marker="+", ms=0.1, color=colour, lw=0)
    if gid:
        pt.set_gid(gid)


def _bar(ax, p, x0, yc, lo_clip, hi_clip, clip):
    """Part ``p`` with its first hole at page x = ``x0`` on centre line ``yc``, clipped to
    [lo_clip, hi_clip] of the bar [mm]."""
    from matplotlib.patches import Circle, Rectangle

    d = p.hole_diameter * 1000
    lo, hi = _bar_mm(p)
    w = 2 * p.edge * 1000
    artists = []
    artists.append(ax.add_patch(Rectangle((x0 + lo, yc - w / 2), hi - lo, w, fill=False, ec="k", lw=0.6)))
    (cl,) = ax.plot([x0 + lo - 3, x0 + hi + 3], [yc, yc], color="0.4", lw=0.3, ls=(0, (8, 2, 1, 2)))
    artists.append(cl)
    for i, (h, label, drilled) in enumerate(zip(p.holes, p.hole_labels, p.drilled)):
        x = x0 + h * 1000
        if not lo_clip - 1e-6 <= h * 1000 <= hi_clip + 1e-6:
            continue
        if drilled:
            artists.append(ax.add_patch(Circle((x, yc), d / 2, fill=False, ec="k", lw=0.6)))
            _cross(ax, x, yc, size=d / 2 + 3, lw=0.3, gid=f"hole-{p.key}-{i}")
            ax.text(x + d / 2 + 1.5, yc + 1.5, f"{label}  Ø{d:g}", fontsize=6.5, va="bottom")
        else:  # a welded joint: its centre marked, no hole (what to do: in the link's title)
            _cross(ax, x, yc, size=d / 2 + 3, lw=0.6, gid=f"weld-{p.key}-{i}")
            words = f"{label}  {WELDED[p.hole_kinds[i]]}, no hole"
            ax.text(x + d / 2 + 1.5, yc + 1.5, words, fontsize=6.5, va="bottom", weight="bold")
        if p.hole_tolerances:
            critical = p.hole_critical[i]
            words = tolerance_text(p.hole_tolerances[i]) + ("  critical" if critical else "")
            tol = ax.text(
                x + d / 2 + 1.5, yc - 1.5, words, fontsize=6.5, va="top", color=CRITICAL if critical else "k"
            )
            tol.set_gid(f"tolerance-{p.key}-{i}")
            if critical:
                ring = Circle((x, yc), d / 2 + 2.5, fill=False, ec=CRITICAL, lw=1.0)
                ring.set_gid(f"critical-{p.key}-{i}")
                artists.append(ax.add_patch(ring))
    if p.end_label:
        x = x0 + p.end * 1000
        if lo_clip - 1e-6 <= p.end * 1000 <= hi_clip + 1e-6:
            (g,) = ax.plot([x, x], [yc - w / 2 - 2, yc + w / 2 + 2], color="C3", lw=0.6)
            artists.append(g)
            tol = "" if p.end_tolerance is None else f", {tolerance_text(p.end_tolerance)}"
            tol += "  critical" if p.end_critical else ""
            end = ax.text(
                x + 2,
                yc,
                f"{p.end_label}: {p.end * 1000:.1f} mm from {p.hole_labels[0]}{tol}",
                fontsize=6.5,
                ha="left",
                va="center",
                color="C3",
            )
            end.set_gid(f"end-{p.key}")
    for a in artists:
        a.set_clip_path(clip)


def _new_page(plt, W, H):
    fig = plt.figure(figsize=(W / MM_PER_INCH, H / MM_PER_INCH))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, W)  # 1 data unit = 1 mm on the paper
    ax.set_ylim(0, H)
    ax.set_axis_off()
    return fig, ax


def _page(plt, parts, page, k, n, paper, name, cut_rows, marks=None, note_text=None):
    from matplotlib.patches import Rectangle

    W, H = PAPERS[paper]
    fig, ax = _new_page(plt, W, H)
    note = ax.text(
        W - MARGIN - 5,
        H - MARGIN - 3,
        "print at 100 % (actual size); lengths in mm",
        fontsize=7,
        va="center",
        ha="right",
    )
    # one line between the margin and the note: a long name loses its middle to an ellipsis
    title = ax.text(MARGIN + 5, H - MARGIN - 3, "", fontsize=10, weight="bold", va="center")
    room = 1 - (2 * MARGIN + 15) / W - width_of(note)
    fit_text(title, name, lambda s: f"{s}: drilling template 1:1, {paper}, page {k} of {n}", room, lines=1)
    for x, y in ((MARGIN, MARGIN), (W - MARGIN, MARGIN), (MARGIN, H - MARGIN), (W - MARGIN, H - MARGIN)):
        _cross(ax, x, y, size=3.0, lw=0.5)  # corner alignment marks
    _scale_bar(ax, MARGIN + 5, MARGIN + 6)
    top = H - MARGIN - HEADER
    if cut_rows:
        ax.text(MARGIN + 5, top, "cut list", fontsize=8, weight="bold", va="top")
        widths = (45, 38, 26, 24, 95, 20)
        for r, row in enumerate(cut_rows):
            x = MARGIN + 5
            for cell, w in zip(row, widths):
                ax.text(x, top - 6 - 5 * r, cell, fontsize=7, va="top", weight="bold" if r == 0 else "normal")
                x += w
        if marks is not None:
            note = ax.text(MARGIN + 5, top - 6 - 5 * len(cut_rows), marks_note(marks), fontsize=6.5, va="top")
            note.set_gid("tolerance-note")
        if note_text:  # what else to make or buy, under the cut list: two lines at most
            import textwrap

            lines = textwrap.wrap(note_text, int((W - 2 * MARGIN - 10) / 1.15))  # ~1.15 mm a character
            y = top - 6 - 5 * (len(cut_rows) + (marks is not None))
            extra = ax.text(MARGIN + 5, y, "\n".join(lines[:2]), fontsize=6, va="top", linespacing=1.2)
            extra.set_gid("bom-note")
        top -= CUT_LIST_HEIGHT
    x_left = MARGIN + 5
    for r, t in enumerate(page):
        p = parts[t.part]
        yc = top - (r + 0.5) * ROW
        x0 = x_left - t.start  # page x of the bar's first hole
        w = 2 * p.edge * 1000
        clip = Rectangle((x_left - 0.01, yc - ROW / 2), t.stop - t.start + 0.02, ROW, transform=ax.transData)
        _bar(ax, p, x0, yc, t.start, t.stop, clip)
        title = link_title(p)
        if p.end_label:
            title += f", {p.end_label} at {p.end * 1000:.1f} mm"
        if t.count > 1:
            title += f"  (piece {t.index + 1} of {t.count})"
        note = welded_note(p, t.start, t.stop)
        title += f"  — {note}" if note else ""
        tx = x_left + (OVERLAP + 2 if t.index else 0)  # clear of the alignment mark J
        ax.text(tx, yc + ROW / 2 - 3, title, fontsize=7.5, weight="bold", va="top")
        if len(p.holes) == 2 and t.count == 1:
            a, b = x0 + p.holes[0] * 1000, x0 + p.holes[1] * 1000
            y = yc - w / 2 - 5
            ax.annotate(
                "",
                xy=(b, y),
                xytext=(a, y),
                arrowprops=dict(arrowstyle="<|-|>", lw=0.5, mutation_scale=6, shrinkA=0, shrinkB=0),
            )
            ax.text(
                (a + b) / 2, y - 1, f"{p.centre_distance * 1000:.1f} mm", fontsize=7, ha="center", va="top"
            )
        # Where two pieces of a long bar meet: the same numbered mark on both, in the overlap.
        for j, at in ((t.index, t.start + OVERLAP / 2), (t.index + 1, t.stop - OVERLAP / 2)):
            if (j == t.index and t.index == 0) or (j == t.index + 1 and t.index + 1 == t.count):
                continue
            x = x0 + at
            for y in (yc + w / 2 + 5, yc - w / 2 - 5):
                _cross(ax, x, y, size=3.0, lw=0.5, colour="C0")
                ax.text(x + 1.5, y + 1.5, f"J{j}", fontsize=6.5, color="C0", va="bottom")
        if t.index + 1 < t.count:
            edge = x0 + t.stop
            ax.plot([edge, edge], [yc - w / 2 - 9, yc + w / 2 + 9], color="C0", lw=0.4, ls="--")
            ax.text(
                x0 + t.stop - OVERLAP / 2 - 6,
                yc - w / 2 - 5,
                f"piece {t.index + 2} continues: lay it over this end, J{t.index + 1} on J{t.index + 1}",
                fontsize=6.5,
                color="C0",
                ha="right",
                va="center",
            )
    return fig


def template_pdf(parts, path, paper: str, name: str, tube_given: bool, marks=None, bom=None) -> int:
    """Write the tiled PDF template (written to a temporary file, then renamed); returns pages."""
    plt = pyplot()
    from matplotlib.backends.backend_pdf import PdfPages

    path = Path(path)
    pages = layout(parts, paper)
    with (
        atomic_write(path, binary=True) as f,
        PdfPages(f, metadata={"Title": f"{name}: drilling template", "Creator": "pumplink"}) as pdf,
    ):
        for k, page in enumerate(pages, 1):
            fig = _page(
                plt,
                parts,
                page,
                k,
                len(pages),
                paper,
                name,
                cut_list_rows(parts, tube_given, bom) if k == 1 else None,
                marks if k == 1 else None,
                bom_note(bom) if k == 1 and bom is not None else None,
            )
            pdf.savefig(fig)
            plt.close(fig)
    return len(pages)


def template_svg(parts, path, name: str, marks=None) -> None:
    """Every bar on one canvas at 1:1, untiled, with its hole centres (SVG, in pt: 1 mm = 72/25.4 pt)."""
    plt = pyplot()
    path = Path(path)
    length = max(hi - lo for lo, hi in map(_bar_mm, parts))
    W = length + 2 * MARGIN + 10
    H = len(parts) * ROW + 2 * MARGIN + HEADER + FOOTER
    fig, ax = _new_page(plt, W, H)
    title = ax.text(MARGIN, H - MARGIN - 3, "", fontsize=10, weight="bold", va="center")
    fit_text(title, name, lambda s: f"{s}: link template 1:1 (mm)", 1 - 2 * MARGIN / W, lines=1)
    _scale_bar(ax, MARGIN + 5, MARGIN + 6)
    top = H - MARGIN - HEADER
    if marks is not None:
        note = ax.text(MARGIN, H - MARGIN - 8, marks_note(marks), fontsize=6.5, va="center")
        note.set_gid("tolerance-note")
    from matplotlib.patches import Rectangle

    for r, p in enumerate(parts):
        yc = top - (r + 0.5) * ROW
        lo, hi = _bar_mm(p)
        x0 = MARGIN + 5 - lo
        clip = Rectangle((0, 0), W, H, transform=ax.transData)
        _bar(ax, p, x0, yc, lo, hi, clip)
        ax.text(
            MARGIN + 5,
            yc + ROW / 2 - 3,
            link_title(p) + (f"  — {welded_note(p)}" if welded_note(p) else ""),
            fontsize=7.5,
            weight="bold",
            va="top",
        )
    try:
        with atomic_write(path, binary=True) as f:
            fig.savefig(f, format="svg")
    finally:
        plt.close(fig)


def template_dxf(parts, path, name: str, marks=None) -> None:
    """The bars in millimetres, one DXF layer per link: outline, centre line, hole circles, label."""
    try:
        import ezdxf
        from ezdxf import units
    except ImportError:
        raise SpecError(f"DXF output needs ezdxf, which is not installed; {DXF_HINT}") from None
    path = Path(path)
    doc = ezdxf.new("R2010", setup=True)
    doc.units = units.MM
    msp = doc.modelspace()
    for r, p in enumerate(parts):
        layer = p.key
        doc.layers.add(layer, color=r + 1)
        attr = {"layer": layer}
        yc = -r * ROW
        lo, hi = _bar_mm(p)
        w = p.edge * 1000
        msp.add_lwpolyline(
            [(lo, yc - w), (hi, yc - w), (hi, yc + w), (lo, yc + w)], close=True, dxfattribs=attr
        )
        msp.add_line((lo - 3, yc), (hi + 3, yc), dxfattribs=attr)
        for i, (h, drilled) in enumerate(zip(p.holes, p.drilled)):
            if drilled:
                msp.add_circle((h * 1000, yc), p.hole_diameter * 500, dxfattribs=attr)
            else:  # a welded joint: a cross at its centre and what to do there, no hole to cut
                size = p.hole_diameter * 500 + 3
                msp.add_line((h * 1000 - size, yc), (h * 1000 + size, yc), dxfattribs=attr)
                msp.add_line((h * 1000, yc - size), (h * 1000, yc + size), dxfattribs=attr)
                words = f"{p.hole_labels[i]} {WELDED[p.hole_kinds[i]]}, no hole"
                at = (h * 1000 + size + 1.5, yc + 1)
                msp.add_text(words, height=2.5, dxfattribs=attr).set_placement(at)
            if p.hole_tolerances:
                words = tolerance_text(p.hole_tolerances[i]) + (" critical" if p.hole_critical[i] else "")
                msp.add_text(words, height=2.5, dxfattribs=attr).set_placement(
                    (h * 1000 + p.hole_diameter * 500 + 1.5, yc - w - 4)
                )
                if p.hole_critical[i]:  # a ring round the hole, as on the paper template
                    msp.add_circle((h * 1000, yc), p.hole_diameter * 500 + 2.5, dxfattribs=attr)
        msp.add_text(
            f"{name}: {link_title(p, ', ')}" + (f"; {welded_note(p)}" if welded_note(p) else ""),
            height=4.0,
            dxfattribs=attr,
        ).set_placement((lo, yc + w + 3))
    if marks is not None:
        msp.add_text(marks_note(marks), height=3.0).set_placement((0.0, ROW))
    text = io.StringIO()
    doc.write(text)
    with atomic_write(path) as f:
        f.write(text.getvalue())


def write_template(parts, path, paper: str, name: str, tube_given: bool, marks=None, bom=None) -> int:
    """The template in the format of ``path``'s extension; returns the number of pages (1 for SVG/DXF).
    ``marks``: the tolerance notes (:class:`pumplink.studies.drawing.Marks`), with the parts';
    ``bom``: the bill of materials (:class:`pumplink.studies.bom.Bom`): the cut list's stock and a
    note of the pins, bushes, lug and ratchet on the PDF's first page."""
    path = check_template_path(path)
    suffix = path.suffix.lower()
    if suffix == ".pdf":
        return template_pdf(parts, path, paper, name, tube_given, marks, bom)
    if suffix == ".svg":
        template_svg(parts, path, name, marks)
    else:
        template_dxf(parts, path, name, marks)
    return 1
