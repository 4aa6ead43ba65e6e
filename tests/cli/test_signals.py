"""SIGTERM and Ctrl-C at any moment of a run: exit 130 and no output file, or the run's own exit
with every file complete (README, "Contract": exit codes 0, 1, 2, 130 and nothing else).

A signal is sent at random moments of real runs of the console script.  How the two accepted
outcomes are told apart:

* **130**: stderr says "interrupted" and no output file (nor a temporary one) exists;
* **0 or 1** (the run's own verdict): the signal came once the run was writing its files or had
  finished.  stderr then carries the run's last line (``... wrote FILE``) and every file is
  complete: the CSV has every variant's row, the JUnit XML parses with every test case.

Anything else fails: death by the signal (-15, -2), 2, a traceback, a partial or leftover file.

The contract starts when pumplink's handler does.  Before it, the interpreter is starting and none
of pumplink's code has run (roughly 50-150 ms here, longer on a loaded machine), so no program can
answer a signal there: SIGTERM's default action kills the process (-15), and a SIGINT meets
CPython's own handler, whose KeyboardInterrupt can stop the start-up ("Fatal Python error:
init_import_site", exit 1), kill it (-2), or be printed by CPython and swallowed ("Failed checking
if argv[0] is an import path entry ... KeyboardInterrupt"), after which the run goes on and exits
with its verdict.  When the handler is in place is read from the kernel (``/proc/PID/status``,
SigCgt: is SIGTERM caught?  pumplink installs its SIGINT and SIGTERM handlers together, the
SIGINT one first; CPython's own SIGINT handler does not set the SIGTERM bit).  The Ctrl-C test
waits for that moment before its random delay starts (:func:`try_once`, ``after_handler``), so it
tests pumplink alone and cannot meet CPython's start-up; the SIGTERM tests of ``batch`` also send
into the start-up, where the default action is the one outcome (-15, accepted only when the kernel
said the handler was not yet in place).  :func:`test_the_handler_comes_before_the_heavy_imports`
pins that the handler is installed before typer and the command modules are imported, so that the
window left to the interpreter is its start alone.
"""

from __future__ import annotations

import csv
import os
import random
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PROTOTYPE = ROOT / "configs" / "prototype.toml"

#: The console script next to this interpreter (what a user runs), else ``python -m pumplink``.
_SCRIPT = Path(sys.executable).with_name("pumplink")
CMD = [str(_SCRIPT)] if _SCRIPT.is_file() else [sys.executable, "-m", "pumplink"]

pytestmark = pytest.mark.skipif(
    not Path("/proc/self/status").is_file(),
    reason="these tests read a process's signal handlers from /proc/<pid>/status, which only Linux has",
)


def env() -> dict:
    e = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS")}
    e["PYTHONIOENCODING"] = "utf-8"
    return e


def catches_sigterm(pid: int) -> bool:
    """True once the process has a handler for SIGTERM (the kernel's SigCgt mask)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = int(next(line for line in status.splitlines() if line.startswith("SigCgt:")).split()[1], 16)
    return bool(mask >> (signal.SIGTERM - 1) & 1)


def small_grid(folder: Path) -> Path:
    """A 4-variant batch file (one variant fails the verdict, so a complete run exits 1)."""
    grid = folder / "grid.toml"
    grid.write_text(
        f'base = "{PROTOTYPE}"\n[vary]\n"linkage.rocker" = [0.2, 0.25]\n"linkage.swing" = [50, 60]\n',
        encoding="utf-8",
    )
    return grid


def try_once(
    args: list, delay: float, sig: int = signal.SIGTERM, after_handler: bool = False
) -> tuple[int, str, bool]:
    """Start the command, send ``sig`` after ``delay`` seconds (or when it has ended); return the
    exit code, stderr followed by stdout, and whether pumplink's handler was in place when the
    signal went.  ``after_handler``: the delay counts from the moment the kernel shows pumplink's
    handler in place (:func:`catches_sigterm`), not from the start."""
    p = subprocess.Popen(
        [*CMD, *map(str, args)],
        cwd=ROOT,
        env=env(),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    if after_handler:
        deadline = time.monotonic() + 30
        while not catches_sigterm(p.pid) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.0005)
    t_end = time.monotonic() + delay
    while time.monotonic() < t_end and p.poll() is None:
        time.sleep(0.001)
    handled = catches_sigterm(p.pid)
    if p.poll() is None:
        p.send_signal(sig)
    out, err = p.communicate(timeout=60)
    return p.returncode, (err + out).decode("utf-8", "replace"), handled


def leftovers(folder: Path) -> list[str]:
    return sorted(f.name for f in folder.iterdir() if f.name.startswith("."))


def check_outcome(
    code: int, err: str, handled: bool, files: dict[Path, int], done_word: str, sig: int = signal.SIGTERM
) -> str:
    """The contract for one try; ``files`` maps each output to the test cases/rows it must hold
    when complete.  Returns which outcome it was."""
    # before any of pumplink's code ran: death by the signal; a SIGINT meets Python's own
    # handler, which can also stop the interpreter's start-up ("Fatal Python error", exit 1)
    python_start = (-sig, 1) if sig == signal.SIGINT else (-sig,)
    if not handled and code in python_start and (code < 0 or "init_import_site" in err):
        assert not any(f.exists() for f in files), err
        return "before pumplink"
    assert "Traceback" not in err, err
    if code == 130:
        assert "interrupted" in err, err
        assert not any(f.exists() for f in files), [f for f in files if f.exists()]
        return "130"
    assert code in (0, 1), (code, handled, err)
    assert done_word in err, err  # the run's own last words: it had finished
    for f, n in files.items():
        if f.suffix == ".csv":
            with f.open(encoding="utf-8", newline="") as fh:
                assert len(list(csv.DictReader(fh))) == n, f
        elif f.suffix == ".xml":
            assert len(ET.parse(f).getroot().findall(".//testcase")) == n, f
    return "complete"


#: Tries per test: 20 random moments of a ~1 s run cover its start-up (where 9 of 9 tries once
#: died by the signal) in a few seconds.
TRIES = 20
#: The one line pumplink prints when a signal ends a run (pumplink.cli._interrupted).
INTERRUPTED = "interrupted; no output file written"


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_in_the_first_200_ms_of_force_exits_130(sig):
    """From the moment pumplink's handler is in place (the kernel's word), a signal at a random
    moment of the next 200 ms (typer, the command modules, numpy, the run) ends ``force`` with 130
    and pumplink's one line, or, once the run has finished, lets it exit with its verdict; the
    interpreter's start-up before it is left out (the module's docstring: no program runs there,
    and CPython's own Ctrl-C handling once made this test fail a clean clone one run in a few)."""
    rng = random.Random(26)
    seen = []
    for _ in range(TRIES):
        code, err, handled = try_once(
            ["force", PROTOTYPE, "--summary"], rng.uniform(0, 0.2), sig, after_handler=True
        )
        outcome = check_outcome(code, err, handled, {}, "VERDICT", sig)
        assert outcome != "before pumplink", (code, err)  # the signal went after the handler
        if outcome == "130":
            assert err.splitlines()[0] == INTERRUPTED and "KeyboardInterrupt" not in err, err
        seen.append(outcome)
    assert "130" in seen, seen  # not vacuous: the handler was reached in some tries


def test_a_signal_in_the_first_200_ms_of_batch_leaves_no_file(tmp_path):
    grid = small_grid(tmp_path)
    rng = random.Random(126)
    seen = []
    for i in range(TRIES):
        out, junit = tmp_path / f"rows{i}.csv", tmp_path / f"r{i}.xml"
        args = ["batch", grid, "--format", "csv", "--out", out, "--junit", junit]
        code, err, handled = try_once(args, rng.uniform(0, 0.2))
        seen.append(check_outcome(code, err, handled, {out: 4, junit: 4}, "wrote"))
        assert leftovers(tmp_path) == []
    assert "130" in seen, seen


def test_a_signal_anywhere_in_a_batch_run_leaves_no_partial_file(tmp_path):
    """Random moments over the whole run (its end included: the files being moved into place)."""
    grid = small_grid(tmp_path)
    t0 = time.monotonic()
    subprocess.run([*CMD, "batch", grid, "--format", "csv"], cwd=ROOT, env=env(), capture_output=True)
    length = time.monotonic() - t0
    rng = random.Random(226)
    seen = []
    for i in range(6):
        out, junit = tmp_path / f"rows{i}.csv", tmp_path / f"r{i}.xml"
        args = ["batch", grid, "--format", "csv", "--out", out, "--junit", junit]
        code, err, handled = try_once(args, rng.uniform(0.5, 1.2) * length)
        seen.append(check_outcome(code, err, handled, {out: 4, junit: 4}, "wrote"))
        assert leftovers(tmp_path) == []
    assert set(seen) - {"before pumplink"}, seen


def test_a_signal_right_after_wrote_lets_the_run_complete(tmp_path):
    """SIGTERM the moment the batch's last line ("... wrote FILE") reaches stderr: the run has
    finished and its files are complete, so it exits with its own code (1: one variant fails),
    never dying by the signal in the interpreter's tear-down (3-12 of 30 tries once did)."""
    grid = small_grid(tmp_path)
    for i in range(8):
        out, junit = tmp_path / f"rows{i}.csv", tmp_path / f"r{i}.xml"
        p = subprocess.Popen(
            [*CMD, "batch", str(grid), "--format", "csv", "--out", str(out), "--junit", str(junit)],
            cwd=ROOT,
            env=env(),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        lines = []
        for line in p.stderr:
            lines.append(line.decode())
            if b"wrote" in line:
                p.send_signal(signal.SIGTERM)
                break
        err = "".join(lines) + p.stderr.read().decode()
        p.wait(timeout=60)
        assert p.returncode == 1, (p.returncode, err)
        assert check_outcome(p.returncode, err, True, {out: 4, junit: 4}, "wrote") == "complete"
        assert leftovers(tmp_path) == []


PROBE = """
import runpy, signal, sys
seen = {}
def audit(event, args):
    if event == "import" and args[0] not in seen and args[0].split(".")[0] in ("typer", "pumplink"):
        seen[args[0]] = type(signal.getsignal(signal.SIGTERM)).__name__
sys.addaudithook(audit)
sys.argv = ["pumplink", "--version"]
try:
    RUN
except SystemExit:
    pass
print(seen)
"""


@pytest.mark.parametrize(
    "how",
    [
        'runpy.run_module("pumplink", run_name="__main__", alter_sys=True)',  # python -m pumplink
        f"runpy.run_path({CMD[0]!r}, run_name='__main__')",  # the console script
    ],
    ids=["module", "script"],
)
def test_the_handler_comes_before_the_heavy_imports(how):
    """Run as the program (``python -m pumplink`` or the console script), the SIGTERM handler is
    in place before typer and every command module is imported (it was once installed after
    them, at 20-80 ms)."""
    # make test installs pumplink (pip install -e), so its console script is there: a missing one
    # is a broken install, not a reason to leave the script's start-up untested
    assert "run_path" not in how or _SCRIPT.is_file(), f"no console script at {_SCRIPT}"
    probe = PROBE.replace("RUN", how)
    p = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, env=env(), capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    seen = eval(p.stdout.strip().splitlines()[-1])  # a dict literal printed by the probe
    assert seen["pumplink.cli"] == "Handlers"  # the default action while pumplink.cli starts
    assert seen["typer"] == "Interrupt", seen
    commands = [m for m in seen if m.startswith("pumplink.cli.") and m != "pumplink.cli"]
    assert "pumplink.cli.force" in commands and "pumplink.cli.batch" in commands
    assert {seen[m] for m in commands} == {"Interrupt"}, seen


#: A command running under the program's handler and hook whose Ctrl-C is raised inside a weak
#: reference's callback (as the import system's module locks have them), where Python cannot
#: propagate it; the run then sleeps for a second, in its own code.
LOST_INTERRUPT = """
import signal, sys, time, weakref
from pumplink import cli
cli.INTERRUPT.install()
sys.unraisablehook = cli._unraisable(sys.unraisablehook)
cli.INTERRUPT.start()
class Thing:
    pass
thing = Thing()
ref = weakref.ref(thing, lambda _ref: signal.raise_signal(signal.SIGINT))
try:
    del thing
    for _ in range(200):
        time.sleep(0.005)
    print("lost")
except KeyboardInterrupt:
    print("delivered")
"""


def test_an_interrupt_python_could_not_raise_is_delivered_again_not_printed():
    """A KeyboardInterrupt the handler raised inside a callback Python cannot propagate from (a
    weak reference's, as the import system's module locks use) reaches ``sys.unraisablehook``,
    which printed it as "Exception ignored ... Traceback" while the run went on (seen in the
    first-200-ms test): the program's hook delivers it again, raised in the command's own code.
    Run for real in a subprocess: the hook once re-sent the signal from inside itself, where the
    handler's KeyboardInterrupt was printed and lost again ("Exception ignored in
    sys.unraisablehook"; a stand-in handler that did not raise hid it)."""
    p = subprocess.run(
        [sys.executable, "-c", LOST_INTERRUPT], cwd=ROOT, env=env(), capture_output=True, text=True
    )
    assert (p.returncode, p.stdout, p.stderr) == (0, "delivered\n", "")


def test_the_hook_leaves_other_exceptions_and_a_late_interrupt_to_the_hook_before_it():
    """Any other unraisable exception, and a KeyboardInterrupt once the run is past its point of
    no return (it completes), go to the hook that was there before."""
    import types

    from pumplink import cli

    printed = []
    hook = cli._unraisable(printed.append)
    state = (cli.INTERRUPT.running, cli.INTERRUPT.held, cli.INTERRUPT.interrupted)
    try:
        cli.INTERRUPT.running, cli.INTERRUPT.held, cli.INTERRUPT.interrupted = True, False, True
        other = types.SimpleNamespace(exc_type=ValueError)
        hook(other)
        cli.INTERRUPT.held = True  # past the point of no return: the run completes, as before
        late = types.SimpleNamespace(exc_type=KeyboardInterrupt)
        hook(late)
        assert printed == [other, late] and cli.INTERRUPT.interrupted is True
    finally:
        cli.INTERRUPT.running, cli.INTERRUPT.held, cli.INTERRUPT.interrupted = state


#: A command, run by the program's main(), whose interrupt lands while Python calls a descriptor's
#: ``__set_name__`` (as importing pydantic's dataclasses does): Python 3.11 re-raises the
#: handler's KeyboardInterrupt as "RuntimeError: Error calling __set_name__ ...".
DISGUISED_INTERRUPT = """
import signal, sys
from pumplink import cli
cli.INTERRUPT.install()
def run(args):
    class Named:
        def __set_name__(self, owner, name):
            signal.raise_signal(signal.SIGINT)
    class Owner:
        field = Named()
    return 0
cli._run = run
cli.main()
"""


def test_an_interrupt_python_re_raised_as_another_exception_still_exits_130():
    """The handler's KeyboardInterrupt wrapped by Python in another exception (its cause) is the
    interrupt: exit 130 with pumplink's one line, not a traceback and exit 1 (seen in the
    first-200-ms test while the machine was loaded: pydantic's import was interrupted)."""
    p = subprocess.run(
        [sys.executable, "-c", DISGUISED_INTERRUPT], cwd=ROOT, env=env(), capture_output=True, text=True
    )
    assert (p.returncode, p.stderr, p.stdout) == (130, INTERRUPTED + "\n", "")
