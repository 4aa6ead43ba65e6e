"""Batch files: a base spec plus axes to vary; parsing, validation and variant naming.

One format for both pumps: the base is a rope-pump spec (:mod:`pumplink.inputs.pump`) or a
piston-pump spec (``mechanism = "crank-slider"``, :mod:`pumplink.inputs.piston`), and the axes
vary that spec's numeric keys.  A batch file (TOML) names a base spec and the keys to vary::

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

The verdict is that of ``pumplink force`` (:func:`pumplink.evaluate.evaluate`).  A variant
whose spec gives inertia (``wheel.inertia``, ``wheel.mass`` or ``load.moving_mass``, in the base or
on an axis) is decided by the least energy model that is enough (the flywheel or full dynamics);
any other by the quasi-static model with the dead band.  Every variant of one batch file has the
same spec keys; a run over several files can mix the models (and the pumps).

Everything here is a pure function of the parsed files except :func:`load_batch` /
:func:`load_inputs`, which read files.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from pumplink.errors import SpecError, bad_character, shown
from pumplink.inputs import load
from pumplink.inputs.piston import PistonSpec, parse_piston
from pumplink.inputs.pump import PumpSpec, parse_spec, spec_to_dict
from pumplink.inputs.toml import (
    MAX_NAME_CHARS,
    is_piston_data,
    read_toml,
    spec_name,
    validate_spec,
)

#: Checks ``--fail-on`` can select (the default selects all three, as ``pumplink force`` does).
#: ``peak`` is the verdict's peak: the flywheel's least peak force where the variant gives
#: inertia, else the windowed peak outside the dead bands.
#: ``checks`` is every other check that can fail a design (transmission angle, power, grip
#: speed); ``warnings`` makes a warning fail the run too (as ``--strict``).  ``all`` is the
#: verdict: the first four.
FAIL_CHECKS = ("mean", "peak", "infeasible", "checks", "warnings")
VERDICT_CHECKS = FAIL_CHECKS[:4]


#: Spec keys that give the inertia and so turn on the energy models (``PumpSpec.gives_inertia``),
#: by mechanism.
INERTIA_KEYS = ("wheel.inertia", "wheel.mass", "load.moving_mass")
PISTON_INERTIA_KEYS = ("wheel.inertia", "wheel.mass")
#: The mechanism of a rope pump (the pump paper's four-bar) and of a piston pump.
FOUR_BAR, CRANK_SLIDER = "four-bar", "crank-slider"


#: Largest number of values on one axis (each axis is held in memory and sent to every worker).
MAX_AXIS_VALUES = 1_000_000


#: Largest number of variants in one run (indices stay exact in float64 and int64).
MAX_VARIANTS = 10**15


#: Significant digits kept for linspace values, so {start=0.2, stop=0.3, num=3} gives 0.25
#: exactly (what a user would type), not 0.25000000000000006.
LINSPACE_DIGITS = 12


_TOP_KEYS = ("name", "base", "vary")


def _leaf_fields(model) -> dict:
    """{dotted key: its pydantic field} of every key of the model's tables."""
    import typing

    fields = {}
    for section, field in model.model_fields.items():
        annotation = field.annotation
        args = [a for a in typing.get_args(annotation) if a is not type(None)] or [annotation]
        for k, sub in (getattr(args[0], "model_fields", None) or {}).items():
            fields[f"{section}.{k}"] = sub
    return fields


def _leaf_keys(model) -> tuple[str, ...]:
    return tuple(_leaf_fields(model))


#: Dotted spec paths that an axis may vary (every key of a spec's tables), by mechanism.
VARIABLE_KEYS = _leaf_keys(PumpSpec)
PISTON_VARIABLE_KEYS = _leaf_keys(PistonSpec)
#: The keys that are counts (whole numbers: an axis's 24.0 is given as 24).
INTEGER_KEYS = frozenset(k for k, f in _leaf_fields(PumpSpec).items() if f.annotation is int)


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
    spec: PumpSpec | PistonSpec
    axes: tuple[Axis, ...]

    def name(self, index: int) -> str:
        """The name of variant ``index`` (:func:`variant_name`)."""
        return variant_name(self, index)

    def names(self, start: int, stop: int) -> list[str]:
        """The names of variants ``start..stop-1`` (:func:`variant_names`)."""
        return variant_names(self, start, stop)

    @property
    def mechanism(self) -> str:
        """:data:`FOUR_BAR` (a rope pump) or :data:`CRANK_SLIDER` (a piston pump)."""
        return CRANK_SLIDER if isinstance(self.spec, PistonSpec) else FOUR_BAR

    @property
    def size(self) -> int:
        return math.prod(len(a.values) for a in self.axes)

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(a.key for a in self.axes)

    def given(self, key: str) -> bool:
        """True when the variants set the spec key ``section.name`` (in the base or on an axis)."""
        section, name = key.split(".")
        return key in self.keys or getattr(getattr(self.spec, section), name, None) is not None

    @property
    def flywheel(self) -> bool:
        """True when the variants give inertia (:data:`INERTIA_KEYS`): the flywheel model decides.

        Every variant of a batch sets the same keys, so this holds for all of them or none.
        """
        keys = PISTON_INERTIA_KEYS if self.mechanism == CRANK_SLIDER else INERTIA_KEYS
        return any(self.given(k) for k in keys)


# ----------------------------------------------------------------------------- parsing
# ----------------------------------------------------------------------------- parsing
def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _is_finite(v: Any) -> bool:
    """A finite float: False for NaN, inf and integers beyond the float range (10**400)."""
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


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
                raise SpecError(
                    f"{where}: [vary] '{key}' has {shown(v)} ({type(v).__name__}), not a number; "
                    f"give a list of numbers such as [0.2, 0.25]"
                )
            if not _is_finite(v):
                raise SpecError(f"{where}: [vary] '{key}' has {shown(v)}, not a finite number")
        if len(raw) > MAX_AXIS_VALUES:
            raise SpecError(
                f"{where}: [vary] '{key}' has {len(raw)} values, more than {MAX_AXIS_VALUES:,}; "
                f"split the batch"
            )
        return np.array(raw, dtype=float)
    if isinstance(raw, dict):
        unknown = sorted(set(raw) - {"start", "stop", "num"})
        if unknown:
            raise SpecError(
                f"{where}: [vary] '{key}' has unknown key '{unknown[0]}'; a range is "
                f"{{ start = ..., stop = ..., num = ... }} (ends included)"
            )
        for part in ("start", "stop", "num"):
            if part not in raw:
                raise SpecError(
                    f"{where}: [vary] '{key}' range is missing '{part}'; a range is "
                    f"{{ start = ..., stop = ..., num = ... }} (ends included)"
                )
        start, stop, num = raw["start"], raw["stop"], raw["num"]
        for part, v in (("start", start), ("stop", stop)):
            if not _is_number(v) or not _is_finite(v):
                raise SpecError(f"{where}: [vary] '{key}' range {part} = {shown(v)} is not a finite number")
        if not isinstance(num, int) or isinstance(num, bool):
            raise SpecError(
                f"{where}: [vary] '{key}' range num = {shown(num)} is not an integer; give the "
                f"number of values, ends included (e.g. num = 7)"
            )
        if not 1 <= num <= MAX_AXIS_VALUES:
            raise SpecError(
                f"{where}: [vary] '{key}' range num = {shown(num)} is out of range; allowed: "
                f"1 <= num <= {MAX_AXIS_VALUES:,}"
            )
        if num > 1 and start == stop:
            raise SpecError(
                f"{where}: [vary] '{key}' range has start = stop = {start!r} with num = {num}; "
                f"give num = 1 or different ends"
            )
        vals = np.linspace(float(start), float(stop), num).tolist()
        lo, hi = min(start, stop), max(start, stop)
        # the ends exactly as written (one ulp below a limit stays below it), the values between
        # rounded to LINSPACE_DIGITS and kept inside the ends
        inner = [min(max(float(f"{v:.{LINSPACE_DIGITS}g}"), lo), hi) for v in vals[1:-1]]
        return np.array([vals[0], *inner, vals[-1]][:num], dtype=float)
    raise SpecError(
        f"{where}: [vary] '{key}' = {shown(raw)} must be a list of numbers or a range "
        f"{{ start = ..., stop = ..., num = ... }}"
    )


def _set(data: dict, key: str, value: float) -> dict:
    section, field = key.split(".")
    if key in INTEGER_KEYS and float(value).is_integer():  # a count (ratchet.teeth): 24.0 is 24
        value = int(value)
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
        raise SpecError(f'{source}: empty batch file; expected base = "spec.toml" (or [base]) and [vary]')
    for k in data:
        if k not in _TOP_KEYS:
            close = difflib.get_close_matches(k, _TOP_KEYS, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise SpecError(f"{source}: unknown key '{k}' in a batch file{hint}; allowed: name, base, [vary]")
    label = data.get("name", stem or Path(source).stem)
    bad = bad_character(label) if isinstance(label, str) else None
    if not isinstance(label, str) or not label.strip() or len(label) > MAX_NAME_CHARS or bad:
        holds = f" (it holds {bad})" if bad else ""
        raise SpecError(
            f"{source}: 'name' = {shown(label)} must be text of 1 to {MAX_NAME_CHARS} printable "
            f"characters{holds}; it is the prefix of every variant name"
        )
    if "base" not in data:
        raise SpecError(
            f"{source}: missing key 'base'; give base = \"spec.toml\" or the spec inline as [base]"
        )
    raw_base = data["base"]
    if isinstance(raw_base, str):
        path = Path(raw_base)
        if not path.is_absolute():
            path = (folder or Path(".")) / path
        try:
            spec = load(path)  # the one loader: a rope pump's or a piston pump's spec
        except SpecError as exc:
            raise SpecError(f"{source}: base = {shown(raw_base)}: {exc}") from None
    elif isinstance(raw_base, dict):
        base = dict(raw_base)
        base.setdefault("name", label)
        spec = (parse_piston if is_piston_data(base) else parse_spec)(base, source=f"{source} [base]")
    else:
        raise SpecError(
            f"{source}: 'base' = {shown(raw_base)} must be a spec file name (text) or a [base] table"
        )
    base = spec_to_dict(spec)
    piston = isinstance(spec, PistonSpec)
    parse = parse_piston if piston else parse_spec
    keys = PISTON_VARIABLE_KEYS if piston else VARIABLE_KEYS
    example = "piston.bore" if piston else "linkage.rocker"

    vary = data.get("vary")
    if vary is None:
        raise SpecError(f'{source}: missing [vary] table; add e.g. [vary] "{example}" = [0.2, 0.25]')
    if not isinstance(vary, dict):
        raise SpecError(
            f"{source}: 'vary' = {shown(vary)} must be a table ([vary]) of \"section.key\" = values"
        )
    if not vary:
        raise SpecError(f'{source}: [vary] is empty; add an axis such as "{example}" = [0.2, 0.25]')
    for key in vary:
        if key not in keys:
            close = difflib.get_close_matches(key, keys, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise SpecError(
                f"{source}: [vary] '{key}' is not a numeric spec key{hint}; allowed: {', '.join(keys)}"
            )
    axes = []
    for (key, raw), short in zip(vary.items(), _short_keys(list(vary))):
        values = _axis_values(key, raw, source)
        for v in sorted({float(values.min()), float(values.max())}):
            # the spec's limits are intervals: the extremes decide for every value on the axis
            parse(_set(base, key, v), source=f"{source}: [vary] '{key}' value {_value_label(v)}")
        labels = tuple(_value_label(v) for v in values.tolist())
        axes.append(Axis(key, values, labels, short))
    first = base
    for a in axes:
        first = _set(first, a.key, float(a.values[0]))
    try:
        parse(first, source=f"{source}: [vary] {', '.join(vary)}")
    except SpecError as exc:
        raise SpecError(f"{exc}".rstrip(".") + " (check the varied keys against the base spec).") from None
    b = Batch(source, label, base, spec, tuple(axes))
    if b.size > MAX_VARIANTS:
        raise SpecError(
            f"{source}: [vary] makes {b.size:.3g} variants, more than {MAX_VARIANTS:.0e}; "
            f"use fewer values per axis"
        )
    return b


def spec_batch(spec: PumpSpec | PistonSpec, source: str) -> Batch:
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
    return spec_batch(validate_spec(spec_name(data, path), str(path), PumpSpec, PistonSpec), str(path))


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
    """``--fail-on``: comma-separated subset of :data:`FAIL_CHECKS`; ``all`` (the verdict: a
    variant that FAILs) or ``none``."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if "none" in parts:
        parts = [p for p in parts if p != "none"]
        if not parts:
            return ()
    if "all" in parts:
        parts = [p for p in parts if p != "all"] + list(VERDICT_CHECKS)
    bad = [p for p in parts if p not in FAIL_CHECKS]
    if bad or not parts:
        raise SpecError(
            f"--fail-on {text!r}: unknown check {bad[0] if bad else '(empty)'!r}; give a comma-separated "
            f"list of {', '.join(FAIL_CHECKS)}, or all (the verdict), or none"
        )
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
    parts = [
        np.array([f"{a.short}={lab}" for lab in a.labels], dtype=object)[ij[:, j]].tolist()
        for j, a in enumerate(batch.axes)
    ]
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
