"""Drawings, animation and templates through the real entry point, read back from the files.

Reference lengths come from the 50-digit synthesis of tests/reference.py (Eq. (2) of the pump
paper by its own route), never from pumplink.  Paper arithmetic: 1 mm = 72 / 25.4 pt (PDF and
matplotlib's SVG both use the PostScript point), so the 100 mm scale bar is 283.4646 pt.
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import zlib
from pathlib import Path

import figures
import pytest
import reference as ref

ROOT = Path(__file__).resolve().parents[2]
PT_PER_MM = 72 / 25.4
#: The prototype (configs/prototype.toml): L1, D1, b, rocker, swing.
PROTO = dict(L1=0.40, D1=0.20, b=0.10, rocker=0.20, swing=math.radians(60.0))


def run(*args, pre="", cwd=ROOT):
    code = f"{pre}import sys; sys.argv = ['pumplink', *{list(args)!r}]; from pumplink.cli import main; main()"
    env = {**os.environ, "COLUMNS": "250"}  # --help examples on one line
    return subprocess.run(
        [sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True, check=False, env=env
    )


def reference_lengths_mm() -> dict[str, float]:
    r = ref.synthesis(**PROTO)
    return {"crank": float(r["crank"]) * 1000, "coupler": float(r["coupler"]) * 1000, "rocker-handle": 200.0}


def svg_point(svg: str, gid: str) -> tuple[float, float]:
    """The marker position inside ``<g id="gid">`` (matplotlib writes a marker as <use x= y=>)."""
    block = svg[svg.index(f'<g id="{gid}">') :]
    m = re.search(r'<use [^>]*x="([-\d.]+)" y="([-\d.]+)"', block)
    return float(m.group(1)), float(m.group(2))


def svg_segment(svg: str, gid: str) -> tuple[tuple[float, float], tuple[float, float]]:
    """The two points of the line drawn inside ``<g id="gid">`` ("M x y L x y")."""
    block = svg[svg.index(f'<g id="{gid}">') :]
    m = re.search(r'd="M ([-\d.]+) ([-\d.]+)\s+L ([-\d.]+) ([-\d.]+)', block)
    x0, y0, x1, y1 = map(float, m.groups())
    return (x0, y0), (x1, y1)


# ----------------------------------------------------------------------------- template: SVG, DXF
def test_template_svg_hole_centres_are_the_link_lengths(tmp_path):
    out = tmp_path / "t.svg"
    p = run("template", "configs/prototype.toml", "--out", str(out))
    assert p.returncode == 0, p.stderr
    svg = out.read_text()
    assert 'width="' in svg and "pt" in svg[:1000]  # user units are points
    for key, length in reference_lengths_mm().items():
        # the crank is welded to the axle at O2 (the default parts): its centre is marked, not drilled
        first = "weld" if key == "crank" else "hole"
        assert f'<g id="{"hole" if first == "weld" else "weld"}-{key}-0">' not in svg
        (x0, y0), (x1, y1) = svg_point(svg, f"{first}-{key}-0"), svg_point(svg, f"hole-{key}-1")
        assert math.hypot(x1 - x0, y1 - y0) / PT_PER_MM == pytest.approx(length, abs=0.01), key


def test_template_dxf_one_layer_per_link_and_hole_centres_are_the_link_lengths(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")  # in the test extra
    out = tmp_path / "t.dxf"
    p = run("template", "configs/prototype.toml", "--out", str(out))
    assert p.returncode == 0, p.stderr
    doc = ezdxf.readfile(out)
    assert doc.units == ezdxf.units.MM
    lengths = reference_lengths_mm()
    assert set(lengths) <= {layer.dxf.name for layer in doc.layers}
    for key, length in lengths.items():
        circles = doc.modelspace().query(f'CIRCLE[layer=="{key}"]')
        # the default parts' 12 mm pins; the crank is welded to the axle at O2: a cross, no circle
        assert all(c.dxf.radius == pytest.approx(6.0) for c in circles)
        centres = [(c.dxf.center.x, c.dxf.center.y) for c in circles]
        lines = doc.modelspace().query(f'LINE[layer=="{key}"]')
        upright = [ln for ln in lines if ln.dxf.start.x == ln.dxf.end.x]  # a welded joint's cross
        assert len(circles) == (1 if key == "crank" else 2) and len(upright) == 2 - len(circles), key
        centres += [(ln.dxf.start.x, (ln.dxf.start.y + ln.dxf.end.y) / 2) for ln in upright]
        assert math.dist(*centres) == pytest.approx(length, abs=0.01), key


def test_template_hole_diameter_comes_from_the_spec(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    text = (
        (ROOT / "configs/prototype.toml")
        .read_text()
        .replace("swing = 60.0", "swing = 60.0\nhole_diameter = 0.0125")
    )
    spec = tmp_path / "p.toml"
    spec.write_text(text)
    p = run("template", str(spec), "--out", str(tmp_path / "t.dxf"))
    assert p.returncode == 0, p.stderr
    radii = {c.dxf.radius for c in ezdxf.readfile(tmp_path / "t.dxf").modelspace().query("CIRCLE")}
    assert radii == {6.25}


def test_dxf_without_ezdxf_says_how_to_install_and_exits_2(tmp_path):
    out = tmp_path / "t.dxf"
    p = run(
        "template",
        "configs/prototype.toml",
        "--out",
        str(out),
        pre="import sys; sys.modules['ezdxf'] = None; ",
    )
    assert p.returncode == 2 and "pip install 'pumplink[dxf]'" in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and not out.exists()


# ----------------------------------------------------------------------------- template: PDF
def pdf_pages(data: bytes) -> list[tuple[tuple[float, ...], bytes]]:
    """(MediaBox, decoded content stream) of each page of an uncompressed-xref PDF (matplotlib's)."""
    objects = {int(n): body for n, body in re.findall(rb"(\d+) 0 obj(.*?)endobj", data, re.S)}
    pages = []
    for body in objects.values():
        if not re.search(rb"/Type\s*/Page\b", body):
            continue
        box = tuple(map(float, re.search(rb"/MediaBox\s*\[\s*([^\]]*)\]", body).group(1).split()))
        stream_obj = objects[int(re.search(rb"/Contents\s+(\d+) 0 R", body).group(1))]
        raw = re.search(rb"stream\r?\n(.*?)\r?\nendstream", stream_obj, re.S).group(1)
        pages.append((box, zlib.decompress(raw) if b"FlateDecode" in stream_obj else raw))
    return pages


def closed_polygons(content: bytes) -> list[tuple[float, float]]:
    """(width, height) of every closed straight-line path ``x y m (x y l)+ h`` in a content stream."""
    out = []
    for m in re.finditer(rb"((?:[-\d.]+ [-\d.]+ [ml]\n)+)h", content):
        pts = [tuple(map(float, p.split()[:2])) for p in m.group(1).strip().split(b"\n")]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        out.append((max(xs) - min(xs), max(ys) - min(ys)))
    return out


@pytest.mark.parametrize("paper, size_mm", [("A4", (297, 210)), ("letter", (279.4, 215.9))])
def test_template_pdf_page_size_and_100_mm_scale_bar_on_every_page(tmp_path, paper, size_mm):
    out = tmp_path / "t.pdf"
    p = run("template", "configs/prototype.toml", "--out", str(out), "--paper", paper)
    assert p.returncode == 0, p.stderr
    pages = pdf_pages(out.read_bytes())
    boxes, contents = [b for b, _ in pages], [c for _, c in pages]
    assert len(boxes) >= 2  # the 1015 mm handle does not fit one page: tiled
    assert f"{len(boxes)} pages" in p.stderr
    for box in boxes:
        assert box[:2] == (0, 0)
        assert box[2] == pytest.approx(size_mm[0] * PT_PER_MM, abs=1e-6)
        assert box[3] == pytest.approx(size_mm[1] * PT_PER_MM, abs=1e-6)
    assert len(contents) == len(boxes)
    for content in contents:
        # The scale bar's outline: 100 mm x 4 mm, measured in the page's own coordinates (points;
        # matplotlib draws paths without a scaling 'cm' in force).
        bars = [wh for wh in closed_polygons(content) if abs(wh[0] - 283.4646) < 0.01]
        assert len(bars) == 1, bars
        assert bars[0][0] == pytest.approx(100 * PT_PER_MM, abs=1e-4)
        assert bars[0][1] == pytest.approx(4 * PT_PER_MM, abs=1e-4)


def test_template_unknown_type_exits_2(tmp_path):
    p = run("template", "configs/prototype.toml", "--out", str(tmp_path / "t.png"))
    assert p.returncode == 2 and ".dxf" in p.stderr and len(p.stderr.strip().splitlines()) == 1


# ----------------------------------------------------------------------------- drawing, animation
def test_drawing_dead_centres_crank_and_coupler_collinear_and_to_scale(tmp_path):
    out = tmp_path / "d.svg"
    p = run("draw", "configs/prototype.toml", "--out", str(out), "--peak")
    assert p.returncode == 0, p.stderr
    scale = float(re.search(r"scale 1:([\d.]+)", p.stderr).group(1))
    svg = out.read_text()
    lengths = reference_lengths_mm()
    for pose, same_way in (("extended", True), ("folded", False), ("peak", None)):
        o2, a = svg_segment(svg, f"{pose}-crank")
        a2, b = svg_segment(svg, f"{pose}-coupler")
        assert a2 == pytest.approx(a, abs=1e-5)
        u, v = (a[0] - o2[0], a[1] - o2[1]), (b[0] - a[0], b[1] - a[1])
        sin = (u[0] * v[1] - u[1] * v[0]) / (math.hypot(*u) * math.hypot(*v))
        crank_mm = math.hypot(*u) / PT_PER_MM * scale
        coupler_mm = math.hypot(*v) / PT_PER_MM * scale
        assert crank_mm == pytest.approx(lengths["crank"], abs=0.01)
        assert coupler_mm == pytest.approx(lengths["coupler"], abs=0.01)
        if same_way is None:
            assert abs(sin) > 0.05  # the peak-force position is not a dead centre
        else:
            assert abs(sin) < 1e-6, pose
            assert (u[0] * v[0] + u[1] * v[1] > 0) == same_way  # extended: same way; folded: back


def test_animation_has_one_frame_per_step_of_a_revolution(tmp_path):
    PIL = pytest.importorskip("PIL.Image")
    out = tmp_path / "a.gif"
    p = run("draw", "configs/prototype.toml", "--animate", str(out), "--steps", "24")
    assert p.returncode == 0, p.stderr
    with PIL.open(out) as im:
        assert im.n_frames == 24
    assert not (tmp_path / "prototype.png").exists()  # --animate alone writes only the GIF


def test_draw_infeasible_spec_exits_1_with_one_line(tmp_path):
    text = (ROOT / "configs/prototype.toml").read_text().replace("D1 = 0.20", "D1 = -0.90")
    spec = tmp_path / "bad.toml"
    spec.write_text(text)
    p = run("draw", str(spec), "--out", str(tmp_path / "d.png"))
    assert p.returncode == 1 and "nothing to draw" in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and not (tmp_path / "d.png").exists()


# The --help examples of draw, template and report run in tests/cli/test_help_examples.py.


# ----------------------------------------------------------------------------- report
def test_report_is_one_self_contained_html_file(tmp_path):
    import base64

    out = tmp_path / "r.html"
    p = run("report", "configs/prototype.toml", "--out", str(out))
    assert p.returncode == 0, p.stderr
    text = out.read_text(encoding="utf-8")
    srcs = re.findall(r'src="([^"]*)"', text)
    assert len(srcs) == 2 and all(s.startswith("data:image/png;base64,") for s in srcs)  # chart, drawing
    for s in srcs:
        assert base64.b64decode(s.split(",", 1)[1]).startswith(b"\x89PNG")
    assert "<link" not in text and "<script" not in text  # nothing fetched from elsewhere
    assert "PASS" in text and "model: quasi-static + dead band" in text
    crank = reference_lengths_mm()["crank"]
    assert f"{crank:.1f} mm" in text  # synthesis table and cut list
    assert "cut list" in text.lower() and 'name = "Prototype"' in text.replace("&quot;", '"')


def test_report_of_a_failing_design_is_written_and_exits_1(tmp_path):
    out = tmp_path / "r.html"
    p = run("report", "examples/well-12m-flywheel.toml", "--out", str(out))
    assert p.returncode == 1 and "FAIL" in p.stderr
    text = out.read_text(encoding="utf-8")
    assert "FAIL" in text and "model: full dynamics" in text


def test_report_carries_the_loads_on_the_parts_and_the_released_handle(tmp_path):
    """The village well's report states the peak joint loads, the parts' pin pressure and fatigue
    safety and the released handle with the numbers `force --explain --format json` gives."""
    import html as html_module
    import json

    out = tmp_path / "r.html"
    p = run("report", "configs/village-10m.toml", "--out", str(out))
    assert p.returncode == 0, p.stderr
    text = html_module.unescape(out.read_text(encoding="utf-8"))
    shop = json.loads(run("force", "configs/village-10m.toml", "--explain", "--format", "json").stdout)
    shop = shop["explain"]["workshop"]
    assert "Loads on the parts (full dynamics, the peak over a turn)" in text
    for j in shop["joints"]:
        assert f"{j['peak_force_N']:.0f} N" in text and f"{j['crank_deg']:.1f}°" in text
    assert f"bear {shop['pin_pressure_MPa']:.1f} MPa" in text and "the spec's [parts]" in text
    assert f"handle tube {shop['handle_fatigue_safety']:.2f}" in text
    assert f"crank bar {shop['crank_fatigue_safety']:.2f}" in text
    # its [ratchet] holds the column: the report says so, with the kick-back to the pawl and the
    # column's torque of the JSON
    force = json.loads(run("force", "configs/village-10m.toml", "--format", "json").stdout)
    assert shop["release"]["needs_ratchet_or_brake"] and "NEEDS A RATCHET" not in text
    assert (
        f"released handle: the ratchet holds the water column (30 N·m for the water column's "
        f"{force['holding_torque_required_Nm']:.1f} N·m); let go at the worst moment, the grip kicks back "
        f"{force['kick_back_m']:.2f} m before its pawl catches"
    ) in " ".join(text.split())


# ----------------------------------------------------------------------------- what fits, read back
#: A 150-character name of words, and one of a single 150-character word (it cannot be wrapped).
LONG_NAME = (
    "Start village well pump for the district council, second revision with the heavier wheel and "
    "the longer handle, village well pump for the distr finish"
)
LONG_WORD = "S" + "x" * 148 + "F"


def named(tmp_path, name, source="configs/village-10m.toml") -> Path:
    text = (ROOT / source).read_text(encoding="utf-8")
    out = tmp_path / f"{len(name)}-{name[-1]}.toml"
    out.write_text(re.sub(r"^name = .*$", f'name = "{name}"', text, count=1, flags=re.M), encoding="utf-8")
    return out


def inside(box, lo, hi) -> bool:
    """``box`` (x0, y0, x1, y1, figure fractions) lies within [lo, hi] on both axes."""
    return lo[0] <= box[0] <= box[2] <= hi[0] and lo[1] <= box[1] <= box[3] <= hi[1]


def overlap(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


@pytest.mark.parametrize("name", [LONG_NAME, LONG_WORD])
def test_draw_title_of_a_long_name_stays_inside_the_page_border_with_both_ends(tmp_path, name):
    """The A4 drawing's name (the side panel's first text): inside the page border drawn 4 mm from
    the sheet's edges (renderer extents), its first and last characters kept (wrapped, or
    shortened in its middle); a 150-character name once ran past the border."""

    out = tmp_path / "d.png"
    p = figures.run("draw", named(tmp_path, name), "--out", out, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    panel = figures.read(out)["axes"][1]
    title, box = panel["texts"][0], panel["text_boxes"][0]
    W, H = 297.0, 210.0
    assert inside(box, (4 / W, 4 / H), (1 - 4 / W, 1 - 4 / H)), box
    flat = title.replace("\n", " ")
    assert flat.startswith(name[:12]) and flat.endswith(name[-12:]) if " " in name else True
    assert title[0] == name[0] and title[-1] == name[-1]
    below = [b[3] for b in panel["text_boxes"][1:]]
    assert max(below) < box[1]  # the panel's other lines start below the name


def test_template_titles_of_a_long_name_fit_the_page_with_both_ends(tmp_path):
    """Each PDF page's title of a 150-character name: one line between the margins, clear of the
    "print at 100 %" note, its first and last characters kept (shortened in its middle)."""
    log = tmp_path / "pages.jsonl"
    out = tmp_path / "t.pdf"
    p = figures.run("template", named(tmp_path, LONG_NAME), "--out", out, cwd=ROOT, log=log)
    assert p.returncode == 0, p.stderr
    pages = figures.logged(log)
    assert len(pages) >= 2
    W = 297.0
    for k, page in enumerate(pages, 1):
        ax = page["axes"][0]
        (i,) = [n for n, t in enumerate(ax["texts"]) if t.startswith(LONG_NAME[:10])]
        title, box = ax["texts"][i], ax["text_boxes"][i]
        note = ax["text_boxes"][ax["texts"].index("print at 100 % (actual size); lengths in mm")]
        assert "\n" not in title and title.endswith(
            f"{LONG_NAME[-10:]}: drilling template 1:1, A4, page {k} of {len(pages)}"
        )
        assert 10 / W <= box[0] and box[2] <= 1 - 10 / W and not overlap(box, note), (box, note)


@pytest.mark.parametrize("spec", ["configs/prototype.toml", "configs/village-10m.toml"])
def test_animation_force_arrow_inside_the_frame_at_every_frame(tmp_path, spec):
    """The force arrow and its head (drawn extents) inside the axes at every frame of a revolution;
    the prototype's quasi-static force is drawn at three times the limit near a dead centre, where
    the grip is at the end of its path, and its arrow was once clipped at the frame's edge."""

    log = tmp_path / "frames.jsonl"
    p = figures.run("draw", spec, "--animate", tmp_path / "a.gif", "--steps", "36", cwd=ROOT, log=log)
    assert p.returncode == 0, p.stderr
    frames = [f for f in figures.logged(log) if "force-arrow" in f["axes"][0]["gids"]]
    assert len(frames) >= 36
    texts = {f["figure_texts"][1] for f in frames}
    model = json.loads(run("force", spec, "--summary", "--format", "json").stdout)["model"]
    assert texts == {f"model: {model}"}
    for f in frames:
        ax = f["axes"][0]
        lo, hi = ax["box"][:2], ax["box"][2:]
        for gid in ("force-arrow", "force-arrow-head"):
            line = ax["gids"][gid]
            assert inside(line["box"], lo, hi), (gid, line)
            assert all(ax["xlim"][0] <= x <= ax["xlim"][1] for x in line["x"])


@pytest.mark.parametrize("spec", ["configs/prototype.toml", "configs/village-10m.toml"])
def test_draw_labels_at_the_axle_do_not_overlap(tmp_path, spec):
    """The joint names O2 and A, and the crank's and the wheel's dimensions, drawn where no two of
    them overlap (renderer extents); on the village well's 53.6 mm crank they once piled up."""

    out = tmp_path / "d.png"
    p = figures.run("draw", spec, "--out", out, "--peak", cwd=ROOT)
    assert p.returncode == 0, p.stderr
    ax = figures.read(out)["axes"][0]
    boxes = {t: b for t, b in zip(ax["texts"], ax["text_boxes"])}
    keys = ["O2", "A"] + [t for t in boxes if t.startswith(("l2 (crank)", "rw (wheel)"))]
    assert len(keys) == 4
    for i, a in enumerate(keys):
        for b in keys[i + 1 :]:
            assert not overlap(boxes[a], boxes[b]), (a, b)
