"""The CLI's contract under abuse: one line on stderr, the right exit code, no traceback.

Every case here is a class of input that once produced a traceback, a multi-line usage panel, a
wrong exit code or a clobbered file.  The expected behaviour is the contract in README.md
(exit codes 0/1/2/130, one-line errors, atomic and device-safe outputs, bounded inputs).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
CMD = [sys.executable, "-m", "pumplink"]


def env() -> dict:
    e = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS")}
    e["PYTHONIOENCODING"] = "utf-8"
    return e


def run(*args, cwd=ROOT, stdout=subprocess.PIPE, timeout=120) -> subprocess.CompletedProcess:
    return subprocess.run(
        [*CMD, *map(str, args)],
        stdout=stdout,
        stderr=subprocess.PIPE,
        env=env(),
        cwd=cwd,
        timeout=timeout,
        encoding="utf-8",
        errors="replace",
    )


def one_error_line(p: subprocess.CompletedProcess, code: int = 2) -> str:
    """Exit ``code``, nothing on stdout, exactly one printable line on stderr; return it."""
    assert p.returncode == code, (p.returncode, p.stdout, p.stderr)
    assert not p.stdout, p.stdout
    assert "Traceback" not in p.stderr, p.stderr
    lines = p.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    assert "\x1b" not in lines[0] and "\r" not in lines[0], repr(lines[0])
    return lines[0]


# ----------------------------------------------------------------------------- option errors
@pytest.mark.parametrize(
    "args,words",
    [
        (["force", "--samples", "0"], ["--samples 0", ">= 1", "pumplink force --help"]),
        (["force", "--speed", "nan"], ["--speed nan", "not a finite number"]),
        (["force", "--speed", "inf"], ["--speed inf", "not a finite number"]),
        (["force", "--format", "xml"], ["--format xml", "'table', 'json', 'csv'"]),
        (["force", "--bogus"], ["No such option: --bogus", "pumplink force --help"]),
        (["force", "--samples=abc"], ["--samples abc", "not a valid integer"]),
        (["batch", "--workers", "1000", "configs"], ["--workers 1000", "<= 256"]),
        (["draw"], ["Missing argument", "pumplink draw --help"]),
        (["nonsense"], ["No such command", "nonsense"]),
    ],
)
def test_option_errors_are_one_line_like_spec_errors(args, words):
    line = one_error_line(run(*args))
    for w in words:
        assert w in line, line
    # `--speed nan` once said "less than or equal to 7200": NaN fails every comparison
    assert "7200" not in line or "nan" not in line


def test_an_option_value_with_control_characters_is_escaped():
    line = one_error_line(run("force", "--samples", "1\x1b[2J\n2"))
    assert "\\x1b[2J\\n2" in line


def test_pumplink_alone_prints_the_help_and_exits_2():
    p = run()
    assert p.returncode == 2 and "Usage" in p.stdout and "Traceback" not in p.stderr


# ----------------------------------------------------------------------------- full disk
@pytest.mark.parametrize("fmt", ["table", "json", "csv"])
def test_a_full_disk_on_stdout_is_one_line_exit_2(fmt):
    with open("/dev/full", "w") as full:
        p = run("force", "--summary", "--format", fmt, stdout=full)
    assert p.returncode == 2, p.stderr
    assert p.stderr.count("\n") == 1 and "No space left on device" in p.stderr, p.stderr


# ----------------------------------------------------------------------------- output paths
@pytest.mark.parametrize(
    "args",
    [
        ["force", "--plot", "/nonexistent/dir/x.png"],
        ["speed", "examples/well-12m-flywheel.toml", "--plot", "/nonexistent/dir/x.png"],
        ["batch", "configs", "--format", "csv", "--out", "/nonexistent/dir/x.csv"],
        ["batch", "configs", "--junit", "/nonexistent/dir/x.xml"],
        ["optimize", "configs/prototype.toml", "--write", "/nonexistent/dir/x.toml"],
        ["transmission", "--chart", "/nonexistent/dir/x.png"],
    ],
)
def test_an_output_in_a_missing_folder_is_one_line_before_any_work(args):
    t0 = time.monotonic()
    line = one_error_line(run(*args))
    assert "/nonexistent/dir" in line and "does not exist" in line, line
    assert time.monotonic() - t0 < 30  # refused up front (optimize would take minutes)


@pytest.mark.parametrize("opt", ["--out", "--junit"])
def test_a_full_device_as_output_is_one_line(opt):
    extra = ["--format", "csv"] if opt == "--out" else []
    line = one_error_line(run("batch", "configs", *extra, opt, "/dev/full"))
    assert "/dev/full" in line and "No space left on device" in line


def _fsize_limit(limit: int):
    def apply():  # a file-size limit fails writes like a full disk (EFBIG), without a full disk
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return apply


@pytest.mark.parametrize(
    "args",
    [
        ["batch", "configs", "--format", "csv", "--out", "{d}/rows.csv"],
        ["batch", "configs", "--junit", "{d}/rows.xml"],
        ["force", "--plot", "{d}/curve.png"],
    ],
)
def test_a_write_that_fails_midway_is_one_line_and_leaves_nothing(tmp_path, args):
    p = subprocess.run(
        [*CMD, *(a.format(d=tmp_path) for a in args)],
        capture_output=True,
        text=True,
        env=env(),
        cwd=ROOT,
        preexec_fn=_fsize_limit(500),
        timeout=120,
    )
    assert p.returncode == 2, p.stderr
    assert "Traceback" not in p.stderr and "cannot be written (File too large)" in p.stderr, p.stderr
    assert list(tmp_path.iterdir()) == []  # no partial file, no temp file


@pytest.mark.parametrize("opt", ["--out", "--junit"])
def test_a_device_output_is_written_in_place_never_replaced(tmp_path, opt):
    # as root, an atomic rename over /dev/null once replaced the device with a regular file;
    # a FIFO here stands for any non-regular file (and needs no root)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    extra = ["--format", "csv"] if opt == "--out" else []
    p = subprocess.Popen(
        [*CMD, "batch", "configs", *extra, opt, str(fifo)],
        cwd=ROOT,
        env=env(),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    with open(fifo) as reader:
        text = reader.read()
    assert p.wait(timeout=120) == 0, p.stderr.read()
    assert ("prototype" in text) and fifo.is_fifo()
    assert sorted(f.name for f in tmp_path.iterdir()) == ["fifo"]


def test_dev_null_stays_a_device():
    p = run("batch", "configs", "--format", "csv", "--out", "/dev/null", "--junit", "/dev/null")
    assert p.returncode == 0, p.stderr
    assert Path("/dev/null").is_char_device()


def test_a_symlinked_output_replaces_the_target_and_keeps_the_link(tmp_path):
    link, real = tmp_path / "link.csv", tmp_path / "real.csv"
    real.write_text("old\n")
    link.symlink_to(real.name)
    assert run("batch", "configs", "--format", "csv", "--out", link).returncode == 0
    assert link.is_symlink() and real.read_text().startswith("name,")
    assert sorted(f.name for f in tmp_path.iterdir()) == ["link.csv", "real.csv"]


def test_a_sigkilled_batch_leaves_no_file_at_all(tmp_path):
    grid = tmp_path / "big.toml"
    grid.write_text(
        f'base = "{ROOT / "configs" / "prototype.toml"}"\n[vary]\n'
        '"linkage.rocker" = { start = 0.15, stop = 0.3, num = 100 }\n'
        '"linkage.swing" = { start = 40, stop = 80, num = 100 }\n'
    )
    out = tmp_path / "out"
    out.mkdir()
    p = subprocess.Popen(
        [*CMD, "batch", grid, "--format", "csv", "--out", out / "rows.csv", "--samples", "4000"],
        cwd=ROOT,
        env=env(),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None and not _holds_file_in(p.pid, out):
        time.sleep(0.05)
    assert p.poll() is None, "the run finished before it could be killed"
    p.kill()  # SIGKILL: no handler runs, no clean-up: the temp file must have no name
    p.wait(timeout=30)
    assert list(out.iterdir()) == []


def _holds_file_in(pid: int, folder: Path) -> bool:
    try:
        return any(os.readlink(fd).startswith(str(folder)) for fd in Path(f"/proc/{pid}/fd").iterdir())
    except OSError:
        return False


# ----------------------------------------------------------------------------- values at the edges
def _json(*args) -> dict:
    import json

    p = run(*args, "--format", "json")
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)


def test_a_huge_crank_angle_is_reduced_exactly_in_degrees():
    # 1e50 is an integer in binary64, and 10**50 mod 360 = 320 exactly (integer arithmetic);
    # reducing after converting to radians gave -513.19 N and a wrong dead-band flag
    assert int(1e50) % 360 == 320
    far, near = (_json("force", "--at", a)["samples"][0] for a in ("1e50", "320"))
    assert far == near and round(far["force_N"], 2) == 42.07


@pytest.mark.parametrize(
    "given,deg_s", [("60rpm", 360.0), ("90 RPM", 540.0), ("360deg/s", 360.0), ("240", 240.0)]
)
def test_speed_takes_units(given, deg_s):
    assert _json("force", "--summary", "--speed", given)["speed_deg_s"] == deg_s


def test_speed_in_rad_per_s():
    got = _json("force", "--summary", "--speed", "3.141592653589793rad/s")["speed_deg_s"]
    assert abs(got - 180.0) < 1e-12


@pytest.mark.parametrize(
    "value,words", [("60furlongs", "unknown unit"), ("1300rpm", "1200 rpm"), ("nanrpm", "not a finite")]
)
def test_speed_units_errors_are_one_line(value, words):
    assert words in one_error_line(run("force", "--speed", value))


@pytest.mark.parametrize(
    "args,code,words",
    [
        (["--time-ratio", "1e6"], 1, "no crank-rocker"),
        (["--time-ratio", "100", "--format", "json"], 1, "no crank-rocker"),
        (["--swing", "0.001"], 0, None),
        (["--swing", "1e-300"], 2, "--swing 1e-300: the rocker swing is out of range"),
        (["--swing", "179.9999"], 1, None),  # answers, but its transmission angle is 0: FAIL
        (["--swing", "180"], 2, "--swing 180: the rocker swing is out of range"),
        (["--rocker", "1e300"], 2, "--rocker"),
        (["--time-ratio", "1e300", "--swing", "0.5"], 1, "no crank-rocker"),
    ],
)
def test_transmission_at_extreme_inputs_answers_or_says_why(args, code, words):
    p = run("transmission", *args)
    assert p.returncode == code and "Traceback" not in p.stderr, (p.returncode, p.stderr)
    if words is None:
        assert "γmin" in p.stdout and "—" not in p.stdout.split("γmin")[1][:40]
    else:
        assert words in one_error_line(p, code)


def test_optimize_seed_minus_one_is_one_line():
    assert "--seed -1" in one_error_line(run("optimize", "configs/prototype.toml", "--seed", "-1"))


# ----------------------------------------------------------------------------- signals
def _catches_sigterm(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    caught = int(next(line for line in status.splitlines() if line.startswith("SigCgt:")).split()[1], 16)
    return bool(caught >> (signal.SIGTERM - 1) & 1)


@pytest.mark.parametrize("args", [["force", "--samples", "100000000", "--summary"], ["speed", "nope.toml"]])
def test_sigterm_as_soon_as_it_is_handled_exits_130(args):
    # once the handler was installed only inside `batch`: SIGTERM elsewhere gave 143
    p = subprocess.Popen([*CMD, *args], cwd=ROOT, env=env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 30
    while not _catches_sigterm(p.pid) and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.001)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, err)
    assert b"Traceback" not in err


def test_junit_parses_when_a_file_name_has_control_characters(tmp_path):
    import xml.etree.ElementTree as ET

    folder = tmp_path / "in"
    folder.mkdir()
    text = (ROOT / "configs" / "prototype.toml").read_text(encoding="utf-8")
    (folder / "p\x1bq.toml").write_text(text, encoding="utf-8")  # the spec names itself
    report = tmp_path / "r.xml"
    assert run("batch", folder, "--junit", report).returncode == 0
    suites = ET.parse(report).getroot()  # XML 1.0 cannot carry \x1b even as &#27;
    assert [s.get("name") for s in suites] == [str(folder / "p\\x1bq.toml")]
