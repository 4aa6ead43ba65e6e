"""Batch runs: a base spec plus axes to vary, evaluated as one vectorised Cartesian product.

A batch file (TOML) names a base spec and the spec keys to vary (issue #4)::

    name = "rocker-study"           # optional; default: the file stem (prefix of variant names)
    base = "prototype.toml"         # a spec file (relative to this file), or the spec inline as [base]
    [vary]
    "linkage.rocker" = [0.20, 0.25, 0.30]                 # a list of numbers
    "linkage.swing" = { start = 40, stop = 70, num = 7 }  # or a linspace (ends included)

Variant ``i`` of a batch is entry ``i`` of ``itertools.product`` over the axes in file order (the
last axis varies fastest); its name is ``<label>#<i>[<key>=<value> ...]`` with ``i`` zero-padded
and the short key (the part after the last dot, the full key where that is ambiguous), for
example ``rocker-study#07[rocker=0.25 swing=45]``.  Names depend only on the batch file, so a
``--chunk K/N`` slice names its variants as the full run does.

The verdict is that of ``pumplink force`` (issue #6).  A variant whose spec gives inertia
(``wheel.inertia``, ``wheel.mass`` or ``load.moving_mass``, in the base or on an axis) is decided by
the flywheel model: it passes iff it is feasible, the mean force is within the limit and the least
peak force with the flywheel (:func:`pumplink.flywheel.required_peak_force` at the variant's speed and
speed fluctuation) is within the limit; the windowed peak outside the dead bands (``peak_force_N``) is
then reported for information only.  Any other variant is decided by the quasi-static model with the
dead band, as before.  The ``peak`` check of ``--fail-on`` is the verdict's peak: the flywheel one
where the variant gives inertia.  Every variant of one batch file has the same spec keys, so one
model decides a whole batch file; a run over several files can mix the models.

Everything here is a pure function of the parsed files except :func:`load_batch` /
:func:`load_inputs` (read files) and :func:`run` (schedules chunks on worker processes).  The
numbers per variant are bit-for-bit those of :func:`pumplink.analysis.force_analysis` (``pumplink
force --summary``) on the same variant: the same kernels, vectorised over designs.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

import numpy as np

from pumplink import flywheel as _fw
from pumplink import force as _force
from pumplink.errors import SpecError
from pumplink.spec import (GRAVITY, WATER_DENSITY, PumpSpec, load_spec, parse_spec, read_toml,
                           spec_from_file_data, spec_to_dict)
from pumplink.synthesis import Linkage, infeasibility_reason, synthesize

#: Checks ``--fail-on`` can select (the default selects all three, as ``pumplink force`` does).
#: ``peak`` is the verdict's peak: the flywheel's least peak force where the variant gives
#: inertia, else the windowed peak outside the dead bands.
FAIL_CHECKS = ("mean", "peak", "infeasible")
#: Spec keys that give the inertia and so turn on the flywheel model (``PumpSpec.inertia``).
INERTIA_KEYS = ("wheel.inertia", "wheel.mass", "load.moving_mass")
#: Largest number of values on one axis (each axis is held in memory and sent to every worker).
MAX_AXIS_VALUES = 1_000_000
#: Largest number of variants in one run (indices stay exact in float64 and int64).
MAX_VARIANTS = 10**15
#: Most designs per chunk (rows handed to the writer at once, one task for a worker process).
CHUNK_DESIGNS = 8192
#: Crank samples per chunk: fewer designs per chunk at large --samples, so a task stays short
#: (an interrupted run waits for the running tasks) and its rows arrive steadily.
TASK_SAMPLES = 3_000_000
#: Designs swept together inside a chunk for the sampled peak: small enough that the kernel's
#: temporaries (designs x 360 samples) stay in the CPU cache.
SUB_DESIGNS = 128
#: Most designs per chunk, and per call of the flywheel kernel, for variants that give inertia:
#: the least peak force costs ~0.5 ms per design (a chunk ~0.5 s) and its temporaries are
#: (designs x ~430 nodes) arrays.
FLYWHEEL_DESIGNS = 1024
#: Significant digits kept for linspace values, so {start=0.2, stop=0.3, num=3} gives 0.25
#: exactly (what a user would type), not 0.25000000000000006.
LINSPACE_DIGITS = 12

_TOP_KEYS = ("name", "base", "vary")


def _leaf_keys() -> tuple[str, ...]:
    keys = []
    for section, field in PumpSpec.model_fields.items():
        sub = getattr(field.annotation, "model_fields", None)
        if sub:
            keys.extend(f"{section}.{k}" for k in sub)
    return tuple(keys)


#: Dotted spec paths that an axis may vary (every numeric key of the spec).
VARIABLE_KEYS = _leaf_keys()


@dataclass(frozen=True)
class Axis:
    """One varied spec key and its values (floats, in file order)."""

    key: str
    values: np.ndarray
    labels: tuple[str, ...]  # value as printed in variant names
    short: str  # key as printed in variant names


@dataclass(frozen=True)
class Batch:
    """A validated batch: base spec mapping plus axes; a plain spec file is a batch of one.

    Attributes
    ----------
    source : the file it came from.
    label : prefix of variant names (batch ``name`` or file stem); for a plain spec, its name.
    base : the base spec as a validated mapping (``spec_to_dict``).
    spec : the validated base spec.
    axes : the varied keys, in file order (empty for a plain spec).
    """

    source: str
    label: str
    base: dict[str, Any]
    spec: PumpSpec
    axes: tuple[Axis, ...]

    @property
    def size(self) -> int:
        return math.prod(len(a.values) for a in self.axes)

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(a.key for a in self.axes)

    def given(self, key: str) -> bool:
        """True when the variants set the spec key ``section.name`` (in the base or on an axis)."""
        section, name = key.split(".")
        return key in self.keys or getattr(getattr(self.spec, section), name) is not None

    @property
    def flywheel(self) -> bool:
        """True when the variants give inertia (:data:`INERTIA_KEYS`): the flywheel model decides.

        Every variant of a batch sets the same keys, so this holds for all of them or none.
        """
        return any(self.given(k) for k in INERTIA_KEYS)


@dataclass(frozen=True)
class Chunk:
    """Results for variants ``start..stop-1`` of one batch (arrays over those variants, SI units).

    ``reason`` holds the infeasibility sentence (None when feasible); the checks follow
    :func:`pumplink.analysis.force_analysis`: ``mean_ok`` = mean <= limit, ``peak_ok`` =
    verdict peak <= limit (False when it is NaN), ``passed`` = feasible and both.  The verdict
    peak (:attr:`verdict_peak`) is ``required_peak_force`` where ``flywheel`` (the variant gives
    inertia), else ``peak_force``.  The flywheel columns are NaN for quasi-static variants, and
    ``required_peak_force`` / ``min_passing_speed`` also for infeasible ones.
    """

    batch: int  # index of the batch in the run
    start: int
    stop: int
    values: np.ndarray  # (n, axes) varied values
    frame_length: np.ndarray
    crank_length: np.ndarray
    coupler_length: np.ndarray
    feasible: np.ndarray
    reason: list
    time_ratio: np.ndarray
    transmission_min: np.ndarray  # [rad]
    transmission_max: np.ndarray  # [rad]
    mean_force: np.ndarray  # [N]
    peak_force: np.ndarray  # exact windowed peak [N]
    sampled_peak: np.ndarray  # peak over the uniform --samples sweep outside the dead bands [N]
    power: np.ndarray  # [W]
    force_limit: np.ndarray  # [N]
    mean_ok: np.ndarray
    peak_ok: np.ndarray
    passed: np.ndarray
    flywheel: np.ndarray  # True: the variant gives inertia, the flywheel model decides
    inertia: np.ndarray  # J [kg m^2]
    speed_fluctuation: np.ndarray  # delta_allow [-]
    required_peak_force: np.ndarray  # least peak force with the flywheel [N] (inf: no energy band)
    min_passing_speed: np.ndarray  # [rad/s] (inf: no speed passes)

    @property
    def verdict_peak(self) -> np.ndarray:
        """The peak force that decides the verdict [N]: flywheel or windowed dead-band peak."""
        return np.where(self.flywheel, self.required_peak_force, self.peak_force)

    def __len__(self) -> int:
        return self.stop - self.start

    def failed(self, fail_on: Sequence[str]) -> np.ndarray:
        """True where a variant fails one of the checks selected by ``--fail-on``."""
        out = np.zeros(len(self), bool)
        if "infeasible" in fail_on:
            out |= ~self.feasible
        if "mean" in fail_on:
            out |= self.feasible & ~self.mean_ok
        if "peak" in fail_on:
            out |= self.feasible & ~self.peak_ok
        return out


# ----------------------------------------------------------------------------- parsing
def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _value_label(v: float) -> str:
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def _axis_values(key: str, raw: Any, where: str) -> np.ndarray:
    """Numbers of one [vary] entry: a list, or a {start, stop, num} linspace table."""
    if isinstance(raw, list):
        if not raw:
            raise SpecError(f"{where}: [vary] '{key}' is an empty list; give at least one value")
        for v in raw:
            if not _is_number(v):
                raise SpecError(f"{where}: [vary] '{key}' has {v!r} ({type(v).__name__}), not a number; "
                                f"give a list of numbers such as [0.2, 0.25]")
            if not math.isfinite(v):
                raise SpecError(f"{where}: [vary] '{key}' has {v!r}, not a finite number")
        if len(raw) > MAX_AXIS_VALUES:
            raise SpecError(f"{where}: [vary] '{key}' has {len(raw)} values, more than {MAX_AXIS_VALUES:,}; "
                            f"split the batch")
        return np.array(raw, dtype=float)
    if isinstance(raw, dict):
        unknown = sorted(set(raw) - {"start", "stop", "num"})
        if unknown:
            raise SpecError(f"{where}: [vary] '{key}' has unknown key '{unknown[0]}'; a range is "
                            f"{{ start = ..., stop = ..., num = ... }} (ends included)")
        for part in ("start", "stop", "num"):
            if part not in raw:
                raise SpecError(f"{where}: [vary] '{key}' range is missing '{part}'; a range is "
                                f"{{ start = ..., stop = ..., num = ... }} (ends included)")
        start, stop, num = raw["start"], raw["stop"], raw["num"]
        for part, v in (("start", start), ("stop", stop)):
            if not _is_number(v) or not math.isfinite(v):
                raise SpecError(f"{where}: [vary] '{key}' range {part} = {v!r} is not a finite number")
        if not isinstance(num, int) or isinstance(num, bool):
            raise SpecError(f"{where}: [vary] '{key}' range num = {num!r} is not an integer; give the "
                            f"number of values, ends included (e.g. num = 7)")
        if not 1 <= num <= MAX_AXIS_VALUES:
            raise SpecError(f"{where}: [vary] '{key}' range num = {num} is out of range; allowed: "
                            f"1 <= num <= {MAX_AXIS_VALUES:,}")
        if num > 1 and start == stop:
            raise SpecError(f"{where}: [vary] '{key}' range has start = stop = {start!r} with num = {num}; "
                            f"give num = 1 or different ends")
        vals = np.linspace(float(start), float(stop), num)
        return np.array([float(f"{v:.{LINSPACE_DIGITS}g}") for v in vals.tolist()])
    raise SpecError(f"{where}: [vary] '{key}' = {raw!r} must be a list of numbers or a range "
                    f"{{ start = ..., stop = ..., num = ... }}")


def _set(data: dict, key: str, value: float) -> dict:
    section, field = key.split(".")
    out = dict(data)
    out[section] = {**out.get(section, {}), field: value}
    return out


def _short_keys(keys: Sequence[str]) -> list[str]:
    tails = [k.rsplit(".", 1)[1] for k in keys]
    return [t if tails.count(t) == 1 else k for k, t in zip(keys, tails)]


def parse_batch(data: Any, source: str, folder: Path | None = None, stem: str | None = None) -> Batch:
    """Validate a batch mapping (as read from TOML) into a :class:`Batch`.

    Every value of every axis is checked against the spec's ranges up front (the spec's limits
    are intervals, so the smallest and largest value of each axis decide), and one combination
    checks the keys that go together (e.g. ``load.rope_force`` against ``load.head``); so every
    variant of the product is a valid spec.

    Raises
    ------
    SpecError
        One sentence naming the offending key (exit 2).
    """
    if not isinstance(data, dict) or not data:
        raise SpecError(f"{source}: empty batch file; expected base = \"spec.toml\" (or [base]) and [vary]")
    for k in data:
        if k not in _TOP_KEYS:
            close = difflib.get_close_matches(k, _TOP_KEYS, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise SpecError(f"{source}: unknown key '{k}' in a batch file{hint}; allowed: name, base, [vary]")
    label = data.get("name", stem or Path(source).stem)
    if not isinstance(label, str) or not label.strip():
        raise SpecError(f"{source}: 'name' = {label!r} must be non-empty text (the prefix of variant names)")
    if "base" not in data:
        raise SpecError(f"{source}: missing key 'base'; give base = \"spec.toml\" or the spec inline as [base]")
    raw_base = data["base"]
    if isinstance(raw_base, str):
        path = Path(raw_base)
        if not path.is_absolute():
            path = (folder or Path(".")) / path
        try:
            spec = load_spec(path)
        except SpecError as exc:
            raise SpecError(f"{source}: base = {raw_base!r}: {exc}") from None
    elif isinstance(raw_base, dict):
        base = dict(raw_base)
        base.setdefault("name", label)
        spec = parse_spec(base, source=f"{source} [base]")
    else:
        raise SpecError(f"{source}: 'base' = {raw_base!r} must be a spec file name (text) or a [base] table")
    base = spec_to_dict(spec)

    vary = data.get("vary")
    if vary is None:
        raise SpecError(f"{source}: missing [vary] table; add e.g. [vary] \"linkage.rocker\" = [0.2, 0.25]")
    if not isinstance(vary, dict):
        raise SpecError(f"{source}: 'vary' = {vary!r} must be a table ([vary]) of \"section.key\" = values")
    if not vary:
        raise SpecError(f"{source}: [vary] is empty; add an axis such as \"linkage.rocker\" = [0.2, 0.25]")
    for key in vary:
        if key not in VARIABLE_KEYS:
            close = difflib.get_close_matches(key, VARIABLE_KEYS, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise SpecError(f"{source}: [vary] '{key}' is not a numeric spec key{hint}; allowed: "
                            f"{', '.join(VARIABLE_KEYS)}")
    axes = []
    for (key, raw), short in zip(vary.items(), _short_keys(list(vary))):
        values = _axis_values(key, raw, source)
        for v in sorted({float(values.min()), float(values.max())}):
            # the spec's limits are intervals: the extremes decide for every value on the axis
            parse_spec(_set(base, key, v), source=f"{source}: [vary] '{key}' value {_value_label(v)}")
        labels = tuple(_value_label(v) for v in values.tolist())
        axes.append(Axis(key, values, labels, short))
    first = base
    for a in axes:
        first = _set(first, a.key, float(a.values[0]))
    try:
        parse_spec(first, source=f"{source}: [vary] {', '.join(vary)}")
    except SpecError as exc:
        raise SpecError(f"{exc}".rstrip(".") + " (check the varied keys against the base spec).") from None
    b = Batch(source, label, base, spec, tuple(axes))
    if b.size > MAX_VARIANTS:
        raise SpecError(f"{source}: [vary] makes {b.size:.3g} variants, more than {MAX_VARIANTS:.0e}; "
                        f"use fewer values per axis")
    return b


def spec_batch(spec: PumpSpec, source: str) -> Batch:
    """A plain spec as a batch of one variant (named as the spec)."""
    return Batch(source, spec.name, spec_to_dict(spec), spec, ())


def is_batch_mapping(data: Any) -> bool:
    """A TOML mapping is a batch file if it has a top-level ``base`` or ``vary`` key."""
    return isinstance(data, dict) and ("base" in data or "vary" in data)


def load_batch(path: str | Path) -> Batch:
    """Read a spec file or a batch file (decided by a top-level ``base``/``vary`` key).

    Raises
    ------
    SpecError
        Unreadable file, invalid TOML, an invalid batch or spec (exit 2).
    """
    path = Path(path)
    data = read_toml(path, "a TOML spec or batch")
    if is_batch_mapping(data):
        return parse_batch(data, str(path), path.parent, path.stem)
    return spec_batch(spec_from_file_data(data, path), str(path))


def load_inputs(paths: Sequence[str | Path]) -> list[Batch]:
    """Batches from files and folders (a folder: its ``*.toml`` files, sorted, not recursive)."""
    out = []
    for p in paths:
        p = Path(p)
        if p.is_dir():
            files = sorted(f for f in p.glob("*.toml") if f.is_file())
            if not files:
                raise SpecError(f"{p}: folder has no .toml spec or batch files")
            out.extend(load_batch(f) for f in files)
        else:
            out.append(load_batch(p))
    return out


def parse_fail_on(text: str) -> tuple[str, ...]:
    """``--fail-on``: comma-separated subset of mean, peak, infeasible; ``all`` or ``none``."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if parts == ["none"]:
        return ()
    if parts == ["all"]:
        return FAIL_CHECKS
    bad = [p for p in parts if p not in FAIL_CHECKS]
    if bad or not parts:
        raise SpecError(f"--fail-on {text!r}: unknown check {bad[0] if bad else '(empty)'!r}; give a comma-separated "
                        f"list of {', '.join(FAIL_CHECKS)}, or all, or none")
    return tuple(c for c in FAIL_CHECKS if c in parts)


def parse_chunk(text: str | None) -> tuple[int, int]:
    """``--chunk K/N`` -> (K, N), 1 <= K <= N; None -> (1, 1)."""
    if text is None:
        return 1, 1
    try:
        k, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise SpecError(f"--chunk {text!r} is not K/N; give e.g. --chunk 2/8 (the 2nd of 8 slices)") from None
    if not (n >= 1 and 1 <= k <= n):
        raise SpecError(f"--chunk {text!r} is out of range; allowed: 1 <= K <= N")
    return k, n


# ----------------------------------------------------------------------------- variants
def axis_indices(batch: Batch, start: int, stop: int) -> np.ndarray:
    """Per-axis value indices of variants start..stop-1, shape (n, axes); last axis fastest."""
    idx = np.arange(start, stop, dtype=np.int64)
    out = np.empty((idx.size, len(batch.axes)), dtype=np.int64)
    for j in range(len(batch.axes) - 1, -1, -1):
        n = len(batch.axes[j].values)
        out[:, j] = idx % n
        idx //= n
    return out


def variant_name(batch: Batch, index: int) -> str:
    """Stable name of variant ``index``: ``<label>#<index>[<key>=<value> ...]``."""
    if not batch.axes:
        return batch.label
    width = len(str(batch.size - 1))
    ij = axis_indices(batch, index, index + 1)[0]
    return _name(batch, index, width, ij)


def _name(batch: Batch, index: int, width: int, ij) -> str:
    parts = " ".join(f"{a.short}={a.labels[j]}" for a, j in zip(batch.axes, ij))
    return f"{batch.label}#{index:0{width}d}[{parts}]"


def variant_names(batch: Batch, start: int, stop: int) -> list[str]:
    """Names of variants start..stop-1 (see :func:`variant_name`)."""
    if not batch.axes:
        return [batch.label] * (stop - start)
    width = len(str(batch.size - 1))
    ij = axis_indices(batch, start, stop)
    parts = [np.array([f"{a.short}={lab}" for lab in a.labels], dtype=object)[ij[:, j]].tolist()
             for j, a in enumerate(batch.axes)]
    label = batch.label
    return [f"{label}#{i:0{width}d}[{p}]" for i, p in zip(range(start, stop), map(" ".join, zip(*parts)))]


def variant_spec(batch: Batch, index: int) -> dict[str, Any]:
    """The spec mapping of variant ``index`` (named as the variant), e.g. to write with tomli-w
    and check with ``pumplink force``."""
    data = dict(batch.base)
    ij = axis_indices(batch, index, index + 1)[0] if batch.axes else ()
    for a, j in zip(batch.axes, ij):
        data = _set(data, a.key, float(a.values[j]))
    data["name"] = variant_name(batch, index)
    return data


def _field(batch: Batch, cols: dict[str, np.ndarray], key: str, n: int):
    if key in cols:
        return cols[key]
    section, name = key.split(".")
    return np.full(n, getattr(getattr(batch.spec, section), name), dtype=float)


def rope_force(batch: Batch, cols: dict[str, np.ndarray], n: int) -> np.ndarray:
    """Rope force at the rim per variant [N]: as ``Load.rope_force_N`` (NOTES.md §4), same
    operation order so the numbers are identical."""
    load = batch.spec.load
    if load.rope_force is not None or "load.rope_force" in cols:
        return _field(batch, cols, "load.rope_force", n)
    head = _field(batch, cols, "load.head", n)
    d = _field(batch, cols, "load.pipe_diameter", n)
    if load.efficiency is None and "load.efficiency" not in cols:
        eff = np.full(n, 0.75)
    else:
        eff = _field(batch, cols, "load.efficiency", n)
    return WATER_DENSITY * GRAVITY * head * np.pi * (d * d) / 4.0 / eff  # NOTES.md §4


def moving_mass(batch: Batch, cols: dict[str, np.ndarray], n: int) -> np.ndarray:
    """Mass moving at rim speed per variant [kg]: as ``Load.moving_mass_kg`` (the water column
    rho * head * pi d^2 / 4 by default with head and pipe_diameter, NOTES.md §4), same operation
    order so the numbers are identical."""
    if batch.given("load.moving_mass"):
        return _field(batch, cols, "load.moving_mass", n)
    if batch.given("load.head"):
        head = _field(batch, cols, "load.head", n)
        d = _field(batch, cols, "load.pipe_diameter", n)
        return WATER_DENSITY * head * np.pi * (d * d) / 4.0  # NOTES.md §4
    return np.zeros(n)


def inertia(batch: Batch, cols: dict[str, np.ndarray], n: int) -> np.ndarray:
    """Moment of inertia about the axle per variant [kg m^2], NaN where the variant gives none.

    As ``PumpSpec.inertia`` (issue #6): wheel.inertia, or wheel.mass * radius^2 (a rim), plus
    the moving mass * radius^2; same operation order so the numbers are identical.
    """
    if not batch.flywheel:
        return np.full(n, np.nan)
    r = _field(batch, cols, "wheel.radius", n)
    if batch.given("wheel.inertia"):
        wheel = _field(batch, cols, "wheel.inertia", n)
    elif batch.given("wheel.mass"):
        wheel = _field(batch, cols, "wheel.mass", n) * r * r
    else:
        wheel = 0.0 * r * r
    return wheel + moving_mass(batch, cols, n) * r * r


def _take(lk: Linkage, idx) -> Linkage:
    return Linkage(*(np.asarray(getattr(lk, f))[idx] for f in
                     ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "branch")))


def evaluate(batch: Batch, start: int, stop: int, samples: int = 360, batch_index: int = 0) -> Chunk:
    """Synthesis, force checks and verdict for variants ``start..stop-1`` of a batch.

    Vectorised over the variants; the numbers equal :func:`pumplink.analysis.force_analysis`
    (``keep_samples=False``) on each variant's spec exactly, the flywheel scene included where
    the variant gives inertia (the verdict then uses its least peak force).

    Parameters
    ----------
    samples : uniform crank samples per revolution for the sampled-peak column (0: skip it).
        The peak force itself is exact whatever the sampling (:func:`pumplink.force.peak_force`).
    """
    n = stop - start
    if batch.axes:
        ij = axis_indices(batch, start, stop)
        values = np.stack([a.values[ij[:, j]] for j, a in enumerate(batch.axes)], axis=1)
    else:
        values = np.empty((n, 0))
    cols = {a.key: values[:, j] for j, a in enumerate(batch.axes)}

    def get(key):
        return _field(batch, cols, key, n)

    swing = np.radians(get("linkage.swing"))
    L1, D1, b = get("linkage.L1"), get("linkage.D1"), get("linkage.b")
    handle = get("linkage.handle")
    syn = synthesize(L1, D1, b, get("linkage.rocker"), swing, handle)
    feasible = np.asarray(syn.feasible, bool)
    mw = rope_force(batch, cols, n) * get("wheel.radius")  # Mw = Fw rw, Eq. (3)
    speed = np.radians(get("operator.speed"))
    band = np.radians(get("operator.dead_band"))
    limit = get("operator.force_limit")
    power = mw * speed

    mean = np.full(n, np.nan)
    peak = np.full(n, np.nan)
    sampled = np.full(n, np.nan)
    lk = syn.linkage
    ok = np.nonzero(feasible)[0]
    if ok.size:
        sub = Linkage(*(np.asarray(getattr(lk, f))[ok] for f in
                        ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "branch")))
        dce, dcf = syn.dead_centre_extended[ok], syn.dead_centre_folded[ok]
        mean[ok] = _force.mean_force(mw[ok], handle[ok], syn.swing[ok])
        # one call per chunk: the refinement (scipy find_minimum) costs ~10 ms per call
        peak[ok] = _force.peak_force(sub, dce, dcf, band[ok], mw[ok])[0]
        for s0 in range(0, ok.size, SUB_DESIGNS):  # cache-sized blocks of designs
            s = slice(s0, s0 + SUB_DESIGNS)
            part = Linkage(*(getattr(sub, f)[s] for f in
                             ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "branch")))
            sampled[ok[s]] = _force.sampled_peak(part, samples, mw[ok][s], dce[s], dcf[s], band[ok][s])
    # The flywheel scene (issue #6), only for the variants that give inertia.
    j = inertia(batch, cols, n)
    fly = ~np.isnan(j)
    delta = np.where(fly, get("operator.speed_fluctuation"), np.nan)
    required = np.full(n, np.nan)
    passing = np.full(n, np.nan)
    rows = np.nonzero(fly & feasible)[0]
    for s0 in range(0, rows.size, FLYWHEEL_DESIGNS):  # bounded temporaries
        r = rows[s0:s0 + FLYWHEEL_DESIGNS]
        part = _take(lk, r)
        dce, dcf = syn.dead_centre_extended[r], syn.dead_centre_folded[r]
        energy = _fw.energy_band(j[r], speed[r], delta[r])  # W = J w^2 delta, Eq. (2) of pumplink.flywheel
        required[r] = _fw.required_peak_force(part, dce, dcf, mw[r], energy)  # Eq. (4) there
        passing[r] = _fw.min_passing_speed(part, dce, dcf, mw[r], limit[r], j[r], delta[r])
    mean_ok = feasible & (mean <= limit)
    peak_ok = feasible & (np.where(fly, required, peak) <= limit)

    reasons: list = [None] * n
    bad = np.nonzero(~feasible)[0]
    if bad.size:
        cache: dict = {}
        codes = np.asarray(syn.reason)
        for i in bad.tolist():
            k = (int(codes[i]), float(L1[i]), float(D1[i]), float(b[i]), float(swing[i]))
            if k not in cache:
                cache[k] = infeasibility_reason(*k)
            reasons[i] = cache[k]
    return Chunk(batch_index, start, stop, values, np.asarray(syn.frame_length), np.asarray(syn.crank_length),
                 np.asarray(syn.coupler_length), feasible, reasons, np.asarray(syn.time_ratio),
                 np.asarray(syn.transmission_min), np.asarray(syn.transmission_max), mean, peak, sampled,
                 power, limit, mean_ok, peak_ok, mean_ok & peak_ok, flywheel=fly, inertia=j,
                 speed_fluctuation=delta, required_peak_force=required, min_passing_speed=passing)


# ----------------------------------------------------------------------------- scheduling
def plan(batches: Sequence[Batch], chunk: tuple[int, int] = (1, 1),
         designs: int = CHUNK_DESIGNS) -> list[tuple[int, int, int]]:
    """Tasks ``(batch, start, stop)`` for slice K of N of the run, in order.

    The run is all variants of all batches, concatenated; slice K (1-based) of N is the
    contiguous range ``[(K-1) T // N, K T // N)`` of that sequence, so the N slices partition it
    and every variant keeps its name.  A task has at most ``designs`` variants, and at most
    :data:`FLYWHEEL_DESIGNS` for a batch that gives inertia (its variants cost far more).
    """
    k, n = chunk
    total = sum(b.size for b in batches)
    lo, hi = (k - 1) * total // n, k * total // n
    tasks, offset = [], 0
    for i, b in enumerate(batches):
        s, e = max(lo, offset) - offset, min(hi, offset + b.size) - offset
        step = min(designs, FLYWHEEL_DESIGNS) if b.flywheel else designs
        for a in range(s, e, step):
            tasks.append((i, a, min(e, a + step)))
        offset += b.size
    return tasks


_worker_batches: Sequence[Batch] = ()


def _init_worker(batches: Sequence[Batch]) -> None:
    import signal

    global _worker_batches
    _worker_batches = batches
    # The parent handles Ctrl-C and SIGTERM (sent to the whole process group by a terminal or a
    # CI runner): it cancels the queued chunks and the workers exit after their current one.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)


def _evaluate_one(batches: Sequence[Batch], task: tuple[int, int, int], samples: int, post):
    i, start, stop = task
    c = evaluate(batches[i], start, stop, samples, i)
    return c, (post(batches[i], c) if post is not None else None)


def _task(task: tuple[int, int, int], samples: int, post):
    return _evaluate_one(_worker_batches, task, samples, post)


def run(batches: Sequence[Batch], samples: int = 360, chunk: tuple[int, int] = (1, 1), workers: int = 1,
        designs: int | None = None, post: Callable[[Batch, Chunk], Any] | None = None) -> Iterator[tuple[Chunk, Any]]:
    """Evaluate slice ``chunk`` of the run, yielding ``(Chunk, post(batch, chunk))`` in variant order.

    With ``workers`` > 1 the chunks are evaluated by that many processes
    (``concurrent.futures.ProcessPoolExecutor``), at most 2 per worker in flight, so memory stays
    bounded whatever the grid size.  ``post`` (a picklable module-level function, e.g. the row
    formatting) runs in the worker too, so it is parallel as well.
    """
    if designs is None:  # about TASK_SAMPLES crank samples per task, whatever --samples is
        designs = max(64, min(CHUNK_DESIGNS, TASK_SAMPLES // max(samples, 1)))
    tasks = plan(batches, chunk, designs)
    if workers <= 1 or len(tasks) <= 1:
        for t in tasks:
            yield _evaluate_one(batches, t, samples, post)
        return
    from collections import deque
    from concurrent.futures import ProcessPoolExecutor

    import scipy.optimize.elementwise  # noqa: F401  imported once here, inherited by forked workers

    pool = ProcessPoolExecutor(max_workers=workers, initializer=_init_worker, initargs=(tuple(batches),))
    try:
        pending: deque = deque()
        it = iter(tasks)
        for t in it:
            pending.append(pool.submit(_task, t, samples, post))
            if len(pending) >= 2 * workers:
                break
        while pending:
            result = pending.popleft().result()
            nxt = next(it, None)
            if nxt is not None:
                pending.append(pool.submit(_task, nxt, samples, post))
            yield result
    finally:
        # Ctrl-C, SIGTERM or an error: drop the queued chunks and let the running ones finish
        # (tasks are sized to take well under a second at ordinary --samples).  Killing a worker
        # instead can cut a result message in half and leave the pool's reader thread blocked.
        pool.shutdown(wait=True, cancel_futures=True)
