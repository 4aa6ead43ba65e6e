"""The pump spec: a TOML file validated by pydantic (SI units; angles in degrees).

The keys and units are the contract other tools write against.  Every bad value is
reported as one sentence naming the key, the value and what is allowed.
"""

from __future__ import annotations

import difflib
import math
import os
import re
import stat
import tomllib
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from pumplink.constants import (
    DEFAULT_ARM_MASS,
    DEFAULT_EFFICIENCY,
    DEFAULT_SPEED_FLUCTUATION,
    FORCE_LIMIT_N,
    GRAVITY,
    WATER_DENSITY,
)
from pumplink.errors import SHOWN_CHARS, SpecError, escape_control, has_control, shown

#: Most of the other problems of a spec listed after the first one in an error message.
MORE_KEYS = 8


# ----------------------------------------------------------------------------- spec physics
# Pure functions of spec values, on floats or numpy arrays alike (a single run passes floats,
# a batch passes one array per key), so one formula serves both and gives the same bits.
def rope_force(rope_force=None, head=None, pipe_diameter=None, efficiency=None):
    """Rope force at the wheel rim Fw [N] (docs/physics.md §5).

    ``rope_force`` when given, else the water column's weight over the pump's efficiency,
    rho g head (pi d^2 / 4) / efficiency, with :data:`~pumplink.constants.DEFAULT_EFFICIENCY`
    when ``efficiency`` is None.

    Parameters
    ----------
    rope_force : Fw [N] or None;  head : pumping head [m];  pipe_diameter : rising-main bore [m];
    efficiency : [-] or None.
    """
    if rope_force is not None:
        return rope_force
    eff = DEFAULT_EFFICIENCY if efficiency is None else efficiency
    return WATER_DENSITY * GRAVITY * head * math.pi * (pipe_diameter * pipe_diameter) / 4.0 / eff


def moving_mass(moving_mass=None, head=None, pipe_diameter=None):
    """Mass moving at rim speed [kg]: ``moving_mass``, else the water column in the rising main
    rho head pi d^2 / 4 when ``head`` is given, else 0 (docs/models.md §2)."""
    if moving_mass is not None:
        return moving_mass
    if head is not None:
        return WATER_DENSITY * head * math.pi * (pipe_diameter * pipe_diameter) / 4.0
    return 0.0


def inertia(radius, wheel_inertia=None, wheel_mass=None, moving_mass_kg=0.0):
    """Moment of inertia about the wheel axle J [kg m^2] (docs/models.md §2).

    ``wheel_inertia``, or ``wheel_mass`` * radius^2 (a rim), or 0, plus the moving mass * radius^2.

    Parameters
    ----------
    radius : wheel radius rw [m];  wheel_inertia : [kg m^2] or None;  wheel_mass : [kg] or None;
    moving_mass_kg : rope and water moving with the rim [kg] (:func:`moving_mass`).
    """
    if wheel_inertia is not None:
        wheel = wheel_inertia
    elif wheel_mass is not None:
        wheel = wheel_mass * radius * radius
    else:
        wheel = 0.0 * radius * radius
    return wheel + moving_mass_kg * radius * radius


class _Section(BaseModel):
    # strict: "0.2" (a string) or true is not a number; ints are accepted as floats.
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class Wheel(_Section):
    radius: float = Field(ge=0.001, le=5, description="upper wheel radius rw [m]")
    axle_height: float | None = Field(
        default=None,
        gt=0,
        le=5,
        description="height of the wheel axle above the ground [m] (optional; the paper uses 0.40-0.70 m)",
    )
    inertia: float | None = Field(
        default=None,
        gt=0,
        le=1000,
        description="moment of inertia of the wheel about its axle [kg m^2] "
        "(optional; turns on the flywheel model)",
    )
    mass: float | None = Field(
        default=None,
        gt=0,
        le=1000,
        description="wheel mass [kg], taken as a rim: J = mass * radius^2 (optional, instead of inertia)",
    )

    @model_validator(mode="after")
    def _one_inertia(self) -> Wheel:
        if self.inertia is not None and self.mass is not None:
            raise ValueError(
                f"give either wheel.inertia [kg m^2] or wheel.mass [kg], not both "
                f"(inertia = {self.inertia!r}, mass = {self.mass!r})"
            )
        return self


class Linkage(_Section):
    L1: float = Field(
        ge=0, le=10, description="horizontal placement of the rocker pivot beyond the stand [m]"
    )
    D1: float = Field(
        ge=-10, le=10, description="depth of the rocker pivot below the axle [m] (negative = above)"
    )
    b: float = Field(ge=0, le=10, description="width of the pump stand [m]")
    rocker: float = Field(ge=0.001, le=10, description="rocker length l4 [m]")
    handle: float = Field(ge=0.001, le=20, description="handle length H, rocker pivot to hand grip [m]")
    swing: float = Field(
        ge=2 * math.pi,  # below: radians, said by _swing_in_degrees
        lt=180,
        description="total handle swing [deg], symmetric about vertical",
    )
    mass_per_length: float | None = Field(
        default=None,
        gt=0,
        le=100,
        description="mass per metre of the handle and coupler [kg/m] for the link-energy estimate "
        "(default 1.56: 3/4-inch steel tube)",
    )
    coupler_mass: float | None = Field(
        default=None,
        ge=0,
        le=1000,
        description="coupler mass [kg] (full dynamics; default mass_per_length * coupler length)",
    )
    handle_mass: float | None = Field(
        default=None,
        ge=0,
        le=1000,
        description="handle mass [kg], a uniform bar from the rocker pivot to the grip (full dynamics; "
        "default mass_per_length * max(handle, rocker))",
    )
    hole_diameter: float | None = Field(
        default=None,
        ge=0.001,
        le=0.1,
        description="diameter of the pin holes on the workshop template [m] (default 0.010)",
    )

    @model_validator(mode="before")
    @classmethod
    def _swing_in_degrees(cls, data: Any) -> Any:
        # A swing below 2 pi is almost surely radians (1.047 for 60 deg): a 1.8 mm crank that
        # fails with no hint otherwise.  Said before the range check, with the fix.
        swing = data.get("swing") if isinstance(data, dict) else None
        if (
            isinstance(swing, (int, float))
            and not isinstance(swing, bool)
            and 0 < swing < 2 * math.pi
            and math.degrees(swing) >= 1  # not a slip of 1e-100, which the range error names
        ):
            deg = f"{round(math.degrees(swing), 1):g}"
            raise ValueError(
                f"linkage.swing = {swing!r} looks like radians: did you mean {deg}°? The swing is in "
                f"degrees, {2 * math.pi:g} <= swing < 180 (write swing = {deg})"
            )
        return data


class Load(_Section):
    rope_force: float | None = Field(
        default=None,
        ge=0.001,  # 1 mN: below, the flywheel's energy balance loses every digit (denormal torques)
        le=10_000,
        description="rope force Fw at the wheel rim [N] (or give head and pipe_diameter)",
    )
    head: float | None = Field(default=None, ge=0.001, le=200, description="pumping head [m]")
    pipe_diameter: float | None = Field(default=None, ge=0.001, le=0.5, description="rising-main bore [m]")
    efficiency: float | None = Field(
        default=None,
        ge=0.05,
        le=1,
        description="rope-pump efficiency with head/pipe_diameter [-] (default 0.75)",
    )
    moving_mass: float | None = Field(
        default=None,
        ge=0,
        le=10_000,
        description="rope, pistons and water moving with the wheel rim [kg] (default with head and "
        "pipe_diameter: the water in the rising main)",
    )

    @model_validator(mode="after")
    def _one_load(self) -> Load:
        by_head = self.head is not None or self.pipe_diameter is not None
        if self.rope_force is not None and by_head:
            raise ValueError("give either load.rope_force or load.head with load.pipe_diameter, not both")
        if self.rope_force is None and not (self.head is not None and self.pipe_diameter is not None):
            raise ValueError(
                "give load.rope_force [N], or load.head [m] together with load.pipe_diameter [m]"
            )
        if self.efficiency is not None and not by_head:
            raise ValueError("load.efficiency only applies with load.head and load.pipe_diameter")
        return self

    @property
    def rope_force_N(self) -> float:
        """Rope force at the rim [N] (:func:`rope_force`)."""
        return rope_force(self.rope_force, self.head, self.pipe_diameter, self.efficiency)

    @property
    def moving_mass_kg(self) -> float:
        """Mass moving at rim speed [kg] (:func:`moving_mass`)."""
        return moving_mass(self.moving_mass, self.head, self.pipe_diameter)


class Operator(_Section):
    force_limit: float = Field(
        default=FORCE_LIMIT_N, ge=1, le=10_000, description="largest acceptable operator force [N]"
    )
    speed: float = Field(default=360.0, gt=0, le=7200, description="wheel speed [deg/s]")
    dead_band: float = Field(
        default=20.0,
        ge=0,
        lt=90,
        description="crank angle each side of a dead centre left to the wheel's inertia [deg] "
        "(quasi-static model only)",
    )
    speed_fluctuation: float = Field(
        default=DEFAULT_SPEED_FLUCTUATION,
        gt=0,
        le=1,
        description="largest coefficient of speed fluctuation (w_max - w_min) / w_mean [-] (flywheel model)",
    )
    arm_mass: float | None = Field(
        default=None,
        ge=0,
        le=100,
        description="operator's hands and forearms moving with the grip [kg] (full dynamics: the "
        "muscular effort and the best cadence; default 4.32)",
    )
    arms_in_verdict: bool | None = Field(
        default=None,
        description="true to judge the muscular effort (arm_mass at the grip) against force_limit "
        "instead of the hand force",
    )

    @property
    def arm_mass_kg(self) -> float:
        """operator.arm_mass, or the anthropometric default (pumplink.constants.DEFAULT_ARM_MASS) [kg]."""
        return DEFAULT_ARM_MASS if self.arm_mass is None else self.arm_mass


class PumpSpec(_Section):
    name: str = Field(default="pump", min_length=1, max_length=200, description="design name")

    @field_validator("name")
    @classmethod
    def _printable_name(cls, name: str) -> str:
        # names go into tables, JUnit XML and file names: a newline or an escape sequence breaks
        # the XML and recolours (or clears) the terminal
        if has_control(name):
            raise ValueError(
                f"name = {shown(name)} contains a control character (newline, tab, escape, ...); "
                "give a name of printable characters"
            )
        return name

    wheel: Wheel = Field(description="the [wheel] table: radius [m]")
    linkage: Linkage = Field(description="the [linkage] table: L1, D1, b, rocker, handle, swing")
    load: Load = Field(description="the [load] table: rope_force [N], or head [m] with pipe_diameter [m]")
    operator: Operator = Field(
        default=Operator(),
        description="the [operator] table: force_limit, speed, dead_band, speed_fluctuation",
    )

    @property
    def wheel_torque(self) -> float:
        """Load torque Mw = Fw * rw on the wheel axle [N m] (Eq. 3 of the pump paper)."""
        return self.load.rope_force_N * self.wheel.radius

    @property
    def inertia(self) -> float | None:
        """Moment of inertia about the wheel axle [kg m^2] for the flywheel model, or None.

        Given when the spec states wheel.inertia, wheel.mass or load.moving_mass: the
        wheel's J (or mass * radius^2, a rim) plus the moving mass * radius^2.  A spec with none of
        them is analysed quasi-statically with the dead band, as before.
        """
        w = self.wheel
        if w.inertia is None and w.mass is None and self.load.moving_mass is None:
            return None
        return inertia(w.radius, w.inertia, w.mass, self.load.moving_mass_kg)


#: The built-in default design (``pumplink force`` with no spec; ``pumplink init``).  It is the
#: prototype example: a 0.5 m wheel (20" rim class, docs/physics.md §5), a 1 m handle swung +-30 deg
#: about vertical, 45 N at the rim (about 8 m head through a 23 mm bore at 75 % efficiency).
DEFAULT_SPEC: dict[str, Any] = {
    "name": "Prototype",
    "wheel": {"radius": 0.25},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"rope_force": 45.0},
    "operator": {"force_limit": 100.0, "speed": 360.0, "dead_band": 20.0},
}


def default_spec() -> PumpSpec:
    """The built-in default design as a validated spec."""
    return PumpSpec.model_validate(DEFAULT_SPEC)


def _field_info(loc: tuple) -> Any:
    model: Any = PumpSpec
    info = None
    for part in loc:
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        info = fields[part]
        model = info.annotation
    return info


def _allowed(info: Any) -> str:
    """'0 < value <= 10' from a field's constraints, plus its description."""
    if info is None:
        return ""
    if info.annotation is str:
        return f"{info.description}, allowed: text of 1 to 200 characters"
    lo = hi = None
    for m in info.metadata:
        for attr, sym in (("gt", "<"), ("ge", "<=")):
            if getattr(m, attr, None) is not None:
                lo = f"{getattr(m, attr):g} {sym} "
        for attr, sym in (("lt", "<"), ("le", "<=")):
            if getattr(m, attr, None) is not None:
                hi = f" {sym} {getattr(m, attr):g}"
    rng = f"{lo or ''}value{hi or ''}" if (lo or hi) else "a finite number"
    return f"{info.description}, allowed: a number with {rng}"


def _sections(model: Any) -> str:
    return ", ".join(model.model_fields)


def _describe(err: dict) -> str:
    loc = tuple(str(p) for p in err["loc"])
    key = escape_control(".".join(loc))[:SHOWN_CHARS]
    kind = err["type"]
    value = shown(err.get("input"))
    info = _field_info(loc)
    if kind == "missing":
        what = f" ({info.description})" if info is not None else ""
        return f"missing key '{key}'{what}"
    if kind == "extra_forbidden":
        parent = _field_info(loc[:-1]).annotation if len(loc) > 1 else PumpSpec
        where = f"[{escape_control('.'.join(loc[:-1]))}]" if len(loc) > 1 else "the top level"
        close = difflib.get_close_matches(loc[-1][:SHOWN_CHARS], list(parent.model_fields), n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        return f"unknown key '{key}' = {value}{hint}; allowed keys in {where}: {_sections(parent)}"
    if kind == "model_type":
        return f"'{key}' = {value} must be a table ([{key}]) with keys {_sections(info.annotation)}"
    if kind == "value_error":
        return str(err["msg"]).removeprefix("Value error, ")
    if kind == "finite_number":
        return f"'{key}' = {value} is not a finite number; {_allowed(info)}"
    if kind in ("float_type", "string_type", "float_parsing"):
        want = "text" if kind == "string_type" else "a number"
        return f"'{key}' = {value} ({type(err.get('input')).__name__}) is not {want}; {_allowed(info)}"
    if kind in ("string_too_short", "string_too_long"):
        return f"'{key}' = {value} has the wrong length; {_allowed(info)}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"'{key}' = {value} is out of range; {_allowed(info)}"
    return f"'{key}' = {value}: {err['msg']}"


def parse_spec(data: Any, source: str = "spec") -> PumpSpec:
    """Validate a spec mapping (as read from TOML).

    Raises
    ------
    SpecError
        One sentence per problem (the first in the message, the count of the others after it).
    """
    if not isinstance(data, dict) or not data:
        raise SpecError(
            f"{source}: empty spec; expected [wheel], [linkage], [load] "
            "(write an example with `pumplink init`)"
        )
    if "mechanism" in data:
        raise SpecError(
            f"{source}: a piston-pump spec (mechanism = {data['mechanism']!r}) runs through "
            "`pumplink force` and `pumplink batch` only (docs/piston-pump.md)"
        )
    try:
        return PumpSpec.model_validate(data)
    except ValidationError as exc:
        # An unknown key is usually a typo that also causes a "missing" error: report it first.
        errs = sorted(exc.errors(), key=lambda e: e["type"] != "extra_forbidden")
        first = _describe(errs[0])
        others = [escape_control(".".join(map(str, e["loc"])) or "load")[:SHOWN_CHARS] for e in errs[1:]]
        if len(others) > MORE_KEYS:
            others = [*others[:MORE_KEYS], "..."]
        more = f" (and {len(errs) - 1} more: {', '.join(others)})" if len(errs) > 1 else ""
        raise SpecError(f"{source}: {first}{more}.") from None


def spec_values(spec):
    """``value(key)`` for :func:`pumplink.evaluate.pump_designs`: the spec's value of a dotted key
    ("linkage.swing"), None where the spec does not give it."""

    def value(key: str):
        section, name = key.split(".")
        return getattr(getattr(spec, section), name, None)

    return value


#: Largest input file read [bytes]: a spec is under 1 kB; a batch axis of a million values written
#: out as a list is about 8 MB.  Anything larger is refused before it is read.
MAX_INPUT_BYTES = 10_000_000

#: Deepest nesting of arrays and inline tables, and most parts of one dotted key, in an input
#: file: a spec is 2 deep, a batch 3.  Deeper input is refused before it is parsed (the TOML
#: parser recurses per level, and a dotted key of n parts costs it n^2 memory).
MAX_NESTING = 32

# Strings and comments (skipped: their brackets and dots are text) and the characters that nest
# or split keys.  A multi-line string first, so that """ is not read as "" and a quote.
_TOML_TOKENS = re.compile(
    r'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*|[\[\]{}=,\n.]',
    re.S,
)


def _check_nesting(text: str, path: Path) -> None:
    """Refuse TOML nested deeper than :data:`MAX_NESTING` (brackets, braces or dotted-key parts)
    before the parser sees it.  A conservative scan: strings and comments are skipped, a dot run
    ends at any of ``= , [ ] { }`` or a line end (so ``[0.1, 0.2]`` counts one dot per value)."""
    depth = dots = 0
    for m in _TOML_TOKENS.finditer(text):
        c = m.group()
        if c in "[{":
            depth += 1
            dots = 0
            if depth > MAX_NESTING:
                line = text.count("\n", 0, m.start()) + 1
                raise SpecError(
                    f"{path}: nested more than {MAX_NESTING} levels deep (line {line}); "
                    "a spec is 2 levels deep, a batch file 3"
                )
        elif c in "]}":
            depth = max(depth - 1, 0)
            dots = 0
        elif c == ".":
            dots += 1
            if dots >= MAX_NESTING:  # parts = dots + 1
                line = text.count("\n", 0, m.start()) + 1
                raise SpecError(
                    f"{path}: a dotted key of more than {MAX_NESTING} parts (line {line}); "
                    "spec keys have 2 parts, e.g. linkage.swing"
                )
        elif c in "=,\n":
            dots = 0


def _not_utf8(path: Path, data: bytes, exc: UnicodeDecodeError, expected: str) -> SpecError:
    line = data.count(b"\n", 0, exc.start) + 1
    col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
    return SpecError(
        f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} at line {line}, column {col}; "
        f"saved as Windows-1252 or Latin-1?), expected {expected}; re-save it as UTF-8 (in the "
        f"editor: Save As, encoding UTF-8; or: iconv -f cp1252 -t utf-8 {path.name} > utf8-{path.name})"
    )


def read_toml(path: str | Path, expected: str = "a TOML spec") -> dict[str, Any]:
    """Read a UTF-8 TOML file into a mapping (a leading byte-order mark is allowed).

    Only a regular file of at most :data:`MAX_INPUT_BYTES` is read (not a device such as
    /dev/zero, a pipe or a socket), and only when nested at most :data:`MAX_NESTING` deep.

    Raises
    ------
    SpecError
        Missing, unreadable, non-regular, too large, too deep or non-UTF-8 file, or invalid TOML;
        ``expected`` names what the file should have been.
    """
    path = Path(path)
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer; no effect on a regular file
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        raise SpecError(f"{path}: no such file (write an example spec with `pumplink init {path}`)") from None
    except IsADirectoryError:
        raise SpecError(f"{path}: is a folder, expected {expected} file") from None
    except OSError as exc:
        raise SpecError(f"{path}: cannot be read ({exc.strerror})") from None
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise SpecError(f"{path}: is a folder, expected {expected} file")
        if not stat.S_ISREG(st.st_mode):
            raise SpecError(
                f"{path}: is not a regular file (a device, pipe or socket), expected {expected} file"
            )
        if st.st_size > MAX_INPUT_BYTES:
            raise SpecError(
                f"{path}: {st.st_size:,} bytes, larger than {MAX_INPUT_BYTES:,}; expected {expected} "
                "(a spec is under 1 kB; use ranges { start, stop, num } for long batch axes)"
            )
        with os.fdopen(os.dup(fd), "rb") as f:
            data = f.read(MAX_INPUT_BYTES + 1)
    except OSError as exc:
        raise SpecError(f"{path}: cannot be read ({exc.strerror})") from None
    finally:
        os.close(fd)
    if len(data) > MAX_INPUT_BYTES:  # grew while being read
        raise SpecError(f"{path}: larger than {MAX_INPUT_BYTES:,} bytes; expected {expected}")
    try:
        text = data.decode("utf-8").removeprefix("\ufeff")  # a BOM, as Windows editors write
    except UnicodeDecodeError as exc:
        raise _not_utf8(path, data, exc, expected) from None
    _check_nesting(text, path)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:  # cannot happen below MAX_NESTING; kept as a last guard
        raise SpecError(f"{path}: nested too deeply to read, expected {expected}") from None


def is_piston_data(data: Any) -> bool:
    """True when a spec mapping names a mechanism kind (else it is a rope-pump spec); the piston
    pump's models are in :mod:`pumplink.piston`, imported only for such a spec."""
    return isinstance(data, dict) and "mechanism" in data


def batch_base(data: dict, path: Path) -> Any:
    """The mapping a batch file's ``base`` names (read from its TOML file), else ``base`` as given."""
    base = data.get("base")
    if isinstance(base, str):
        return read_toml(path.parent / base, expected="a TOML spec")
    return base


def is_piston_file(path: str | Path) -> bool:
    """True for a piston-pump spec file, or a batch file whose base is one.  Unreadable files are
    not piston files (the rope-pump path reports their errors)."""
    path = Path(path)
    if not path.is_file():
        return False
    try:
        data = read_toml(path)
        return is_piston_data(data) or (isinstance(data, dict) and is_piston_data(batch_base(data, path)))
    except SpecError:
        return False


def spec_from_file_data(data: Any, path: str | Path) -> PumpSpec:
    """Validate the mapping read from ``path``; the name defaults to the file stem."""
    path = Path(path)
    if isinstance(data, dict) and ("vary" in data or "base" in data):
        raise SpecError(
            f"{path}: this is a batch file (it has "
            f"{'vary' if 'vary' in data else 'base'}); run it with `pumplink batch {path}`"
        )
    if isinstance(data, dict) and data and "name" not in data:
        data = {"name": path.stem, **data}
    return parse_spec(data, source=str(path))


def load_spec(path: str | Path) -> PumpSpec:
    """Read and validate a TOML spec file; the name defaults to the file stem.

    Raises
    ------
    SpecError
        Unreadable file, invalid TOML, or an invalid spec.
    """
    return spec_from_file_data(read_toml(path), path)


def spec_to_dict(spec: PumpSpec) -> dict[str, Any]:
    """The spec as a plain mapping for tomli-w (optional keys left out when unset)."""
    return spec.model_dump(exclude_none=True)


#: The commented spec ``pumplink init`` writes: the default design with every key's unit and
#: allowed range, and the optional keys commented out.  ``{name}`` is filled in.
SPEC_TEMPLATE = """\
# A pumplink spec: the rope pump's wheel, the four-bar linkage, the load and the operator.
# Units: metres, degrees, newtons, kilograms, seconds.  Check it with:  pumplink force {path}
# The keys are explained in docs/physics.md §1 (with a sketch of L1, D1 and b).
name = "{name}"

[wheel]
radius = 0.25          # wheel radius rw [m], 0.001-5 (a 20" tyre rim: about 0.25)
# axle_height = 0.55   # axle height above the ground [m], 0-5: adds grip-height checks
# mass = 4.0           # wheel mass [kg] as a rim, J = mass rw^2: turns on the flywheel model,
#                      # where the wheel speed decides the verdict (docs/models.md §2)
# inertia = 0.25       # or the wheel's moment of inertia [kg m^2] instead of mass

[linkage]
L1 = 0.40              # rocker pivot beyond the stand, horizontally [m], 0-10
D1 = 0.20              # rocker pivot below the axle [m], -10..10 (negative: above)
b = 0.10               # width of the pump stand [m], 0-10
rocker = 0.20          # rocker length l4 [m], 0.001-10
handle = 1.00          # handle length H, rocker pivot to grip [m], 0.001-20
swing = 60.0           # total handle swing [deg], 1-179, symmetric about vertical (not radians)
# mass_per_length = 1.56  # handle and coupler tube [kg/m] (default: 3/4" steel tube)

[load]
rope_force = 45.0      # rope force at the wheel rim Fw [N], 0-10000; or instead:
# head = 10.0          # pumping head [m], 0-200
# pipe_diameter = 0.023  # rising-main bore [m], 0.001-0.5
# efficiency = 0.75    # rope-pump efficiency [-], 0.05-1 (with head and pipe_diameter)
# moving_mass = 4.0    # rope and water moving with the rim [kg] (flywheel model)

[operator]
force_limit = 100.0    # largest acceptable push/pull [N], 1-10000 (women: 70; UK HSE guidance)
speed = 360.0          # wheel speed [deg/s], 0-7200 (360 deg/s = 60 rpm)
dead_band = 20.0       # crank angle each side of a dead centre left to the wheel [deg], 0-89
# speed_fluctuation = 0.2  # largest (w_max - w_min) / w_mean [-], 0-1 (flywheel model)
"""


def spec_template(name: str, path: str = "pump.toml") -> str:
    """The commented spec of :data:`SPEC_TEMPLATE` with this design ``name`` (TOML-quoted)."""
    import json

    quoted = json.dumps(name, ensure_ascii=False)[1:-1]  # a TOML basic string is JSON-compatible
    return SPEC_TEMPLATE.replace("{name}", quoted).replace("{path}", path)
