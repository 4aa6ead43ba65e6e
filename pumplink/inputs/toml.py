"""Reading pumplink's input files: TOML with guards, one strict base model, one error sentence.

Every file pumplink reads (pump spec, piston spec, batch file, mechanism file) goes through
:func:`read_toml` and is validated by a model derived from :class:`Section` through
:func:`validate`, so every bad value is reported the same way: one sentence naming the key, the
value and what is allowed (:class:`pumplink.errors.SpecError`, exit 2).
"""

from __future__ import annotations

import difflib
import os
import re
import stat
import sys
import tomllib
import types
import typing
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from pumplink.errors import SHOWN_CHARS, SpecError, bad_character, escape_control, shown

#: Most of the other problems of a file listed after the first one in an error message.
MORE_KEYS = 8


#: Longest name of a design, a mechanism or a batch [characters] (a batch's name is the prefix
#: of every variant name).
MAX_NAME_CHARS = 200


def check_name(name: str) -> str:
    """``name`` if it can be written everywhere a name goes (tables, file names, CSV, JSON, JUnit
    XML), else ValueError saying which character cannot (:func:`pumplink.errors.bad_character`)."""
    bad = bad_character(name)
    if bad is not None:
        raise ValueError(f"name = {shown(name)} contains {bad}; give a name of printable characters")
    return name


class Section(BaseModel):
    """The base of every input model: unknown keys, strings for numbers, NaN and inf are errors
    ("0.2" or true is not a number; integers are accepted as floats), and values are frozen.
    A ``name`` (of a spec, a piston-pump spec, a mechanism) is checked by :func:`check_name`."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)

    @field_validator("name", check_fields=False)
    @classmethod
    def _writable_name(cls, name: str) -> str:
        return check_name(name)


def optional(description: str, **bounds) -> Any:
    """A key a file may leave out (None when it does): ``Field(default=None, ...)`` with its
    ``description`` (what the key is, its unit and what leaving it out means) and ``bounds``
    (``ge``, ``le``, ...)."""
    return Field(default=None, description=description, **bounds)


# ----------------------------------------------------------------------------- error sentences
def _inner(annotation: Any) -> Any:
    """The model (or value type) inside ``X | None``, ``list[X]`` and ``dict[K, X]``."""
    while True:
        origin = typing.get_origin(annotation)
        if origin in (typing.Union, types.UnionType):
            args = [a for a in typing.get_args(annotation) if a is not type(None)]
            annotation = args[0] if len(args) == 1 else annotation
            if len(args) != 1:
                return annotation
        elif origin in (list, dict):
            annotation = typing.get_args(annotation)[-1]
        else:
            return annotation


def _container(annotation: Any) -> bool:
    """True for ``dict[K, V]`` or ``list[V]`` (possibly ``| None``): its location has one key more."""
    args = [a for a in typing.get_args(annotation) if a is not type(None)]
    if typing.get_origin(annotation) in (typing.Union, types.UnionType) and len(args) == 1:
        annotation = args[0]
    return typing.get_origin(annotation) in (list, dict)


def _field_info(root: Any, loc: tuple) -> Any:
    """The pydantic field at ``loc`` (a dict key or list index after a container is skipped), or
    None."""
    model: Any = root
    info = None
    skip = False
    for part in loc:
        if skip:  # the key or index inside a dict- or list-typed field
            skip = False
            continue
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        info = fields[part]
        skip = _container(info.annotation)
        model = _inner(info.annotation)
    return info


def _allowed(info: Any) -> str:
    """'0 < value <= 10' from a field's constraints, plus its description."""
    if info is None:
        return ""
    if info.annotation is str:
        longest = next((m.max_length for m in info.metadata if getattr(m, "max_length", None)), None)
        size = f"1 to {longest}" if longest else "at least 1"
        return f"{info.description}, allowed: text of {size} characters"
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


def _choices(info: Any) -> str:
    """The words a Literal field allows: 'a, b or c'."""
    words = [str(a) for a in typing.get_args(_inner(info.annotation))] if info is not None else []
    if not words:
        return "one of the allowed words"
    return words[0] if len(words) == 1 else f"{', '.join(words[:-1])} or {words[-1]}"


#: What a value of the wrong type should have been, by pydantic error type.
_TYPE_WORDS = {
    "float_type": "a number",
    "float_parsing": "a number",
    "int_type": "a whole number",
    "string_type": "text",
    "bool_type": "true or false",
    "list_type": "a list",
    "dict_type": "a table",
}


def describe(root: Any, err: dict) -> str:
    """One pydantic error of a file validated by the model ``root`` as one sentence: the key, the
    value given and what is allowed."""
    loc = tuple(str(p) for p in err["loc"])
    key = escape_control(".".join(loc))[:SHOWN_CHARS] or "the file"
    kind = err["type"]
    value = shown(err.get("input"))
    info = _field_info(root, loc)
    if kind == "missing":
        what = f" ({info.description})" if info is not None and info.description else ""
        return f"missing key '{key}'{what}"
    if kind == "extra_forbidden":
        parent_info = _field_info(root, loc[:-1]) if len(loc) > 1 else None
        parent = _inner(parent_info.annotation) if parent_info is not None else root
        where = f"[{escape_control('.'.join(loc[:-1]))}]" if len(loc) > 1 else "the top level"
        close = difflib.get_close_matches(loc[-1][:SHOWN_CHARS], list(parent.model_fields), n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        return f"unknown key '{key}' = {value}{hint}; allowed keys in {where}: {_sections(parent)}"
    if kind == "model_type":
        return f"'{key}' = {value} must be a table ([{key}]) with keys {_sections(_inner(info.annotation))}"
    if kind == "value_error":
        return str(err["msg"]).removeprefix("Value error, ")
    if kind == "literal_error":
        return f"'{key}' = {value} must be {_choices(info)}"
    if kind == "finite_number":
        return f"'{key}' = {value} is not a finite number; {_allowed(info)}"
    if kind in (
        "float_type",
        "string_type",
        "float_parsing",
        "int_type",
        "bool_type",
        "list_type",
        "dict_type",
    ):
        want = {
            "int_type": "a whole number",
            "string_type": "text",
            "bool_type": "true or false",
            "list_type": "a list",
            "dict_type": "a table",
        }
        return (
            f"'{key}' = {value} ({type(err.get('input')).__name__}) is not {want.get(kind, 'a number')}; "
            f"{_allowed(info)}"
        ).rstrip("; ")
    if kind in ("string_too_short", "string_too_long"):
        return f"'{key}' = {value} has the wrong length; {_allowed(info)}"
    if kind in ("too_short", "too_long"):
        return f"'{key}' = {value} has the wrong length: {err['msg'][0].lower()}{err['msg'][1:]}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"'{key}' = {value} is out of range; {_allowed(info)}"
    return f"'{key}' = {value}: {err['msg']}"


def validate(model: type[Section], data: Any, source: str):
    """``model.model_validate(data)``, or :class:`~pumplink.errors.SpecError` with the first
    problem as one sentence (an unknown key first: it is usually a typo that also causes a
    "missing" error) and where the others are.  A mechanism file (frame, links, [joints]) where
    a pump spec belongs is named as such, with the command that reads it."""
    if isinstance(data, dict) and "joints" in data and "joints" not in model.model_fields:
        raise SpecError(
            f"{source}: is a mechanism file (frame, links, [joints]), not a pump spec; analyse it with "
            f"`pumplink structure {source}`"
        )
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        errs = sorted(exc.errors(), key=lambda e: e["type"] != "extra_forbidden")
        first = describe(model, errs[0])
        others = [escape_control(".".join(map(str, e["loc"])) or "the file")[:SHOWN_CHARS] for e in errs[1:]]
        n = len(others)
        # "at": places in the file, which a reader must not take for more allowed keys
        if n > MORE_KEYS:
            where = f"{', '.join(others[:MORE_KEYS])} and {n - MORE_KEYS:,} others"
        else:
            where = " and ".join([", ".join(others[:-1]), others[-1]] if n > 1 else others)
        more = f"; {n} more problem{'s' if n > 1 else ''}, at {where}" if n else ""
        raise SpecError(f"{source}: {first}{more}.") from None


# ----------------------------------------------------------------------------- reading files
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


def _check_nesting(text: str, path: str | Path) -> None:
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


def _not_utf8(path: str | Path, data: bytes, exc: UnicodeDecodeError, expected: str) -> SpecError:
    line = data.count(b"\n", 0, exc.start) + 1
    col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
    name = Path(path).name
    convert = "iconv -f cp1252 -t utf-8" + ("" if path == STDIN_WORDS else f" {name} > utf8-{name}")
    return SpecError(
        f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} at line {line}, column {col}; "
        f"saved as Windows-1252 or Latin-1?), expected {expected}; re-save it as UTF-8 (in the "
        f"editor: Save As, encoding UTF-8; or: {convert})"
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
    if is_stdin(path):
        return _parse(_stdin_bytes(expected), STDIN_WORDS, expected)
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
    return _parse(data, path, expected)


#: The path that means standard input (``pumplink init - | pumplink force -``), and its name in
#: messages.
STDIN = "-"
STDIN_WORDS = "standard input"

# What standard input held: it can be read once, and a command may read its spec twice (to see
# whether it is a piston pump's, then to load it).
_STDIN_READ: dict[str, bytes] = {}


def is_stdin(path: str | Path | None) -> bool:
    """True for the path ``-``: the spec comes from standard input."""
    return path is not None and str(path) == STDIN


def _stdin_bytes(expected: str) -> bytes:
    """Standard input, read once, at most :data:`MAX_INPUT_BYTES` (SpecError beyond, or when it is
    a terminal: a spec is piped in, not typed)."""
    if "data" not in _STDIN_READ:
        stream = sys.stdin
        if stream is None or stream.isatty():
            raise SpecError(
                f"-: {STDIN_WORDS} is a terminal; pipe {expected} in, e.g. pumplink init - | pumplink force -"
            )
        try:
            _STDIN_READ["data"] = stream.buffer.read(MAX_INPUT_BYTES + 1)
        except OSError as exc:
            raise SpecError(f"{STDIN_WORDS}: cannot be read ({exc.strerror})") from None
    data = _STDIN_READ["data"]
    if len(data) > MAX_INPUT_BYTES:
        raise SpecError(f"{STDIN_WORDS}: larger than {MAX_INPUT_BYTES:,} bytes; expected {expected}")
    return data


def _parse(data: bytes, path: str | Path, expected: str) -> dict[str, Any]:
    """The bytes of a TOML file, decoded (UTF-8, a byte-order mark allowed) and parsed."""
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
    """True when a spec mapping names a mechanism kind (``mechanism = "crank-slider"``: a piston
    pump, :mod:`pumplink.inputs.piston`); else it is a rope-pump spec."""
    return isinstance(data, dict) and "mechanism" in data


#: What a rope-pump spec's file must hold, said when it is empty.
EMPTY_SPEC = "empty spec; expected [wheel], [linkage], [load] (write an example with `pumplink init`)"


def validate_spec(data: Any, source: str, pump: type[Section], piston: type[Section] | None = None):
    """A spec mapping validated once as the pump it describes: a piston pump (``piston``) where it
    names a mechanism (:func:`is_piston_data`) and ``piston`` is given, else a rope pump
    (``pump``); :class:`~pumplink.errors.SpecError` for an empty mapping, a piston pump where only
    rope pumps are read, or the first problem :func:`validate` finds."""
    if piston is not None and is_piston_data(data):
        return validate(piston, data, source)
    if not isinstance(data, dict) or not data:
        raise SpecError(f"{source}: {EMPTY_SPEC}")
    if "mechanism" in data:
        raise SpecError(
            f"{source}: a piston-pump spec (mechanism = {data['mechanism']!r}) runs through "
            "`pumplink force` and `pumplink batch` only (docs/piston-pump.md)"
        )
    return validate(pump, data, source)


def read_spec(path: str | Path, pump: type[Section], piston: type[Section] | None = None):
    """Read a spec file once and validate it (:func:`validate_spec`): the one loader of pump
    specs.  The name defaults to the file's stem (:func:`spec_name`); a batch file is named as
    such, with the command that runs it."""
    data = spec_name(read_toml(path), path)
    piston_pump = piston is not None and is_piston_data(data)
    if isinstance(data, dict) and ("vary" in data or "base" in data) and not piston_pump:
        raise SpecError(
            f"{path}: this is a batch file (it has {'vary' if 'vary' in data else 'base'}); run it with "
            f"`pumplink batch {path}`"
        )
    return validate_spec(data, str(path), pump, piston)


def batch_base(data: dict, path: Path) -> Any:
    """The mapping a batch file's ``base`` names (read from its TOML file), else ``base`` as given."""
    base = data.get("base")
    if isinstance(base, str):
        return read_toml(path.parent / base, expected="a TOML spec")
    return base


def spec_name(data: Any, path: str | Path) -> Any:
    """The mapping read from ``path`` with ``name`` defaulting to the file stem (SpecError when
    the stem cannot be a name, :func:`check_name`)."""
    if isinstance(data, dict) and data and "name" not in data:
        stem = "stdin" if is_stdin(path) else Path(path).stem
        bad = bad_character(stem) or (
            f"more than {MAX_NAME_CHARS} characters" if len(stem) > MAX_NAME_CHARS else None
        )
        if bad is not None:
            raise SpecError(
                f"{escape_control(str(path))}: the name defaults to the file's name {shown(stem)}, "
                f'which holds {bad}; add name = "..." to the file, or rename it'
            )
        return {"name": stem, **data}
    return data
