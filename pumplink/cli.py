"""Command-line interface: load spec -> call the library -> hand rows to ``pumplink.report``.

Exit codes: 0 every design passes (or is feasible, for ``synth``); 1 a design fails a check or
is infeasible; 2 the input cannot be used (one line on stderr, no traceback; ``--debug`` shows it).
Heavy imports (numpy, pydantic, scipy) happen inside the commands so ``--help`` starts fast.
"""

from __future__ import annotations

import signal
import sys
from enum import Enum
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.errors import PumplinkError, SpecError

app = typer.Typer(
    name="pumplink",
    help="Design the four-bar linkage that lets a standing operator drive a rope pump by hand.\n\n"
         "Example: [bold]pumplink init pump.toml && pumplink force pump.toml --speed 360[/]",
    no_args_is_help=True,
    rich_markup_mode="rich",
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
    add_completion=False,
)

_state = {"debug": False}


class Format(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


FormatOpt = Annotated[Format, typer.Option("--format", "-f", help="Output: table (Rich), json or csv.")]
SAMPLE_LIMIT_KEPT = 1_000_000


def _version(value: bool) -> None:
    if value:
        from importlib.metadata import version

        typer.echo(f"pumplink {version('pumplink')}")
        raise typer.Exit()


@app.callback()
def _main(
    debug: Annotated[bool, typer.Option("--debug", help="Show the full traceback on errors.")] = False,
    version: Annotated[Optional[bool], typer.Option("--version", callback=_version, is_eager=True,
                                                    help="Print the version and exit.")] = None,
) -> None:
    _state["debug"] = debug


def _load(paths: list[Path]):
    from pumplink.spec import load_spec

    return [load_spec(p) for p in paths]


@app.command()
def synth(
    specs: Annotated[list[Path], typer.Argument(help="One or more TOML pump specs.", show_default=False)],
    fmt: FormatOpt = Format.table,
) -> None:
    """Dead-centre synthesis: link lengths, dead centres, time ratio, transmission range.

    One row per spec (Table 1 of the pump paper).  Exit 1 if any design is infeasible.

    Example: [bold]pumplink synth configs/prototype.toml configs/*.toml --format json[/]
    """
    from pumplink.analysis import design
    from pumplink.report import render_designs

    designs = [design(s) for s in _load(specs)]
    render_designs(designs, fmt.value)
    raise typer.Exit(0 if all(d.feasible for d in designs) else 1)


@app.command()
def force(
    spec: Annotated[Optional[Path], typer.Argument(help="TOML pump spec; omit for the built-in default design.",
                                                   show_default=False)] = None,
    speed: Annotated[Optional[float], typer.Option(help="Wheel speed \\[deg/s] (default: the spec's operator.speed).",
                                                   min=1e-9, max=7200)] = None,
    samples: Annotated[int, typer.Option(help="Uniform crank samples over one revolution.", min=1, max=1_000_000_000)] = 360,
    at: Annotated[Optional[list[float]], typer.Option("--at", help="Evaluate exactly this crank angle \\[deg] (repeatable).",
                                                      show_default=False)] = None,
    summary: Annotated[bool, typer.Option("--summary", help="Only the checks and verdict (no per-sample rows).")] = False,
    plot: Annotated[Optional[Path], typer.Option(help="Also write the force curve to this .png/.svg/.pdf "
                                                      "(needs the plot extra: pip install 'pumplink\\[plot]').",
                                                 show_default=False)] = None,
    explain: Annotated[bool, typer.Option("--explain", help="Also report which effects the model includes, their "
                                                            "size at this speed, and why the model is enough.")] = False,
    verify: Annotated[bool, typer.Option("--verify", help="Flywheel model: integrate the equation of motion "
                                                          "(scipy solve_ivp) under the reported force profile and "
                                                          "check it is periodic with the mean speed and δ.")] = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Operator force over the crank cycle, the checks and the 100 N verdict.

    Two models decide the verdict.  With the wheel's inertia in the spec
    (wheel.mass or wheel.inertia; the rope and water are added) the
    [bold]flywheel[/] model finds the least peak force that keeps the wheel at
    the mean --speed with a speed fluctuation within
    operator.speed_fluctuation: the speed changes the answer.  Without it the
    force is [bold]quasi-static[/] (Eq. 3 of the pump paper), infinite at the
    two dead centres, so the peak is taken outside ±operator.dead_band of
    them, exactly, whatever --samples. Exit 0 if the design passes, 1 if it
    fails, is infeasible or --verify disagrees.

    Example: [bold]pumplink force pump.toml --speed 360 --at 90 --at 270 --format json[/]

    Example: [bold]pumplink force examples/well-12m-flywheel.toml --speed 540 --explain --verify[/]
    """
    import math

    from pumplink.analysis import force_analysis
    from pumplink.report import render_force
    from pumplink.spec import default_spec, load_spec

    if at and any(not math.isfinite(a) for a in at):
        raise SpecError(f"--at {next(a for a in at if not math.isfinite(a))!r} is not a finite angle; give degrees such as --at 90")
    if not summary and not at and samples > SAMPLE_LIMIT_KEPT:
        raise SpecError(f"--samples {samples} keeps too many rows (at most {SAMPLE_LIMIT_KEPT:,}); add --summary to stream them")
    if plot is not None:
        from pumplink.plots import check_path, pyplot

        check_path(plot)
        pyplot()  # fail early (exit 2) when matplotlib is missing
    from pumplink.report import progress

    s = load_spec(spec) if spec is not None else default_spec()
    if verify and s.inertia is None:
        raise SpecError(f"--verify checks the flywheel model, but {s.name} gives no inertia; add wheel.mass [kg] "
                        "or wheel.inertia [kg m^2] to the spec")
    with progress(1000, "force sweep") as advance:  # drawn on a terminal for sweeps over a second
        done = [0]

        def tick(fraction: float) -> None:
            k = int(fraction * 1000)
            advance(k - done[0])
            done[0] = k

        result = force_analysis(s, speed, samples, at_deg=at or None, keep_samples=not summary, progress=tick)
    extra, agrees = {}, True
    if explain and result.design.feasible:
        from pumplink.analysis import explain as explain_model
        from pumplink.report import explain_rows

        effects, why = explain_model(result)
        extra["explain"] = {"model": result.model, "effects": explain_rows(effects), "why": why}
    scene_ok = result.scene is not None and math.isfinite(result.scene.peak_force)
    if verify and scene_ok:
        from pumplink.flywheel import simulate
        from pumplink.report import verify_row

        extra["verify"] = verify_row(simulate(result.scene), result)
        agrees = extra["verify"]["agrees"]
    elif verify and result.design.feasible:  # an infinite least peak force: no periodic motion exists
        sys.stderr.write(f"verify: nothing to integrate; no finite peak force keeps the wheel turning "
                         f"(energy band J·ω̄²·δ = {result.energy_band:.3g} J)\n")
    render_force(result, fmt.value, summary=summary, extra=extra)
    if fmt.value != "json":  # the reports follow the table; with CSV on stdout they go to stderr
        from pumplink.report import render_explain, render_verify

        side = sys.stdout if fmt.value == "table" else sys.stderr
        if "explain" in extra:
            render_explain(effects, why, out=side)
        if "verify" in extra:
            render_verify(extra["verify"], out=side)
    if plot is not None and result.design.feasible:
        from pumplink.plots import force_curve

        force_curve(result, plot)
        sys.stderr.write(f"wrote {plot}\n")
    raise typer.Exit(0 if result.passed and agrees else 1)


@app.command()
def speed(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec with the wheel's inertia (wheel.mass or wheel.inertia).",
                                         show_default=False)],
    lo: Annotated[float, typer.Option("--from", help="Lowest mean wheel speed \\[deg/s].", min=1e-6, max=7200)] = 120.0,
    hi: Annotated[float, typer.Option("--to", help="Highest mean wheel speed \\[deg/s].", min=1e-6, max=7200)] = 720.0,
    step: Annotated[float, typer.Option(help="Speed step \\[deg/s].", min=1e-3, max=7200)] = 30.0,
    plot: Annotated[Optional[Path], typer.Option(help="Write the chart (peak force against speed) to this "
                                                      ".png/.svg/.pdf (needs pumplink\\[plot]).", show_default=False)] = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Least peak operator force against mean wheel speed, and the slowest speed
    that passes.

    The flywheel model (see [bold]pumplink force --help[/]): a faster wheel
    stores more energy (J·ω̄²·δ) to carry the linkage through the dead
    centres, so the operator's peak force falls toward the mean force, while
    the power Mw·ω̄ rises.  Exit 0 if the spec's own speed passes, 1 if not, 2
    if the spec gives no inertia.

    Example: [bold]pumplink speed examples/well-12m-flywheel.toml --plot speed.png[/]
    """
    import numpy as np

    from pumplink.analysis import speed_sweep
    from pumplink.report import render_speed

    if hi < lo:
        raise SpecError(f"--to {hi:g} is below --from {lo:g}; give --from LOW --to HIGH in deg/s")
    n = int(np.floor((hi - lo) / step + 1e-9)) + 1
    if n > 10_000:
        raise SpecError(f"--from {lo:g} --to {hi:g} --step {step:g} gives {n} speeds; at most 10,000 (raise --step)")
    if plot is not None:
        from pumplink.plots import check_path, pyplot

        check_path(plot)
        pyplot()
    s = _load([spec])[0]
    speeds = [float(f"{v:.12g}") for v in lo + step * np.arange(n)]  # 420, not 420.00000000000006
    sw = speed_sweep(s, speeds)
    render_speed(sw, fmt.value)
    if plot is not None:
        from pumplink.plots import speed_chart

        speed_chart(sw, plot)
        sys.stderr.write(f"wrote {plot}\n")
    # The spec's own speed passes iff it is at least the slowest passing speed (Eq. (2)-(3) of
    # pumplink.flywheel: the least peak force falls as the speed rises) and the mean force passes.
    own = sw.mean_force <= sw.force_limit and np.radians(s.operator.speed) >= sw.min_passing_speed
    raise typer.Exit(0 if own else 1)


@app.command()
def init(
    path: Annotated[Path, typer.Argument(help="Where to write the spec ('-' for stdout).")] = Path("pump.toml"),
    overwrite: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
) -> None:
    """Write the built-in default spec (a realistic prototype) as TOML to edit.

    Example: [bold]pumplink init my-pump.toml[/] then edit it and run [bold]pumplink force my-pump.toml[/]
    """
    import tomli_w

    from pumplink.spec import DEFAULT_SPEC

    text = tomli_w.dumps(DEFAULT_SPEC)
    if str(path) == "-":
        sys.stdout.write(text)
        return
    if path.exists() and not overwrite:
        raise SpecError(f"{path} exists; choose another path or add --force to overwrite it")
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise SpecError(f"{path}: cannot be written ({exc.strerror})") from None
    typer.echo(f"wrote {path}; edit it, then run: pumplink force {path}", err=True)


# ----------------------------------------------------------------------------- methods (issue #3)
def _seconds_per_position(fn, args, n: int, repeats: int, budget: float = 1.0) -> float:
    """Median wall time of ``fn(*args)`` per position [s] over ``repeats`` runs (fewer if slow)."""
    import statistics
    import time

    times = []
    start = time.perf_counter()
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        fn(*args)
        times.append(time.perf_counter() - t0)
        if time.perf_counter() - start > budget and len(times) >= 1:
            break
    return statistics.median(times) / n


@app.command()
def methods(
    spec: Annotated[Optional[Path], typer.Argument(help="TOML pump spec; omit for the built-in default design.",
                                                   show_default=False)] = None,
    samples: Annotated[int, typer.Option(help="Uniform crank samples of the accuracy sweep.", min=4, max=100_000)] = 360,
    method: Annotated[Optional[list[str]], typer.Option("--method", "-m", help="Only this method (repeatable): "
                                                        "vector, paper, numeric, reference.", show_default=False)] = None,
    repeats: Annotated[int, typer.Option(help="Timing repeats per method and sampling (median).", min=1, max=1000)] = 7,
    plot: Annotated[Optional[Path], typer.Option("--plot", help="Write log error vs log time per position "
                                                 "(.png or .svg).", show_default=False)] = None,
    samples_plot: Annotated[Optional[Path], typer.Option("--samples-plot", help="Write sampled vs exact peak and "
                                                         "mean force for N = 12..3600 (.png or .svg).",
                                                         show_default=False)] = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Speed against accuracy of the force methods, where each one fails, and how many samples a sweep needs.

    Every method (vector: production; paper: the seed's instant centre, Eq. 4-6; numeric: scipy
    root finding + finite difference; reference: mpmath, 50 digits) is timed (median of
    --repeats) and compared with the reference on a uniform sweep, next to the dead centres
    (1 to 1e-6 deg) and at the danger points (crank or rocker perpendicular to the frame line,
    crank parallel to the rocker, crank along the frame line).  Exit 0 if no method returns a
    silently wrong value, 1 otherwise.

    Example: [bold]pumplink methods --plot docs/methods.png --samples-plot sampling.svg --format json[/]
    """
    import numpy as np

    from pumplink import accuracy
    from pumplink.analysis import design
    from pumplink.errors import InfeasibleDesign
    from pumplink.methods import METHODS, UNIFORM, NEAR_DEAD_CENTRE
    from pumplink.report_methods import plot_methods, plot_sampling, render_methods
    from pumplink.spec import default_spec, load_spec

    names = method or list(METHODS)
    unknown = [m for m in names if m not in METHODS]
    if unknown:
        raise SpecError(f"--method {unknown[0]!r} is not a method; choose from {', '.join(METHODS)}")
    for path in (plot, samples_plot):
        if path is not None and path.suffix.lower() not in (".png", ".svg"):
            raise SpecError(f"{path}: the chart format comes from the extension, which must be .png or .svg")
    if plot is not None or samples_plot is not None:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise SpecError("writing a chart needs matplotlib; install it with: pip install 'pumplink[plot]'") from None
    try:
        import mpmath  # noqa: F401
    except ImportError:
        raise SpecError("the 50-digit reference needs mpmath; install it with: pip install mpmath") from None

    s = load_spec(spec) if spec is not None else default_spec()
    d = design(s)
    if not d.feasible:
        raise InfeasibleDesign(f"{s.name}: {d.error}")
    syn, mw = d.synthesis, s.wheel_torque
    lk = syn.linkage
    sets = accuracy.sample_sets(lk, syn.dead_centre_extended, syn.dead_centre_folded, samples)
    refs = {k: METHODS["reference"].function(lk, a, mw) for k, a in sets.items()}
    rows = []
    for name in names:
        m = METHODS[name]
        per_set = {}
        for kind, angles in sets.items():
            tol = m.tolerance.get(kind, max(m.tolerance[k] for k in m.tolerance))
            stats = accuracy.error_stats(m.function(lk, angles, mw), refs[kind], tol)
            stats["seconds_per_position"] = _seconds_per_position(m.function, (lk, angles, mw), angles.size,
                                                                  repeats)
            per_set[kind] = stats
        rows.append({"name": name, "summary": m.summary, "cannot_handle": m.cannot,
                     "seconds_per_position": per_set[UNIFORM]["seconds_per_position"],
                     "max_rel_error_uniform": per_set[UNIFORM]["max_rel_error"],
                     "max_rel_error_near_dead_centre": per_set[NEAR_DEAD_CENTRE]["max_rel_error"],
                     "failures": accuracy.failures(per_set), "samplings": per_set})
    study = accuracy.sampling_study(lk, syn.dead_centre_extended, syn.dead_centre_folded,
                                    float(np.radians(s.operator.dead_band)), mw, syn.swing)
    render_methods(s.name, rows, study, fmt.value, dead_band_deg=s.operator.dead_band)
    if plot is not None:
        plot_methods(rows, plot, title=s.name)
        typer.echo(f"wrote {plot}", err=True)
    if samples_plot is not None:
        plot_sampling(study, samples_plot, title=s.name, dead_band_deg=s.operator.dead_band)
        typer.echo(f"wrote {samples_plot}", err=True)
    silent = any(st["wrong"] or st["missed_singular"] for r in rows for st in r["samplings"].values())
    raise typer.Exit(1 if silent else 0)


# ----------------------------------------------------------------------------- design search (issue #5)
class Objective(str, Enum):
    peak = "peak"
    mean = "mean"


@app.command()
def transmission(
    time_ratio: Annotated[float, typer.Option("--time-ratio", "-k", help="Time ratio K > 1 (slow/fast stroke).")] = 1.1818,
    swing: Annotated[float, typer.Option(help="Rocker swing φ \\[deg].")] = 40.0,
    rocker: Annotated[float, typer.Option(help="Rocker length (any unit; the other lengths come out in it).")] = 50.0,
    compare_seed: Annotated[bool, typer.Option("--compare-seed/--no-compare-seed",
                                               help="Compare with seed 001's published designs (its example only).")] = True,
    chart: Annotated[Optional[Path], typer.Option(help="Write seed 001's design diagram (contours over θ and φ) "
                                                       "to this image file instead (needs pumplink\\[plot]).",
                                                  show_default=False)] = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank-rocker with the best minimum transmission angle for K and φ (seed 001, exact).

    Solves seed 001's problem to solver tolerance on the one-branch arc of the design circle and
    verifies the result by simulating the linkage (the swing and K it really produces).  With the
    defaults it is the seed's worked example (K = 1.1818, φ = 40°, rocker 50 mm) compared with the
    seed's published designs.

    Example: [bold]pumplink transmission --time-ratio 1.25 --swing 50 --rocker 0.3[/]
    """
    import math

    if chart is not None:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise SpecError("--chart needs matplotlib; install it with: pip install 'pumplink[plot]'") from None
        import numpy as np

        from pumplink.report_design import transmission_chart
        from pumplink.transmission import optimal_crank_rocker, time_ratio_from_angle

        th = np.linspace(1.0, 40.0, 40)  # 1 deg steps of theta
        ph = np.linspace(10.0, 120.0, 56)  # 2 deg steps of phi
        opt = optimal_crank_rocker(time_ratio_from_angle(np.radians(th))[:, None], np.radians(ph)[None, :])
        try:
            transmission_chart(chart, th, ph, opt)
        except (OSError, ValueError) as exc:
            raise SpecError(f"{chart}: cannot write the chart ({exc})") from None
        typer.echo(f"wrote {chart}", err=True)
        return

    from pumplink.report_design import SEED_001_DESIGNS, SEED_001_EXAMPLE, render_transmission, transmission_rows
    from pumplink.synthesis import Linkage
    from pumplink.transmission import optimal_crank_rocker, optimum_linkage, simulate

    for name, v in (("--time-ratio", time_ratio), ("--swing", swing), ("--rocker", rocker)):
        if not math.isfinite(v):
            raise SpecError(f"{name} {v!r} is not a finite number")
    opt = optimal_crank_rocker(time_ratio, math.radians(swing), rocker)
    sim = simulate(optimum_linkage(opt))
    comps = []
    ex = SEED_001_EXAMPLE
    if compare_seed and (time_ratio, swing, rocker) == (ex["time_ratio"], ex["swing_deg"], ex["rocker"]):
        for label, (c, k, r, f) in SEED_001_DESIGNS.items():
            # Place the seed's design with the crank pivot at the origin and the frame along +x.
            comps.append((label, (c, k, r, f), simulate(Linkage(f, 0.0, c, k, r, r, 1.0))))
    render_transmission(transmission_rows(opt, sim, comps), fmt.value)


@app.command()
def optimize(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec: fixed values and the starting design.", show_default=False)],
    vary: Annotated[Optional[list[str]], typer.Option("--vary", help="KEY=LO:HI in spec units (repeatable); keys: L1, D1, "
                                                      "b, rocker, handle \\[m], swing \\[deg]. Default: rocker=0.1:0.4 "
                                                      "L1=0:1 D1=-0.3:1.2 swing=30:100.", show_default=False)] = None,
    objective: Annotated[Objective, typer.Option(help="Minimise the peak force of the verdict (the flywheel's "
                                                     "least peak force when the spec gives inertia, else the exact "
                                                     "peak outside the dead bands) or the mean force.")] = Objective.peak,
    seed: Annotated[int, typer.Option(help="Random seed of the differential evolution (same seed, same answer).")] = 0,
    axle_height: Annotated[Optional[float], typer.Option(help="Wheel-axle height \\[m] (default: the spec's "
                                                         "wheel.axle_height, else 0.55).", show_default=False)] = None,
    grip_height: Annotated[str, typer.Option(help="Allowed grip height above ground over the swing, LO:HI \\[m].")] = "0.5:0.9",
    stroke: Annotated[str, typer.Option(help="Allowed horizontal grip stroke, LO:HI \\[m].")] = "0:1.0",
    write: Annotated[Optional[Path], typer.Option(help="Write the optimum as a new spec (TOML).", show_default=False)] = None,
    overwrite: Annotated[bool, typer.Option("--force", help="Overwrite the --write file if it exists.")] = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Search frame placement, rocker and swing for the least operator force.

    Differential evolution over the vectorised force kernel, then a local polish, subject to: a
    crank-rocker exists, transmission angle >= 45°, grip height and stroke in the ergonomic
    ranges.  The verdict is that of pumplink force (the model key says which model decided).
    Exit 0 if the optimum passes the force limit, 1 if it fails or nothing is feasible.

    Example: [bold]pumplink optimize configs/prototype.toml --vary D1=0:0.8 --vary swing=40:90 --write best.toml[/]
    """
    from pumplink.optimize import GRIP_HEIGHT_M, STROKE_M, make_problem, optimize as run, parse_bounds, parse_range
    from pumplink.report_design import optimize_row, render_optimize

    bounds = parse_bounds(vary)
    gh = parse_range("grip-height", grip_height, GRIP_HEIGHT_M)
    st = parse_range("stroke", stroke, STROKE_M)
    if write is not None and write.exists() and not overwrite:
        raise SpecError(f"{write} exists; choose another path or add --force to overwrite it")
    problem = make_problem(_load([spec])[0], bounds, objective.value, axle_height, gh, st)
    result = run(problem, seed=seed)
    row = optimize_row(result)
    render_optimize(row, fmt.value)
    if write is not None:
        import tomli_w

        from pumplink.optimize import best_spec_dict

        try:
            write.write_text(tomli_w.dumps(best_spec_dict(result)), encoding="utf-8")
        except OSError as exc:
            raise SpecError(f"{write}: cannot be written ({exc.strerror})") from None
        typer.echo(f"wrote {write}; check it with: pumplink force {write}", err=True)
    raise typer.Exit(0 if row["optimum"]["passes_force_limit"] else 1)


@app.command()
def batch(
    inputs: Annotated[list[Path], typer.Argument(help="Batch files, spec files or folders of them (*.toml).",
                                                 show_default=False)],
    samples: Annotated[int, typer.Option(help="Uniform crank samples per variant for the sampled-peak column "
                                              "(0: skip it); peak_force_N is exact whatever this is.",
                                         min=0, max=1_000_000)] = 360,
    fmt: Annotated[Format, typer.Option("--format", "-f", help="Rows as csv or json; table: the summary "
                                                               "(and the rows, or the failures of a large run).")] = Format.table,
    out: Annotated[Optional[Path], typer.Option("--out", "-o", help="Write the rows to this file (atomically) "
                                                                    "instead of stdout.", show_default=False)] = None,
    junit: Annotated[Optional[Path], typer.Option("--junit", help="Also write JUnit XML, one testcase per variant "
                                                                  "(atomically).", show_default=False)] = None,
    workers: Annotated[int, typer.Option(help="Worker processes (0: one per CPU).", min=0, max=256)] = 1,
    fail_on: Annotated[str, typer.Option("--fail-on", help="Checks that make the run fail (exit 1): any of "
                                                           "mean,peak,infeasible; or all, or none. peak is the "
                                                           "verdict's peak: the least peak force with the flywheel "
                                                           "where the variant gives inertia (wheel.mass, "
                                                           "wheel.inertia or load.moving_mass), else the peak "
                                                           "outside the dead bands.")] = "mean,peak,infeasible",
    chunk: Annotated[Optional[str], typer.Option("--chunk", help="Evaluate only slice K of N (1-based) of all "
                                                                 "variants, e.g. 3/8; names stay those of the full run.",
                                                 show_default=False)] = None,
) -> None:
    """Evaluate many variants at once: a base spec plus axes to vary (Cartesian product).

    A batch file is TOML: base = "pump.toml" (or the spec inline as \\[base]) and a \\[vary] table of
    "section.key" = \\[values] or { start, stop, num }.  Plain spec files count as one variant;
    a folder means its *.toml files (not sub-folders).

    One row per variant (lengths, feasibility, forces, verdict) and a summary (counts, lowest
    peak force).  The verdict is that of pumplink force: the flywheel model where the variant
    gives inertia, else quasi-static with the dead band (the model column says which).  Exit 0 if
    no variant fails a --fail-on check, 1 if one does, 2 for bad input.

    Example: [bold]pumplink batch configs/ --junit report.xml[/]
    """
    import functools
    import os
    import signal
    import time
    from concurrent.futures.process import BrokenProcessPool

    from pumplink import batch as _batch
    from pumplink import report_batch as rb
    from pumplink.report import progress

    t0 = time.perf_counter()
    sel = _batch.parse_fail_on(fail_on)
    k_n = _batch.parse_chunk(chunk)
    if fmt.value == "table" and out is not None:
        raise SpecError("--out writes rows: give --format csv or --format json with it")
    for opt, path in (("--out", out), ("--junit", junit)):  # before any work: fail fast, exit 2
        if path is not None and (path.is_dir() or not path.parent.is_dir()):
            raise SpecError(f"{opt} {path}: " + ("is a folder; give a file name" if path.is_dir() else
                                                 f"folder {path.parent} does not exist"))
    batches = _batch.load_inputs(inputs)
    tasks = _batch.plan(batches, k_n)
    total = sum(e - s for _, s, e in tasks)
    n_workers = workers or os.cpu_count() or 1

    def _terminate(signum, frame):  # SIGTERM: unwind like Ctrl-C so no temp file is left behind
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        with progress(total, "batch") as advance:
            post = functools.partial(rb.render_chunk, fmt=fmt.value, vkeys=rb.varied_keys(batches), fail_on=sel,
                                     junit=junit is not None)  # runs in the workers
            results = _batch.run(batches, samples, k_n, n_workers, post=post)
            summary, rows = rb.write_stream(batches, results, total, fmt.value, out, junit, sel, samples, k_n, advance)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted; no output file written\n")
        raise typer.Exit(130) from None
    except BrokenProcessPool:  # a worker was killed (SIGKILL, out of memory)
        sys.stderr.write("interrupted: a worker process was killed (out of memory?); no output file written\n")
        raise typer.Exit(130) from None
    finally:
        signal.signal(signal.SIGTERM, previous)
    if fmt.value == "table":
        rb.render_table(summary, rows)
    else:
        wrote = [p for p in (out, junit) if p is not None]
        sys.stderr.write(rb.summary_line(summary, time.perf_counter() - t0, wrote) + "\n")
    raise typer.Exit(1 if summary["failed_selected"] else 0)


def main() -> None:
    """Console-script entry point: PumplinkError -> one line on stderr and its exit code."""
    if hasattr(signal, "SIGPIPE"):  # `pumplink ... | head` ends quietly, like any Unix filter (not exit 1)
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    for stream in (sys.stdout, sys.stderr):  # a non-UTF-8 terminal or pipe gets '?' for θ, ±, ∞, not a crash
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="replace")
    try:
        app()
    except PumplinkError as exc:
        if _state["debug"]:
            raise
        sys.stderr.write(f"error: {exc}\n")
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)
    except BrokenPipeError:
        sys.exit(0)
