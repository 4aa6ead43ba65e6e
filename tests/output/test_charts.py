"""Charts through the real entry point: written when matplotlib is there, exit 2 when not; what
they show is read from the figure objects (``tests/figures.py``), not from the file's bytes."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import figures
import pytest

ROOT = Path(__file__).resolve().parents[2]


def run(*args, pre=""):
    code = f"{pre}import sys; sys.argv = ['pumplink', *{list(args)!r}]; from pumplink.cli import main; main()"
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=False)


def test_force_plot_shows_the_curve_limits_dead_centres_and_the_peak(tmp_path):
    """The force chart of the prototype (the quasi-static model decides): its title, the legend, the
    limit and mean-force lines, a dotted line at each dead centre and the verdict's peak marked
    where the JSON puts it, in PNG and SVG."""
    for name in ("f.png", "f.svg"):
        out = figures.run(
            "force",
            "configs/prototype.toml",
            "--summary",
            "--format",
            "json",
            "--plot",
            tmp_path / name,
            cwd=ROOT,
        )
        assert out.returncode == 0, out.stderr
        j = json.loads(out.stdout)
        data = (tmp_path / name).read_bytes()
        assert data.startswith(b"\x89PNG") if name.endswith(".png") else b"<svg" in data[:2000]
        (ax,) = figures.read(tmp_path / name)["axes"]
        band, limit, mean = 20, j["force_limit_N"], j["mean_force_N"]
        assert j["model"] == "quasi-static + dead band"
        assert " ".join(ax["title"].split()) == (
            f"Prototype: operator force, quasi-static + dead band decides (grey: ±{band}° dead bands "
            "left to the wheel's inertia)"
        )
        assert ax["legend"] == [
            "quasi-static operator force Fh",
            f"limit ±{limit:g} N",
            f"mean force ±{mean:.1f} N",
            f"verdict's peak {j['peak_force_N']:.1f} N (quasi-static + dead band)",
        ]
        flat = {(ln["y"][0], ln["y"][1]) for ln in ax["lines"] if ln["x"] == [0.0, 1.0]}  # horizontal lines
        assert {(limit, limit), (-limit, -limit), (mean, mean), (-mean, -mean)} <= flat
        vertical = sorted(ln["x"][0] for ln in ax["lines"] if ln["y"] == [0.0, 1.0])
        assert vertical == pytest.approx(sorted(j["dead_centres_deg"].values()), abs=1e-12)
        ((x, y),) = figures.marked(ax, "o")
        # the JSON gives a peak's crank angle to 6 significant digits (docs/json.md, Digits)
        assert float(f"{x:.5e}") == j["dead_band_peak_crank_deg"]
        assert abs(y) == pytest.approx(j["peak_force_N"], rel=1e-12)
        (curve,) = [ln for ln in ax["lines"] if ln["label"] == "quasi-static operator force Fh"]
        assert curve["x"][0] == 0.0 and curve["x"][-1] == 360.0 and len(curve["x"]) > 1000


@pytest.mark.parametrize(
    "spec, extra, model",
    [
        ("configs/village-10m.toml", (), "full dynamics"),
        ("examples/well-12m-flywheel.toml", ("--model", "flywheel"), "flywheel"),
    ],
)
def test_force_plot_names_the_energy_model_that_decided_and_marks_its_peak(tmp_path, spec, extra, model):
    """Where the flywheel or full dynamics decides, the chart's title and legend name that model
    (not "the flywheel" for full dynamics, no dead bands), and the red dot is the verdict's peak:
    its force is the JSON's peak force, at the crank angle where the JSON's samples (0.05° apart)
    have the slowest wheel, where their operator force is that peak.  The village well once showed
    "operator force with the flywheel" and the dead-band peak 109.7 N for a 91.1 N verdict."""
    out = figures.run(
        "force", spec, *extra, "--samples", "7200", "--format", "json", "--plot", tmp_path / "f.png", cwd=ROOT
    )
    assert out.returncode in (0, 1), out.stderr
    j = json.loads(out.stdout)
    assert j["model"] == model
    peak = j["peak_force_N"]
    ax = figures.read(tmp_path / "f.png")["axes"][0]
    title = " ".join(ax["title"].split())
    assert f"operator force, {model} decides" in title and "dead band" not in title
    assert f"operator force, {model} (peak {peak:.1f} N)" in ax["legend"]
    assert f"verdict's peak {peak:.1f} N ({model})" in ax["legend"]
    if model == "full dynamics":
        assert not any("flywheel" in t for t in ax["legend"])
    ((x, y),) = figures.marked(ax, "o")
    assert abs(y) == pytest.approx(peak, rel=1e-12)
    rows = j["samples"]
    assert max(abs(r["operator_force_N"]) for r in rows) == pytest.approx(peak, rel=1e-12)
    slowest = min(rows, key=lambda r: r["wheel_speed_deg_s"])
    assert x == pytest.approx(slowest["crank_deg"], abs=0.05)
    assert y == pytest.approx(slowest["operator_force_N"], rel=1e-12)
    assert y != pytest.approx(j["dead_band_peak_force_N"], rel=1e-3)  # not the dead-band peak


#: A 150-character name (words, so that a wrapped title can be read back with its spaces).
LONG_NAME = (
    "Start village well pump for the district council, second revision with the heavier wheel and "
    "the longer handle, village well pump for the distr finish"
)


def long_spec(tmp_path, source="configs/village-10m.toml", name=LONG_NAME) -> Path:
    import re

    text = (ROOT / source).read_text(encoding="utf-8")
    out = tmp_path / "long.toml"
    out.write_text(re.sub(r"^name = .*$", f'name = "{name}"', text, count=1, flags=re.M), encoding="utf-8")
    return out


def test_long_name_titles_fit_the_figure_and_keep_both_ends(tmp_path):
    """A 150-character name in the force and speed charts' titles: wrapped inside the figure (the
    title's drawn extent within the figure's), its first and last words kept; the force title once
    ran off both ends."""
    assert len(LONG_NAME) == 150
    spec = long_spec(tmp_path)
    for cmd in ("force", "speed"):
        out = figures.run(cmd, spec, "--plot", tmp_path / f"{cmd}.png", cwd=ROOT)
        assert out.returncode in (0, 1), out.stderr
        ax = figures.read(tmp_path / f"{cmd}.png")["axes"][0]
        x0, y0, x1, y1 = ax["title_box"]
        assert 0.0 <= x0 < x1 <= 1.0 and 0.0 <= y0 < y1 <= 1.0, (cmd, ax["title_box"])
        title = " ".join(ax["title"].split())
        assert title.startswith(LONG_NAME[:40]) and LONG_NAME[-30:] + ":" in title, title
        assert ax["title"].count("\n") <= 2


def test_speed_plot_marks_the_verdict_at_the_specs_speed(tmp_path):
    """The speed chart names the model that decides at the spec's own speed and marks its peak
    where ``pumplink force`` (JSON) puts it."""
    out = figures.run("speed", "configs/village-10m.toml", "--plot", tmp_path / "s.png", cwd=ROOT)
    assert out.returncode in (0, 1), out.stderr
    j = json.loads(run("force", "configs/village-10m.toml", "--summary", "--format", "json").stdout)
    ax = figures.read(tmp_path / "s.png")["axes"][0]
    ((x, y),) = figures.marked(ax, "D")
    assert x == j["speed_deg_s"] and y == pytest.approx(j["peak_force_N"], rel=1e-12)
    legend = figures.read(tmp_path / "s.png")["figure_legend"]
    assert (
        f"the verdict at the spec's {j['speed_deg_s']:g} deg/s: {j['model']}, peak {j['peak_force_N']:.1f} N"
        in legend
    )


def test_plot_without_matplotlib_says_how_to_install_and_exits_2(tmp_path):
    out = run(
        "force", "--plot", str(tmp_path / "f.png"), pre="import sys; sys.modules['matplotlib'] = None; "
    )
    assert out.returncode == 2
    assert "pip install 'pumplink[plot]'" in out.stderr
    assert "Traceback" not in out.stderr and out.stdout == ""
    assert not (tmp_path / "f.png").exists()


def test_plot_unknown_extension_exits_2(tmp_path):
    out = run("force", "--plot", str(tmp_path / "f.txt"))
    assert out.returncode == 2 and "--plot" in out.stderr and ".png" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
