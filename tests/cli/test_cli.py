"""CLI tests through the real entry point (the installed ``pumplink`` console script in a subprocess).

What is checked here is the contract as a user or another tool sees it: exit codes,
the JSON keys and their values, CSV headers and row counts, one-line error messages on stderr
(naming the key, the value and the allowed range) and readable tables when piped or with
NO_COLOR.  Expected numbers come from hand derivations written out in this file (docs/physics.md:
frame Eq. (1), dead-centre geometry, law of cosines for the transmission angle, an independent
circle-intersection position analysis differentiated numerically for the force), never from the
code under test.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

_EXE = shutil.which("pumplink", path=str(Path(sys.executable).parent))
CMD = [_EXE] if _EXE else [sys.executable, "-m", "pumplink"]

# An SGR escape that sets a foreground/background colour (NO_COLOR forbids these; bold is allowed).
COLOUR_SGR = re.compile(r"\x1b\[(?:[0-9;]*;)?(?:3[0-9]|4[0-9]|9[0-7]|10[0-7])(?:;[0-9;]*)?m")
ANY_ESC = "\x1b"


def _env(extra: dict | None = None) -> dict:
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS", "LINES", "TTY_COMPATIBLE", "TTY_INTERACTIVE")
    }
    env["PYTHONIOENCODING"] = "utf-8"  # the encoding bug has its own test below
    env.update(extra or {})
    return env


_CACHE: dict = {}


def run(
    *args, env: dict | None = None, cwd=None, cmd=None, cache: bool = False
) -> subprocess.CompletedProcess:
    """Run the CLI; ``cache=True`` reuses the result of an identical earlier call (the CLI is
    deterministic and each start-up costs ~0.5-1.5 s here; spec files must not change in between)."""
    key = (tuple(map(str, args)), tuple(sorted((env or {}).items())), str(cwd), tuple(cmd or CMD))
    if cache and key in _CACHE:
        return _CACHE[key]
    p = subprocess.run(
        [*(cmd or CMD), *map(str, args)],
        capture_output=True,
        env=_env(env),
        cwd=cwd,
        timeout=120,
        encoding="utf-8",
        errors="replace",
    )
    if cache:
        _CACHE[key] = p
    return p


def one_error_line(p: subprocess.CompletedProcess) -> str:
    """Exit 2, nothing on stdout, exactly one line on stderr, no traceback; return that line."""
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    assert p.stdout == "", p.stdout
    assert "Traceback" not in p.stderr, p.stderr
    lines = p.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].strip(), p.stderr
    return lines[0]


# ----------------------------------------------------------------------------- specs
SPEC = {  # deliberately not the default design, so defaults cannot make a wrong key pass
    "name": "Test pump",
    "wheel": {"radius": 0.22},
    "linkage": {"L1": 0.35, "D1": 0.15, "b": 0.12, "rocker": 0.22, "handle": 1.10, "swing": 64.0},
    "load": {"rope_force": 40.0},
    "operator": {"force_limit": 110.0, "speed": 300.0, "dead_band": 15.0},
}

BASE_TOML = """\
name = "t"
[wheel]
radius = 0.25
[linkage]
L1 = 0.40
D1 = 0.20
b = 0.10
rocker = 0.20
handle = 1.00
swing = 60.0
[load]
rope_force = 45.0
"""


def write(tmp_path: Path, data: dict, name: str = "spec.toml") -> Path:
    p = tmp_path / name
    p.write_text(tomli_w.dumps(data), encoding="utf-8")
    return p


def variant(**sections) -> dict:
    """SPEC with some values changed; a [load] given here replaces the whole section."""
    d = json.loads(json.dumps(SPEC))
    for sec, vals in sections.items():
        if isinstance(vals, dict) and sec != "load":
            d[sec].update(vals)
        else:
            d[sec] = vals
    return d


@pytest.fixture(scope="module")
def spec_path(tmp_path_factory) -> Path:
    """SPEC written once for the module (so identical CLI calls can share one subprocess)."""
    return write(tmp_path_factory.mktemp("spec"), SPEC)


def jrun(*args, expect: int | None = 0, **kw) -> dict:
    """JSON output of the CLI, parsed strictly (NaN/Infinity tokens rejected); ``expect=None``: 0 or 1."""
    p = run(*args, "--format", "json", **kw)
    assert p.returncode == expect if expect is not None else p.returncode in (0, 1), (p.returncode, p.stderr)
    assert "Traceback" not in p.stderr
    return json.loads(p.stdout, parse_constant=_no_nan)


def _no_nan(tok):
    raise AssertionError(f"non-standard JSON token {tok!r}")


# ----------------------------------------------------------------------------- hand computations
def hand_design(lk: dict) -> dict:
    """docs/physics.md: frame Eq. (1), beta, psi1/2, Eq. (2) by the law of cosines, and the dead-centre
    crank angles from the geometry (crank and coupler collinear with O2B at the rocker extremes)."""
    L1, D1, b, l4, s = lk["L1"], lk["D1"], lk["b"], lk["rocker"], lk["swing"]
    ox, oy = -(L1 + b / 2), -D1
    l1 = math.hypot(L1 + b / 2, D1)
    beta = 90 + math.degrees(math.atan2(D1, L1 + b / 2))
    psi1, psi2 = 180 - beta + s / 2, 180 - beta - s / 2
    d1 = math.sqrt(l1**2 + l4**2 - 2 * l1 * l4 * math.cos(math.radians(psi1)))
    d2 = math.sqrt(l1**2 + l4**2 - 2 * l1 * l4 * math.cos(math.radians(psi2)))
    l2, l3 = (d1 - d2) / 2, (d1 + d2) / 2
    # rocker at 90 + s/2 (angle psi1 to the frame line): B on the ray O2->A at distance l2 + l3
    bex = (ox + l4 * math.cos(math.radians(90 + s / 2)), oy + l4 * math.sin(math.radians(90 + s / 2)))
    # rocker at 90 - s/2: B at distance l3 - l2, A on the opposite side of O2
    bfo = (ox + l4 * math.cos(math.radians(90 - s / 2)), oy + l4 * math.sin(math.radians(90 - s / 2)))
    assert math.isclose(math.hypot(*bex), l2 + l3, rel_tol=1e-12)
    assert math.isclose(math.hypot(*bfo), l3 - l2, rel_tol=1e-12)
    ext = math.degrees(math.atan2(bex[1], bex[0])) % 360
    fold = math.degrees(math.atan2(-bfo[1], -bfo[0])) % 360
    arc = (ext - fold) % 360
    # transmission angle extremes: crank along the frame line, |AO4| = l1 -+ l2 (law of cosines)
    gmin = math.degrees(math.acos((l3**2 + l4**2 - (l1 - l2) ** 2) / (2 * l3 * l4)))
    gmax = math.degrees(math.acos((l3**2 + l4**2 - (l1 + l2) ** 2) / (2 * l3 * l4)))
    return dict(
        frame_length=l1,
        beta_deg=beta,
        psi1_deg=psi1,
        psi2_deg=psi2,
        crank_length=l2,
        coupler_length=l3,
        rocker_length=l4,
        handle_length=lk["handle"],
        rocker_pivot=[ox, oy],
        ext=ext,
        fold=fold,
        time_ratio=max(arc, 360 - arc) / min(arc, 360 - arc),
        gmin=gmin,
        gmax=gmax,
    )


def rocker_angle(h: dict, theta_rad, branch: float) -> np.ndarray:
    """Independent position analysis: B = intersection of circle(A, l3) and circle(O4, l4)."""
    l2, l3, l4 = h["crank_length"], h["coupler_length"], h["rocker_length"]
    ox, oy = h["rocker_pivot"]
    ax, ay = l2 * np.cos(theta_rad), l2 * np.sin(theta_rad)
    ux, uy = ax - ox, ay - oy
    d = np.hypot(ux, uy)
    a = (l4**2 - l3**2 + d**2) / (2 * d)
    hh = np.sqrt(l4**2 - a**2)
    bx = ox + (a * ux - branch * hh * uy) / d
    by = oy + (a * uy + branch * hh * ux) / d
    return np.arctan2(by - oy, bx - ox)


def branch_of(h: dict, swing: float) -> float:
    """The assembly branch whose rocker stays inside 90 +- swing/2 (checked on a grid)."""
    grid = np.radians(np.arange(0.0, 360.0, 0.5))
    lo, hi = math.radians(90 - swing / 2) - 1e-9, math.radians(90 + swing / 2) + 1e-9
    ok = [
        br
        for br in (1.0, -1.0)
        if np.all((rocker_angle(h, grid, br) >= lo) & (rocker_angle(h, grid, br) <= hi))
    ]
    assert len(ok) == 1, ok
    return ok[0]


def hand_force(h: dict, branch: float, theta_deg, Mw: float, H: float, step: float = 1e-6):
    """Fh = Mw / (dPx/dtheta2) (virtual work, docs/physics.md), Px = O4x + H cos(theta4), by a central
    difference of the independent position analysis; also |dtheta4/dtheta2|."""
    t = np.radians(np.asarray(theta_deg, float))
    r_p, r_m = rocker_angle(h, t + step, branch), rocker_angle(h, t - step, branch)
    dpx = H * (np.cos(r_p) - np.cos(r_m)) / (2 * step)
    rate = (r_p - r_m) / (2 * step)
    return Mw / dpx, np.abs(rate)


# ----------------------------------------------------------------------------- help / version
def test_force_help_states_units():
    """Units in the option help ("[deg/s]", "[deg]") must survive Rich markup."""
    out = run("force", "--help").stdout
    assert "deg/s" in out
    at_help = out[out.index("Evaluate") :]  # the --at option's help text, up to the next option
    assert "deg" in at_help.split("--summary")[0], at_help


def test_version_console_script_and_module():
    from importlib.metadata import version

    want = version("pumplink")
    for cmd in (CMD, [sys.executable, "-m", "pumplink"]):
        p = run("--version", cmd=cmd)
        assert p.returncode == 0 and want in p.stdout, (cmd, p.stdout, p.stderr)


# ----------------------------------------------------------------------------- JSON contract
DESIGN_KEYS = {
    "name",
    "feasible",
    "error",
    "frame_length",
    "beta_deg",
    "psi1_deg",
    "psi2_deg",
    "crank_length",
    "coupler_length",
    "rocker_length",
    "handle_length",
    "rocker_pivot",
    "dead_centres_deg",
    "time_ratio",
    "transmission_angle_deg",
}
FORCE_KEYS = DESIGN_KEYS | {
    "speed_deg_s",
    "wheel_torque_Nm",
    "power_W",
    "force_limit_N",
    "dead_band_deg",
    "mean_force_N",
    "peak_force_N",
    "pass",
    "checks",
}
SAMPLE_KEYS = {"crank_deg", "force_N", "handle_speed_m_s", "phi_deg", "rocker_deg", "transmission_deg"}


def check_design_fields(row: dict, spec: dict) -> None:
    h = hand_design(spec["linkage"])
    assert DESIGN_KEYS <= row.keys(), DESIGN_KEYS - row.keys()
    assert row["name"] == spec["name"] and row["feasible"] is True and row["error"] is None
    for k in (
        "frame_length",
        "beta_deg",
        "psi1_deg",
        "psi2_deg",
        "crank_length",
        "coupler_length",
        "rocker_length",
        "handle_length",
        "time_ratio",
    ):
        assert row[k] == pytest.approx(h[k], rel=1e-12, abs=1e-12), k
    assert row["rocker_pivot"] == pytest.approx(h["rocker_pivot"], abs=1e-15)
    dc = row["dead_centres_deg"]
    assert set(dc) >= {"extended", "folded"}
    for k, want in (("extended", h["ext"]), ("folded", h["fold"])):
        assert 0 <= dc[k] < 360
        assert dc[k] == pytest.approx(want, abs=1e-9), k
    tr = row["transmission_angle_deg"]
    assert tr["min"] == pytest.approx(h["gmin"], abs=1e-9)
    assert tr["max"] == pytest.approx(h["gmax"], abs=1e-9)


def test_synth_json_contract_against_hand_computation(tmp_path):
    spec2 = variant(name="Second", linkage={"L1": 0.45, "D1": -0.05, "swing": 50.0})
    out = jrun("synth", write(tmp_path, SPEC, "a.toml"), write(tmp_path, spec2, "b.toml"))
    assert list(out) == ["designs"] and len(out["designs"]) == 2
    check_design_fields(out["designs"][0], SPEC)
    check_design_fields(out["designs"][1], spec2)


N_SAMPLES = 36


def test_force_json_contract_against_hand_computation(spec_path):
    n = N_SAMPLES
    out = jrun("force", spec_path, "--samples", n, cache=True)
    assert FORCE_KEYS <= out.keys(), FORCE_KEYS - out.keys()
    check_design_fields(out, SPEC)
    lk, op = SPEC["linkage"], SPEC["operator"]
    Mw = SPEC["load"]["rope_force"] * SPEC["wheel"]["radius"]  # Mw = Fw rw
    omega = math.radians(op["speed"])
    assert out["speed_deg_s"] == pytest.approx(op["speed"], rel=1e-12)
    assert out["wheel_torque_Nm"] == pytest.approx(Mw, rel=1e-12)
    assert out["power_W"] == pytest.approx(Mw * omega, rel=1e-12)
    assert out["force_limit_N"] == pytest.approx(op["force_limit"], rel=1e-12)
    assert out["dead_band_deg"] == pytest.approx(op["dead_band"], rel=1e-12)
    mean = math.pi * Mw / (2 * lk["handle"] * math.sin(math.radians(lk["swing"]) / 2))
    assert out["mean_force_N"] == pytest.approx(mean, rel=1e-12)

    # peak outside the dead bands: dense grid of the independent force, band edges included
    h = hand_design(lk)
    br = branch_of(h, lk["swing"])
    band = op["dead_band"]
    grid = np.concatenate(
        [
            np.linspace(0, 360, 200_001),
            [(h["ext"] + s * band) % 360 for s in (-1, 1)] + [(h["fold"] + s * band) % 360 for s in (-1, 1)],
        ]
    )

    def dist(a, b):
        return np.abs((a - b + 180) % 360 - 180)

    grid = grid[(dist(grid, h["ext"]) >= band - 1e-12) & (dist(grid, h["fold"]) >= band - 1e-12)]
    f_grid, _ = hand_force(h, br, grid, Mw, lk["handle"])
    # The grid holds the four band edges, and this design's peak sits on one (asserted), so the
    # grid step plays no part: the two differ by the rounding of the hand force's central
    # difference (step 1e-6 rad).  Each cos(theta4) is off by <= 2 eps (the angle's rounding and
    # the cosine's), their difference by <= 4 eps, over 2e-6 rad: relative to the grip's travel
    # per radian there, dPx/dtheta = Mw / F, that is 4 eps / 2e-6 * H F / Mw (5e-9; measured 8e-10).
    j = int(np.argmax(np.abs(f_grid)))
    assert grid[j] in grid[-4:], "the peak is not at a band edge"
    rounding = 4 * np.finfo(float).eps / 2e-6 * lk["handle"] * abs(f_grid[j]) / Mw
    assert out["peak_force_N"] == pytest.approx(abs(f_grid[j]), rel=rounding)
    checks = out["checks"]
    assert checks and all(
        {"key", "name", "value", "unit", "warn_limit", "fail_limit", "result"} <= c.keys() for c in checks
    )
    by_key = {c["key"]: c for c in checks}
    for key, v in (("mean_force", out["mean_force_N"]), ("peak_force", out["peak_force_N"])):
        c = by_key[key]
        assert c["value"] == pytest.approx(v, rel=1e-12) and c["fail_limit"] == pytest.approx(
            op["force_limit"]
        )
        assert c["result"] == ("pass" if v <= op["force_limit"] else "fail")
    # peak grip speed: the largest |dtheta4/dtheta2| of the independent position analysis times w H
    # (docs/models.md §4); warn above 2.5 m/s, fail above 4 m/s
    _, rate = hand_force(h, br, np.linspace(0, 360, 200_001), Mw, lk["handle"])
    grip = float(np.max(rate)) * omega * lk["handle"]
    c = by_key["grip_speed"]
    assert c["value"] == pytest.approx(grip, rel=1e-6)
    assert c["result"] == ("fail" if grip > 4.0 else "warn" if grip > 2.5 else "pass")
    # the grip stroke 2 H sin(swing/2) (warn above 1 m)
    stroke = 2 * lk["handle"] * math.sin(math.radians(lk["swing"]) / 2)
    assert by_key["stroke"]["value"] == pytest.approx(stroke, rel=1e-12)
    assert by_key["stroke"]["result"] == ("warn" if stroke > 1.0 else "pass")
    results = {c["result"] for c in checks}
    assert out["pass"] is ("fail" not in results)
    assert out["verdict"] == (
        "FAIL" if "fail" in results else "PASS with warnings" if "warn" in results else "PASS"
    )

    samples = out["samples"]
    assert len(samples) == n
    assert all(SAMPLE_KEYS <= s.keys() for s in samples)
    crank = np.array([s["crank_deg"] for s in samples])
    assert crank == pytest.approx(np.arange(n) * 360 / n, abs=1e-9)
    finite = [s for s in samples if s["force_N"] is not None]
    assert len(finite) == n  # no sample falls on a dead centre here
    th = np.array([s["crank_deg"] for s in finite])
    f_hand, rate = hand_force(h, br, th, Mw, lk["handle"])
    assert np.array([s["force_N"] for s in finite]) == pytest.approx(f_hand, rel=1e-6)
    assert np.array([s["rocker_deg"] for s in finite]) == pytest.approx(
        np.degrees(rocker_angle(h, np.radians(th), br)), abs=1e-9
    )
    assert np.array([s["phi_deg"] for s in finite]) == pytest.approx(
        np.array([s["rocker_deg"] for s in finite]) - 90, abs=1e-9
    )
    assert np.array([s["handle_speed_m_s"] for s in finite]) == pytest.approx(
        rate * omega * lk["handle"], rel=1e-6
    )
    tr = out["transmission_angle_deg"]
    assert all(tr["min"] - 1e-9 <= s["transmission_deg"] <= tr["max"] + 1e-9 for s in finite)


def test_head_based_load_in_force_json(tmp_path):
    """Rope force from the head: rho g head (pi d^2/4) / efficiency (docs/physics.md §5), 0.75 by default
    (an explicit efficiency is covered in test_spec.py)."""
    out = jrun(
        "force",
        write(tmp_path, variant(load={"head": 10.0, "pipe_diameter": 0.023})),
        "--summary",
        expect=None,
    )
    fw = 1000 * 9.81 * 10.0 * math.pi * 0.023**2 / 4 / 0.75
    assert fw == pytest.approx(54.4, abs=0.1)  # docs/physics.md §5: "about 54 N"
    assert out["wheel_torque_Nm"] == pytest.approx(fw * SPEC["wheel"]["radius"], rel=1e-12)


def test_summary_omits_samples(spec_path):
    out = jrun("force", spec_path, "--summary", cache=True)
    assert FORCE_KEYS <= out.keys() and "samples" not in out


def test_at_evaluates_exactly_those_angles_and_flags_dead_centres(spec_path):
    spec = spec_path
    dc = jrun("synth", spec, cache=True)["designs"][0]["dead_centres_deg"]
    angles = [10.0, dc["extended"], 90.0, dc["folded"], 275.5]
    out = jrun("force", spec, *[a for x in angles for a in ("--at", repr(x))])
    s = out["samples"]
    assert [x["crank_deg"] for x in s] == pytest.approx(angles, abs=1e-9)
    for i in (1, 3):
        assert s[i]["force_N"] is None and s[i]["singular"] is True, s[i]
        assert s[i]["handle_speed_m_s"] == pytest.approx(0.0, abs=1e-9)
    for i in (0, 2, 4):
        assert s[i]["force_N"] is not None and math.isfinite(s[i]["force_N"]) and s[i]["singular"] is False
    # the rocker sits at its extremes at the dead centres (90 +- swing/2)
    sw = SPEC["linkage"]["swing"]
    assert s[1]["rocker_deg"] == pytest.approx(90 + sw / 2, abs=1e-9)
    assert s[3]["rocker_deg"] == pytest.approx(90 - sw / 2, abs=1e-9)


def test_speed_changes_power_and_handle_speed_not_forces(spec_path):
    a = jrun("force", spec_path, "--samples", N_SAMPLES, cache=True)  # the spec's speed, 300 deg/s
    b = jrun("force", spec_path, "--samples", N_SAMPLES, "--speed", "720", expect=1)  # grip too fast
    ratio = 720 / SPEC["operator"]["speed"]
    assert a["speed_deg_s"] == pytest.approx(SPEC["operator"]["speed"]) and b["speed_deg_s"] == pytest.approx(
        720
    )
    assert b["power_W"] == pytest.approx(ratio * a["power_W"], rel=1e-12)
    assert b["power_W"] == pytest.approx(b["wheel_torque_Nm"] * math.radians(720), rel=1e-12)
    assert len(a["samples"]) == len(b["samples"]) == N_SAMPLES
    for sa, sb in zip(a["samples"], b["samples"]):
        assert sb["crank_deg"] == sa["crank_deg"]
        assert sb["handle_speed_m_s"] == pytest.approx(ratio * sa["handle_speed_m_s"], rel=1e-12)
        assert sb["force_N"] == pytest.approx(sa["force_N"], rel=1e-12)
    for k in ("mean_force_N", "peak_force_N", "wheel_torque_Nm"):
        assert a[k] == pytest.approx(b[k], rel=1e-12)


# ----------------------------------------------------------------------------- CSV
def test_csv_formats(tmp_path, spec_path):
    a, b = spec_path, write(tmp_path, variant(name="B"), "b.toml")
    p = run("synth", a, b, "--format", "csv")
    assert p.returncode == 0, p.stderr
    rows = list(csv.DictReader(io.StringIO(p.stdout)))
    assert len(rows) == 2 and [r["name"] for r in rows] == ["Test pump", "B"]
    for k in (
        "feasible",
        "frame_length",
        "crank_length",
        "rocker_pivot_x",
        "rocker_pivot_y",
        "dead_centres_deg_extended",
        "dead_centres_deg_folded",
        "transmission_angle_deg_min",
        "time_ratio",
    ):
        assert k in rows[0], k
    h = hand_design(SPEC["linkage"])
    assert float(rows[0]["frame_length"]) == pytest.approx(h["frame_length"], rel=1e-12)
    assert float(rows[0]["rocker_pivot_x"]) == pytest.approx(h["rocker_pivot"][0], rel=1e-12)

    p = run("force", a, "--samples", "7", "--format", "csv")
    assert p.returncode == 0, p.stderr
    rows = list(csv.DictReader(io.StringIO(p.stdout)))
    assert len(rows) == 7 and SAMPLE_KEYS <= rows[0].keys()
    assert [float(r["crank_deg"]) for r in rows] == pytest.approx([i * 360 / 7 for i in range(7)], abs=1e-9)

    p = run("force", a, "--summary", "--format", "csv")
    assert p.returncode == 0, p.stderr
    rows = list(csv.DictReader(io.StringIO(p.stdout)))
    assert len(rows) == 1 and {"mean_force_N", "peak_force_N", "pass", "power_W"} <= rows[0].keys()

    dc = jrun("synth", a, cache=True)["designs"][0]["dead_centres_deg"]["folded"]
    p = run("force", a, "--at", repr(dc), "--at", "90", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(p.stdout)))
    assert len(rows) == 2 and rows[0]["force_N"] == "" and float(rows[1]["force_N"]) != 0
    assert "nan" not in p.stdout.lower() and "inf" not in p.stdout.lower()


# ----------------------------------------------------------------------------- exit codes / verdict
def test_default_design_runs_and_states_its_verdict():
    p = run("force", cache=True)
    assert p.returncode in (0, 1), p.stderr
    verdict = "PASS" if p.returncode == 0 else "FAIL"
    assert f"VERDICT: {verdict}" in p.stdout or (verdict in p.stdout and "VERDICT" in p.stdout.upper())
    out = jrun("force", "--summary", expect=p.returncode)
    assert out["pass"] is (p.returncode == 0)
    # the default is the prototype: Mw = 45 N * 0.25 m, mean = pi Mw / (2 * 1 m * sin 30 deg)
    assert out["wheel_torque_Nm"] == pytest.approx(45 * 0.25)
    assert out["mean_force_N"] == pytest.approx(math.pi * 45 * 0.25 / (2 * 1.0 * 0.5), rel=1e-12)


def test_heavy_load_fails_with_exit_1(tmp_path):
    spec = write(tmp_path, variant(load={"rope_force": 400.0}))
    out = jrun("force", spec, "--summary", expect=1)
    assert out["pass"] is False and out["peak_force_N"] > out["force_limit_N"]
    assert any(c["result"] == "fail" for c in out["checks"])
    p = run("force", spec, "--summary")
    assert p.returncode == 1 and "FAIL" in p.stdout and ANY_ESC not in p.stdout


def test_force_limit_decides_the_verdict(tmp_path, spec_path):
    """Same linkage, the limit just above and just below the reported peak (and above the mean)."""
    base = jrun("force", spec_path, "--summary", cache=True)
    peak = base["peak_force_N"]
    assert base["mean_force_N"] < peak
    hi = jrun(
        "force", write(tmp_path, variant(operator={"force_limit": peak * 1.001})), "--summary", expect=0
    )
    lo = jrun(
        "force", write(tmp_path, variant(operator={"force_limit": peak * 0.999})), "--summary", expect=1
    )
    assert hi["pass"] is True and lo["pass"] is False


def test_infeasible_design_exit_1(tmp_path):
    """D1 = 3 m: the frame line rises at atan2(3, 0.41) = 82 deg, steeper than the forward extreme of the
    swing (90 - 32 = 58 deg), so psi2 < 0: no crank-rocker (docs/physics.md)."""
    bad = write(tmp_path, variant(name="Deep", linkage={"D1": 3.0}), "bad.toml")
    good = write(tmp_path, SPEC, "good.toml")
    assert hand_design(variant(linkage={"D1": 3.0})["linkage"])["psi2_deg"] < 0
    out = jrun("synth", good, bad, expect=1)
    g, d = out["designs"]
    assert g["feasible"] is True and d["feasible"] is False
    assert isinstance(d["error"], str) and len(d["error"]) > 20
    assert d["crank_length"] is None and d["coupler_length"] is None
    assert d["dead_centres_deg"]["extended"] is None
    f = jrun("force", bad, expect=1)
    assert f["pass"] is False and f["feasible"] is False and f["peak_force_N"] is None
    p = run("force", bad)
    assert p.returncode == 1 and "FAIL" in p.stdout and "Traceback" not in p.stderr
    p = run("synth", bad)
    assert p.returncode == 1 and d["error"][:40] in " ".join(p.stdout.split())


# ----------------------------------------------------------------------------- tables
def test_force_table_piped_and_no_color(tmp_path):
    for env in ({}, {"NO_COLOR": "1"}):
        p = run("force", env=env, cache=True)
        assert p.returncode == 0, p.stderr
        out = p.stdout
        assert ANY_ESC not in out, env
        assert "PASS" in out
        assert out.count("DC extended") == 1 and out.count("DC folded") == 1 and out.count(" ∞ ") >= 2
        assert max(len(line) for line in out.splitlines()) <= 80  # piped: 80 columns unless COLUMNS
        for unit in ("[N]", "[°]", "[m/s]"):
            assert unit in out, unit
        assert not re.search(r"\bnan\b", out, re.I)


def test_synth_table_piped(spec_path):
    p = run("synth", spec_path, Path(__file__).parents[2] / "configs" / "prototype.toml")
    assert p.returncode == 0, p.stderr
    assert ANY_ESC not in p.stdout
    assert "Test pump" in p.stdout and "Prototype" in p.stdout
    assert "[m]" in p.stdout or " m" in p.stdout
    assert not re.search(r"\bnan\b", p.stdout, re.I)
    h = hand_design(SPEC["linkage"])
    assert f"{h['crank_length']:.4f}" in p.stdout or f"{h['crank_length']:.3f}" in p.stdout


def test_user_text_with_rich_markup_is_shown_literally(tmp_path):
    spec = write(tmp_path, variant(name="Well [bold]3[/bold] [red"))
    for cmd in ("synth", "force"):
        p = run(cmd, spec)
        assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
        assert "Well [bold]3[/bold] [red" in p.stdout, cmd


def _run_on_tty(args, env):
    m, s = os.openpty()  # POSIX; the suite runs on Linux
    proc = subprocess.Popen([*CMD, *args], stdout=s, stderr=subprocess.PIPE, env=_env(env))
    os.close(s)
    chunks = []
    while True:
        try:
            b = os.read(m, 65536)
        except OSError:
            break
        if not b:
            break
        chunks.append(b)
    proc.wait(timeout=60)
    os.close(m)
    return proc.returncode, b"".join(chunks).decode("utf-8", "replace")


def test_no_color_on_a_terminal():
    """On a terminal colours are on (so the check below can fail); NO_COLOR=1 removes every colour code."""
    rc, out = _run_on_tty(["force", "--summary"], {"TERM": "xterm-256color", "COLUMNS": "200"})
    assert rc == 0 and COLOUR_SGR.search(out), repr(out[:200])
    rc, out = _run_on_tty(
        ["force", "--summary"], {"TERM": "xterm-256color", "COLUMNS": "200", "NO_COLOR": "1"}
    )
    assert rc == 0
    assert not COLOUR_SGR.search(out), set(COLOUR_SGR.findall(out))
    assert "PASS" in re.sub(r"\x1b\[[0-9;]*m", "", out)


def test_non_utf8_stdout_does_not_traceback():
    """A legacy (non-UTF-8) console: the tables use ∞, Δ, ±, °; no traceback whatever the encoding."""
    for fmt in ("table", "json"):
        p = run("force", "--summary", "--format", fmt, env={"PYTHONIOENCODING": "ascii"})
        assert "Traceback" not in p.stderr, (fmt, p.stderr[-300:])
        assert p.returncode in (0, 2), p.returncode


# ----------------------------------------------------------------------------- bad input
def _sub(old: str, new: str) -> str:
    assert old in BASE_TOML
    return BASE_TOML.replace(old, new)


def _bounds(section: str, key: str) -> list[str]:
    """The allowed range declared on the model (so the message can be checked to state it)."""
    from pumplink.inputs.pump import PumpSpec

    info = PumpSpec.model_fields[section].annotation.model_fields[key]
    out = []
    for m in info.metadata:
        for attr in ("gt", "ge", "lt", "le"):
            v = getattr(m, attr, None)
            if v is not None:
                out.append(f"{v:g}")
    return out


# name, file content (str or bytes), substrings that must appear in the one stderr line,
# (section, key) for range
BAD_FILES = [
    ("toml-syntax", _sub("swing = 60.0", "swing = 60.0 ="), ["line"], None),
    ("duplicate-key", _sub("b = 0.10", "b = 0.10\nb = 0.2"), ["b"], None),
    ("missing-key", _sub("radius = 0.25\n", ""), ["radius"], None),
    ("missing-section", BASE_TOML.split("[load]")[0], ["load"], None),
    ("unknown-key", _sub("rocker = 0.20", "rockr = 0.20"), ["rockr"], None),
    ("unknown-section", BASE_TOML + "[operater]\nspeed = 300.0\n", ["operater"], None),
    ("negative-length", _sub("rocker = 0.20", "rocker = -0.2"), ["rocker", "-0.2"], ("linkage", "rocker")),
    ("negative-radius", _sub("radius = 0.25", "radius = -0.25"), ["radius", "-0.25"], ("wheel", "radius")),
    ("nan", _sub("L1 = 0.40", "L1 = nan"), ["L1", "nan"], ("linkage", "L1")),
    ("inf", _sub("D1 = 0.20", "D1 = inf"), ["D1", "inf"], ("linkage", "D1")),
    ("minus-inf", _sub("handle = 1.00", "handle = -inf"), ["handle", "inf"], ("linkage", "handle")),
    ("overflow-to-inf", _sub("L1 = 0.40", "L1 = 1e400"), ["L1", "inf"], ("linkage", "L1")),
    ("swing-180", _sub("swing = 60.0", "swing = 180.0"), ["swing", "180"], ("linkage", "swing")),
    ("swing-250", _sub("swing = 60.0", "swing = 250"), ["swing", "250"], ("linkage", "swing")),
    ("swing-zero", _sub("swing = 60.0", "swing = 0"), ["swing"], ("linkage", "swing")),
    ("string-for-number", _sub("handle = 1.00", 'handle = "1.0"'), ["handle", "1.0"], ("linkage", "handle")),
    ("boolean-for-number", _sub("handle = 1.00", "handle = true"), ["handle", "true"], ("linkage", "handle")),
    ("array-for-number", _sub("handle = 1.00", "handle = [1.0]"), ["handle"], None),
    (
        "section-not-table",
        "linkage = 5\n"
        + BASE_TOML.replace("name", "nom", 0).split("[linkage]")[0]
        + BASE_TOML.split("swing = 60.0")[1],
        ["linkage"],
        None,
    ),
    ("name-not-text", _sub('name = "t"', "name = 3"), ["name"], None),
    (
        "dead-band-90",
        BASE_TOML + "[operator]\ndead_band = 90.0\n",
        ["dead_band", "90"],
        ("operator", "dead_band"),
    ),
    ("zero-speed", BASE_TOML + "[operator]\nspeed = 0\n", ["speed"], ("operator", "speed")),
    (
        "both-loads",
        _sub("rope_force = 45.0", "rope_force = 45.0\nhead = 10.0\npipe_diameter = 0.023"),
        ["rope_force", "head"],
        None,
    ),
    ("head-without-pipe", _sub("rope_force = 45.0", "head = 10.0"), ["pipe_diameter"], None),
    (
        "efficiency-without-head",
        _sub("rope_force = 45.0", "rope_force = 45.0\nefficiency = 0.7"),
        ["efficiency"],
        None,
    ),
    (
        "efficiency-above-1",
        _sub("rope_force = 45.0", "head = 10.0\npipe_diameter = 0.023\nefficiency = 1.5"),
        ["efficiency", "1.5"],
        ("load", "efficiency"),
    ),
    ("empty-file", "", [], None),
    ("comment-only", "# nothing here\n\n", [], None),
    ("non-utf8", b'name = "\xff\xfe"\n[wheel]\nradius = 0.25\n', ["UTF-8"], None),
]


# `force` reads specs through the same load_spec as `synth`; it is run on a representative subset
# (each subprocess costs ~0.5 s here) and `synth` on all of them.
FORCE_TOO = {
    "toml-syntax",
    "unknown-key",
    "negative-length",
    "nan",
    "string-for-number",
    "empty-file",
    "non-utf8",
}


#: Runs ``pumplink.cli.main(argv)`` (the console script's function) once per argv given as JSON on
#: stdin, in this one process, and prints each call's exit code, stdout and stderr as JSON.
MAIN_PER_ARGV = """
import io, json, sys
from pumplink.cli import main
out = []
for argv in json.load(sys.stdin):
    sys.stdout, sys.stderr = io.StringIO(), io.StringIO()
    try:
        main(argv)
        code = 0
    except SystemExit as exc:
        code = exc.code
    out.append([code, sys.stdout.getvalue(), sys.stderr.getvalue()])
sys.__stdout__.write(json.dumps(out))
"""


@pytest.fixture(scope="module")
def bad_results(tmp_path_factory) -> dict:
    """Every bad file through the console script's function, ``pumplink.cli.main`` (the parsing,
    the one-line error and the exit code of the installed ``pumplink``), all in one interpreter:
    36 start-ups of ~0.4 s each otherwise.  The console script itself meets a bad spec in
    test_missing_file_and_folder_exit_2, test_heavy_load_fails_with_exit_1 and the others."""
    folder = tmp_path_factory.mktemp("bad")
    jobs = []
    for name, content, _, _ in BAD_FILES:
        f = folder / f"{name}.toml"
        if isinstance(content, bytes):
            f.write_bytes(content)
        else:
            f.write_text(content, encoding="utf-8")
        jobs += [(name, cmd, f) for cmd in ("synth", "force") if cmd == "synth" or name in FORCE_TOO]
    argvs = [[cmd, str(f)] for _, cmd, f in jobs]
    p = subprocess.run(
        [sys.executable, "-c", MAIN_PER_ARGV], input=json.dumps(argvs), capture_output=True, text=True,
        env=_env(), timeout=300,
    )  # fmt: skip
    assert p.returncode == 0, p.stderr
    results = json.loads(p.stdout)
    return {
        (name, cmd): subprocess.CompletedProcess(argv, *r)
        for (name, cmd, _), argv, r in zip(jobs, argvs, results, strict=True)
    }


@pytest.mark.parametrize("name,content,words,rng", BAD_FILES, ids=[c[0] for c in BAD_FILES])
def test_bad_spec_files_exit_2_with_one_line(bad_results, name, content, words, rng):
    for cmd in ("synth", "force"):
        if (name, cmd) not in bad_results:
            continue
        line = one_error_line(bad_results[name, cmd])
        assert f"{name}.toml" in line, line  # says which file
        for w in words:
            assert w.lower() in line.lower(), (cmd, w, line)
        if rng:
            for bound in _bounds(*rng):
                assert bound in line, (cmd, bound, line)
        assert "None" not in line, line  # no Python internals in a user message


def test_missing_file_and_folder_exit_2(tmp_path):
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    for target in (tmp_path / "nope.toml", folder):
        for cmd in ("synth", "force"):
            line = one_error_line(run(cmd, target))
            assert target.name in line, line


def test_first_bad_spec_in_a_batch_stops_synth(tmp_path):
    good = write(tmp_path, SPEC, "good.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text(_sub("rocker = 0.20", "rockr = 0.20"), encoding="utf-8")
    line = one_error_line(run("synth", good, bad))
    assert "bad.toml" in line and "rockr" in line


@pytest.mark.parametrize(
    "args,option",
    [
        (["force", "--samples", "0"], "--samples"),
        (["force", "--speed", "-1"], "--speed"),
        (["force", "--speed", "0"], "--speed"),
        (["force", "--format", "xml"], "--format"),
        (["synth", "--format", "xml", "configs/prototype.toml"], "--format"),
        (["force", "--at", "nan"], "--at"),
        (["force", "--at", "inf"], "--at"),
        (["force", "--at", "ninety"], "--at"),
        (["force", "--samples", "2000000"], "--samples"),
        (["force", "--bogus"], "--bogus"),
        (["speed"], "spec"),  # a command whose spec is required (synth has a default)
    ],
)
def test_bad_options_exit_2(args, option):
    p = run(*args, cwd=Path(__file__).parents[2])
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    assert p.stdout == "" and "Traceback" not in p.stderr
    assert option.lower() in p.stderr.lower(), p.stderr


def test_debug_shows_the_traceback(tmp_path):
    p = run("--debug", "synth", tmp_path / "nope.toml")
    assert p.returncode != 0 and "Traceback" in p.stderr and "nope.toml" in p.stderr


# ----------------------------------------------------------------------------- init
def test_init_writes_a_spec_that_loads_and_passes(tmp_path):
    p = run("init", cwd=tmp_path)  # default path pump.toml
    assert p.returncode == 0 and p.stdout == "", (p.stdout, p.stderr)
    written = tmp_path / "pump.toml"
    data = tomllib.loads(written.read_text(encoding="utf-8"))
    assert {"wheel", "linkage", "load"} <= data.keys()
    from pumplink.inputs.pump import load_spec

    load_spec(written)  # validates
    out = jrun("force", written, "--summary", expect=0)
    assert out["pass"] is True

    # refuses to overwrite; the file is untouched
    written.write_text(written.read_text(encoding="utf-8") + "# edited\n", encoding="utf-8")
    before = written.read_text(encoding="utf-8")
    line = one_error_line(run("init", written))
    assert "pump.toml" in line and "--force" in line
    assert written.read_text(encoding="utf-8") == before
    p = run("init", written, "--force")
    assert p.returncode == 0 and "# edited" not in written.read_text(encoding="utf-8")

    # '-' prints the same TOML to stdout, nothing else
    p = run("init", "-")
    assert p.returncode == 0 and tomllib.loads(p.stdout) == {**data, "name": "pump"}

    line = one_error_line(run("init", tmp_path / "no" / "such" / "dir" / "x.toml"))
    assert "x.toml" in line


def test_init_example_writes_the_shipped_example(tmp_path):
    """``init NAME --example village-10m`` writes the shipped example's text (configs/ in the
    repository), which loads and passes; an unknown name is one line."""
    root = Path(__file__).parents[2]
    listed = run("init", "--example", "list")
    assert listed.returncode == 0 and "village-10m" in listed.stdout
    p = run("init", "v.toml", "--example", "village-10m", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    written = (tmp_path / "v.toml").read_text(encoding="utf-8")
    assert written == (root / "configs" / "village-10m.toml").read_text(encoding="utf-8")
    # the same text as the shipped file, so the same verdict; that it loads and passes is checked here
    assert jrun("force", tmp_path / "v.toml", "--summary", expect=0)["verdict"] == "PASS"
    line = one_error_line(run("init", "x.toml", "--example", "village-11m", cwd=tmp_path))
    assert "village-11m" in line and not (tmp_path / "x.toml").exists()


# ----------------------------------------------------------------------------- --strict
def _prototype(tmp_path, speed, mass=None) -> Path:
    """configs/prototype.toml at another wheel speed [deg/s] (and with a wheel mass [kg])."""
    d = tomllib.loads((Path(__file__).parents[2] / "configs" / "prototype.toml").read_text(encoding="utf-8"))
    d["operator"]["speed"] = speed
    if mass is not None:
        d["wheel"]["mass"] = mass
    return write(tmp_path, d, f"proto-{speed}-{mass}.toml")


@pytest.mark.parametrize(
    "command,mass",
    [("force", None), ("speed", 20.0)],
)
def test_strict_fails_a_pass_with_warnings_and_passes_a_clean_pass(tmp_path, command, mass):
    """--strict (the CI gate): exit 1 where the verdict is PASS with warnings, 0 on a clean PASS.
    The prototype's grip moves at 3.28 m/s at 360 deg/s (warns above 2.5 m/s, docs/models.md §4)
    and at 2/3 of that at 240 deg/s; with a 20 kg wheel (full dynamics) the same holds."""
    sweep = ("--from", "240", "--to", "360", "--step", "120") if command == "speed" else ("--summary",)
    for speed, verdict, strict in ((360.0, "PASS with warnings", 1), (240.0, "PASS", 0)):
        spec = _prototype(tmp_path, speed, mass)
        p = run(command, spec, *sweep, "--format", "json")
        assert p.returncode == 0, p.stderr
        q = run(command, spec, *sweep, "--format", "json", "--strict")
        assert q.returncode == strict, q.stderr
        j, k = json.loads(p.stdout), json.loads(q.stdout)
        assert k.pop("strict", True) is True and j.pop("strict", False) is False
        assert k == j  # the same answer, another exit code
        if command == "speed":  # the row at the spec's own speed decides
            (j,) = [r for r in j["speeds"] if r["speed_deg_s"] == speed]
        assert j["verdict"] == verdict


def test_strict_optimize_follows_the_verdict_of_the_optimum(tmp_path):
    """optimize --strict: exit 1 when the optimum only passes with warnings (here its grip height,
    with the grip-height and stroke limits opened wide), 0 when it passes cleanly (the prototype
    at 240 deg/s, whose optimum's grip is slower than 2.5 m/s)."""
    relaxed = ("--vary", "D1=-0.5:0.8", "--grip-height", "0:5", "--stroke", "0:5", "--format", "json")
    p = run("optimize", "configs/prototype.toml", *relaxed, cwd=Path(__file__).parents[2])
    assert p.returncode == 0, p.stderr
    assert json.loads(p.stdout)["optimum"]["verdict"] == "PASS with warnings"
    q = run("optimize", "configs/prototype.toml", *relaxed, "--strict", cwd=Path(__file__).parents[2])
    assert q.returncode == 1, q.stderr
    j, k = json.loads(p.stdout), json.loads(q.stdout)
    assert k.pop("strict", True) is True and j.pop("strict", False) is False and k == j
    c = run("optimize", _prototype(tmp_path, 240.0), "--seed", "3", "--format", "json", "--strict")
    assert c.returncode == 0, c.stderr
    assert json.loads(c.stdout)["optimum"]["verdict"] == "PASS"


def test_bracketed_units_and_extras_survive_rich_markup_in_help():
    """Rich eats lowercase [tags]: units like [deg] and the extra [plot] must be escaped."""
    wants = {
        "force": ["[deg/s]", "[deg]", "pumplink[plot]"],
        "transmission": ["[deg]", "pumplink[plot]"],
        "optimize": ["[m]", "[deg]"],
    }
    for cmd, needles in wants.items():
        out = subprocess.run(
            [sys.executable, "-m", "pumplink", cmd, "--help"],
            capture_output=True,
            text=True,
            env={**os.environ, "COLUMNS": "250"},
            check=False,
        ).stdout
        for n in needles:
            assert n in out, (cmd, n)


def test_long_force_sweep_draws_a_progress_bar_on_a_terminal_only(tmp_path):
    """`force --summary` with a sweep of more than a second: a Rich bar on a terminal's stderr,
    nothing extra when stderr is a pipe (the verdict on stdout is the same)."""
    from terminal import run_on_terminal

    args = [*CMD, "force", "--summary", "--samples", "150000000", "--format", "json"]
    code, text, out = run_on_terminal(args)
    assert code == 0
    assert "force sweep" in text and "━" in text and "/1000" in text
    piped = subprocess.run(args, capture_output=True, check=False)
    assert piped.returncode == 0 and b"force sweep" not in piped.stderr
    assert json.loads(piped.stdout)["sampled_peak_force_N"] == json.loads(out)["sampled_peak_force_N"]


# ----------------------------------------------------------------------------- flywheel model
FLY = Path(__file__).parents[2] / "examples" / "well-12m-flywheel.toml"


def _result(j: dict, key: str) -> str:
    """The result of check ``key`` in a force JSON."""
    return next(c["result"] for c in j["checks"] if c["key"] == key)


def _force_json(*args):
    p = run("force", *args, "--summary", "--format", "json", cache=True)
    return p, json.loads(p.stdout)


def test_speed_decides_the_verdict_with_inertia():
    """The flywheel model's promise (--model flywheel): with inertia in the spec, --speed 360 and
    --speed 540 give different verdicts, each cross-checked by integrating the equation of motion
    (--verify).

    Physically right: a faster wheel stores J w^2 / 2, so the least peak force falls (from above the
    limit to below it), bounded below by the mean force; the power Mw w rises in proportion."""
    p360, j360 = _force_json(FLY, "--speed", "360", "--verify", "--model", "flywheel")
    p540, j540 = _force_json(FLY, "--speed", "540", "--verify", "--model", "flywheel")
    # the peak force decides between them; at 540 deg/s power and grip speed fail instead
    assert (p360.returncode, p540.returncode) == (1, 1), (p360.stderr, p540.stderr)
    assert [_result(j360, "peak_force"), _result(j540, "peak_force")] == ["fail", "pass"]
    assert [_result(j540, "power"), _result(j540, "grip_speed")] == ["fail", "fail"]
    for j in (j360, j540):
        assert j["model"] == "flywheel" and j["inertia_kg_m2"] > 0 and j["speed_fluctuation"] == 0.2
        assert j["verify"]["agrees"] is True
        assert j["verify"]["periodicity"] < 1e-6 and j["verify"]["fluctuation"] <= 0.2 * (1 + 1e-6)
        assert j["verify"]["mean_speed_deg_s"] == pytest.approx(j["speed_deg_s"], rel=1e-6)
        assert j["least_peak_force_N"] >= j["mean_force_N"] * (1 - 1e-12)
    assert j360["least_peak_force_N"] > 100 > j540["least_peak_force_N"]
    assert j360["pass"] is False and j540["pass"] is False
    assert j540["power_W"] == pytest.approx(1.5 * j360["power_W"], rel=1e-12)
    # The energy band scales as w^2: J w^2 delta (Eq. (2) of pumplink.models.flywheel).
    assert j540["energy_band_J"] == pytest.approx(2.25 * j360["energy_band_J"], rel=1e-12)
    # The speed-blind dead-band model passes this design at both speeds: the flywheel answer differs.
    assert j360["dead_band_peak_force_N"] < 100 < j360["peak_force_N"] == j360["least_peak_force_N"]


def test_full_dynamics_decides_the_shipped_example_and_the_arms_make_faster_harder():
    """Without --model the least model that is enough decides: the 12 m example's 1.2 m steel handle
    carries 1.5 x the flywheel's energy band, so full dynamics.  Its hand force still falls with
    speed (above the flywheel's: the handle's inertia and weight), but the operator's effort with
    their own arms rises past the best cadence; both speeds are cross-checked by --verify."""
    (p360, j360), (p540, j540) = (_force_json(FLY, "--speed", v, "--verify") for v in ("360", "540"))
    _, fly360 = _force_json(FLY, "--speed", "360", "--model", "flywheel")
    for j in (j360, j540):
        assert j["model"] == "full dynamics" and j["verify"]["agrees"] is True
        assert j["verify"]["periodicity"] < 1e-6 and j["link_kinetic_energy_J"] > 0.1 * j["energy_band_J"]
    assert j360["peak_force_N"] > 100 > j540["peak_force_N"]  # the hand force falls with speed
    assert j360["peak_force_N"] > fly360["peak_force_N"]  # the links cost force
    assert j540["effort_peak_force_N"] > j360["effort_peak_force_N"] > j360["peak_force_N"]


def test_verdict_flips_at_the_reported_minimum_speed():
    """min_passing_speed_deg_s (the flywheel's) is where the verdict changes: just below fails,
    just above passes."""
    _, j = _force_json(FLY, "--model", "flywheel")
    v = j["min_passing_speed_deg_s"]
    assert 360 < v < 540
    below, jb = _force_json(FLY, "--speed", f"{v * 0.999:.6f}", "--model", "flywheel")
    above, ja = _force_json(FLY, "--speed", f"{v * 1.001:.6f}", "--model", "flywheel")
    assert [_result(jb, "peak_force"), _result(ja, "peak_force")] == ["fail", "pass"]
    assert jb["least_peak_force_N"] > 100 > ja["least_peak_force_N"]


def test_samples_carry_the_operator_profile_and_wheel_speed():
    p = run("force", FLY, "--samples", "72", "--format", "json", cache=True)
    j = json.loads(p.stdout)
    rows = j["samples"]
    fp = j["least_peak_force_N"]
    ops = [r["operator_force_N"] for r in rows]
    ws = [r["wheel_speed_deg_s"] for r in rows]
    assert all(o is not None and abs(o) <= fp * (1 + 1e-12) for o in ops)
    assert max(abs(o) for o in ops) == pytest.approx(fp, rel=1e-12)  # the operator does push Fp somewhere
    lo, hi = j["wheel_speed_range_deg_s"]["min"], j["wheel_speed_range_deg_s"]["max"]
    assert all(lo * (1 - 1e-9) <= w <= hi * (1 + 1e-9) for w in ws)
    assert (hi + lo) / 2 == pytest.approx(360.0, rel=1e-12) and (hi - lo) / 360.0 == pytest.approx(
        0.2, rel=1e-9
    )
    # Quasi-static specs keep the same columns: the quasi-static force at a constant speed.
    q = json.loads(run("force", "--samples", "8", "--format", "json", cache=True).stdout)
    assert q["model"] == "quasi-static + dead band" and q["least_peak_force_N"] is None
    assert all(r["wheel_speed_deg_s"] == 360.0 for r in q["samples"])
    assert all(r["operator_force_N"] == r["force_N"] for r in q["samples"])


def test_table_names_the_model_that_answered():
    dyn = run("force", FLY, "--summary", cache=True).stdout
    # no speed passes (the grip is too fast where the force passes; the speeds are judged with a
    # ratchet fitted, so its checks are left out): the verdict line says so
    nowhere = "some check besides the ratchet's fails at every mean speed from 60 to 1440 deg/s"
    assert (
        "model: full dynamics, J = " in dyn and "VERDICT: FAIL" in dyn and nowhere in " ".join(dyn.split())
    )  # (the words joined over the wrapped lines, their trailing spaces too)
    fly = run("force", FLY, "--summary", "--model", "flywheel", cache=True).stdout
    assert "model: flywheel, J = " in fly and "VERDICT: FAIL" in fly and nowhere in " ".join(fly.split())
    qs = run("force", "--summary", cache=True).stdout
    assert "model: quasi-static + dead band" in qs and "give wheel.mass or wheel.inertia" in qs


def test_explain_reports_effects_and_reason():
    p, j = _force_json(FLY, "--explain")
    ex = j["explain"]
    names = [e["effect"] for e in ex["effects"]]
    assert any("coupler + handle" in n for n in names) and any("power" in n for n in names)
    link = next(e for e in ex["effects"] if "kinetic energy of coupler + handle" in e["effect"])
    weight = next(e for e in ex["effects"] if "weight of coupler + handle" in e["effect"])
    arms = next(e for e in ex["effects"] if "arms" in e["effect"])
    for e in (link, weight, arms):
        assert e["ratio"] == pytest.approx(e["value"] / j["energy_band_J"], rel=1e-12)
    # a 1.2 m steel handle at 360 deg/s carries more energy than the band: full dynamics decides,
    # with the links in the model and the arms only in the effort
    assert link["ratio"] > 1 and link["included"] and weight["included"] and not arms["included"]
    assert ex["why"].startswith("Full dynamics decided") and "more than 10%" in ex["why"]
    assert j["link_kinetic_energy_J"] == link["value"] and j["link_weight_J"] == weight["value"]
    cad = ex["best_cadence"]  # no speed passes: the grip is too fast where the force passes
    assert cad["speed_deg_s"] is None and cad["verdict_passes_deg_s"] is None
    assert cad["force_passes_deg_s"]["min"] == 390.0
    # the flywheel asked for where it is not enough: the reason says so
    _, f = _force_json(FLY, "--explain", "--model", "flywheel")
    assert f["explain"]["why"].startswith("Flywheel decided because --model flywheel asked for it")
    q = run("force", "--summary", "--explain", cache=True).stdout
    assert "Quasi-static + dead band decided" in q and "Model choice" in q


def test_verify_without_inertia_checks_the_quasi_static_answer():
    """Without inertia --verify checks virtual work from positions and the exact peak against a
    dense sweep (the quasi-static model has no motion to integrate)."""
    p = run("force", "--summary", "--verify", "--format", "json", cache=True)
    assert p.returncode == 0, p.stderr
    v = json.loads(p.stdout)["verify"]
    assert v["agrees"] is True and v["virtual_work"] < 1e-6 and v["angles"] > 1000
    assert v["peak_force_N"] * (1 - 1e-3) <= v["sweep_peak_force_N"] <= v["peak_force_N"] * (1 + 1e-9)


def test_speed_command(tmp_path):
    p = run("speed", FLY, "--from", "300", "--to", "600", "--step", "60", "--format", "json", cache=True)
    assert p.returncode == 1  # the spec's own 360 deg/s fails
    j = json.loads(p.stdout)
    sp = [r["speed_deg_s"] for r in j["speeds"]]
    assert sp == [300.0, 360.0, 420.0, 480.0, 540.0, 600.0]
    f = [r["peak_force_N"] for r in j["speeds"]]
    assert all(a > b for a, b in zip(f, f[1:]))  # faster: less hand force
    assert all(r["model"] == "full dynamics" for r in j["speeds"])
    assert all(r["dynamics_peak_force_N"] > r["flywheel_peak_force_N"] for r in j["speeds"])
    # the force passes from the least passing speed on, but the grip then moves faster than 4 m/s
    cad = j["best_cadence"]
    assert [x <= 100 for x in f] == [v >= cad["force_passes_deg_s"]["min"] for v in sp]
    assert cad["verdict_passes_deg_s"] is None
    assert [r["pass"] for r in j["speeds"]] == [False] * 6 and all(
        r["grip_speed_m_s"] > 4 for r in j["speeds"]
    )
    _, one = _force_json(FLY, "--speed", "480")
    assert f[3] == pytest.approx(one["least_peak_force_N"], rel=1e-12)  # same numbers as `force`
    assert j["speeds"][3]["verdict"] == one["verdict"] == "FAIL"
    import figures

    png = tmp_path / "s.png"
    t = figures.run("speed", FLY, "--plot", png, env=_env({"COLUMNS": "80"}))
    assert png.read_bytes()[:4] == b"\x89PNG" and "within 100 N: from 390 deg/s up" in t.stdout
    assert "best cadence" not in t.stdout and "some check fails at every speed" in t.stdout
    # the chart (read from the figure): the models' curves and the limits in the legend, and the
    # best cadence starred where the JSON puts it
    chart = figures.read(png)
    ax = chart["axes"][0]
    assert ax["title"].startswith("Well, 12 m head: the force a person needs against cadence (J = ")
    assert chart["figure_legend"][:2] == ["flywheel (links' inertia neglected)", "full dynamics: hand force"]
    assert "force limit 100 N" in chart["figure_legend"]
    assert figures.marked(ax, "*") == []  # no best cadence where no speed passes
    q = run("speed", "configs/prototype.toml", cwd=Path(__file__).parents[2])
    assert q.returncode == 2 and q.stderr.count("\n") == 1 and "wheel.mass" in q.stderr
    bad = run("speed", FLY, "--from", "500", "--to", "100")
    assert bad.returncode == 2 and "--to" in bad.stderr


def test_zero_inertia_fails_cleanly(tmp_path):
    """load.moving_mass = 0 and no wheel mass: a flywheel with J = 0 has no energy band, so no finite
    peak force keeps the wheel turning (the limit W -> 0).  Found by review: it used to raise
    ZeroDivisionError in the link-energy share and in --explain."""
    d = tomllib.loads((Path(__file__).parents[2] / "configs" / "prototype.toml").read_text(encoding="utf-8"))
    d["load"]["moving_mass"] = 0.0
    spec = tmp_path / "j0.toml"
    spec.write_text(tomli_w.dumps(d), encoding="utf-8")
    p = run("force", spec, "--summary", "--explain", "--verify", "--format", "json", "--model", "flywheel")
    assert p.returncode == 1 and "Traceback" not in p.stderr and "nothing to integrate" in p.stderr
    j = json.loads(p.stdout)
    assert j["model"] == "flywheel" and j["inertia_kg_m2"] == 0 and j["least_peak_force_N"] is None
    assert j["pass"] is False and j["verify"] is None  # asked for, nothing to integrate: null (docs/json.md)
    # by the least model that is enough: the links are the only flywheel, full dynamics decides
    a = json.loads(run("force", spec, "--summary", "--format", "json").stdout)
    assert a["model"] == "full dynamics" and a["peak_force_N"] > 1000 and a["pass"] is False
