"""TOML scene files: read with ``tomllib`` (Python >= 3.11, or the ``tomli`` package on
3.9/3.10), written by a small writer for the scene structure (no dependency). Neither knows any key:
the reader hands the parsed tables to :meth:`Scene.from_dict` (the engine's schema checks
every key and type), and the writer walks the scene dataclasses, leaving out what equals
the engine's default in compact tables.

The file holds exactly ``Scene.to_dict()``: the tables ``[belt]``, ``[[pulleys]]`` (with
``[pulleys.friction]``, ``[pulleys.takeup]``, ``[pulleys.drive]``, ``[pulleys.brake]``),
``[[idlers]]``, ``[solver]``, ``[recording]`` and the root key ``gravity``. Keys left out
take their defaults; keys whose default is "none" (``pulleys.inertia``, ``belt.length``, a
pulley's ``takeup`` ...) are simply absent. Every key, its unit, default and rule:
``docs/scene-format.md``.

Floats are written with ``repr``, the shortest text that reads back as the same double,
so ``load_scene(path)`` after ``scene.save(path)`` gives an equal scene, and the same
simulation bit for bit.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import fields, is_dataclass
from pathlib import Path
from typing import Any, Union

from ._beltrs import SceneError, __version__
from .scene import Idler, Scene, field_default

try:  # Python >= 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - exercised on Python 3.9/3.10 only
    try:
        import tomli as _toml  # type: ignore[no-redef]
    except ModuleNotFoundError:
        _toml = None  # type: ignore[assignment]

__all__ = ["dumps_scene", "load_scene", "loads_scene", "save_scene"]

PathLike = Union[str, "os.PathLike[str]"]

#: Scene classes written compactly: one short block each, fields at their defaults left
#: out (a long conveyor has thousands of idlers). Other tables are written in full.
_COMPACT = (Idler,)
#: Fields always written, even at their default.
_ALWAYS = {"center"}
#: Fields written first in their table (what the table is), the rest in field order.
_FIRST = ("name", "formulation", "model")


def _need_reader() -> Any:
    if _toml is None:
        raise ImportError(
            "reading TOML scene files needs Python >= 3.11 (tomllib) or the 'tomli' package on "
            "Python 3.9/3.10: pip install tomli"
        )
    return _toml


# --- reading ----------------------------------------------------------------------------
def loads_scene(text: str, source: str = "<string>") -> Scene:
    """Read a scene from the text of a TOML scene file.

    Raises:
        beltrs.SceneError: the text is not valid TOML, or holds an unknown key (with a "did
            you mean" suggestion) or a value of the wrong type. The message starts with
            ``source``.
    """
    toml = _need_reader()
    try:
        data = toml.loads(text)
    except toml.TOMLDecodeError as err:
        raise SceneError(f"{source}: not valid TOML: {err}") from None
    except RecursionError:
        # The TOML reader recurses once per nested array or inline table; no scene key is
        # nested more than a few levels.
        raise SceneError(
            f"{source}: an array or inline table nested deeper than Python's recursion limit: "
            "no scene key is nested more than 5 levels"
        ) from None
    try:
        return Scene.from_dict(data)
    except SceneError as err:
        raise SceneError(f"{source}: {err}") from None


def load_scene(path: PathLike) -> Scene:
    """Read a TOML scene file (``docs/scene-format.md``).

    Only the structure is checked here (unknown keys, types); values are checked against
    their rules (ranges, geometry) when the scene is compiled by
    :class:`beltrs.Simulation`.

    Raises:
        beltrs.SceneError: invalid TOML, an unknown key or a wrong type; the message starts
            with the file name and names the full key path.
        OSError: the file cannot be read.
    """
    path = Path(path)
    with open(path, "rb") as fh:
        raw = fh.read()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise SceneError(f"{path}: not UTF-8 text ({err})") from None
    return loads_scene(text, str(path))


# --- writing ----------------------------------------------------------------------------
def _string(s: str) -> str:
    out = ['"']
    for ch in s:
        code = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\r":
            out.append("\\r")
        elif code < 0x20 or code == 0x7F:
            out.append(f"\\u{code:04X}")
        elif 0xD800 <= code <= 0xDFFF:
            raise SceneError(f"string {s!r}: contains a lone surrogate, which TOML (UTF-8) cannot hold")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _value(v: Any) -> str:
    """One TOML value. The scene has been normalised, so floats are floats."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        # repr is the shortest text that reads back as the same double; inf, -inf and nan
        # are TOML 1.0 floats too.
        return repr(v)
    if isinstance(v, str):
        return _string(v)
    if is_dataclass(v):
        items = [f"{k} = {_value(x)}" for k, x in _items(v, compact=False)]
        return "{ " + ", ".join(items) + " }" if items else "{}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise SceneError(f"{v!r}: cannot be written to a scene file")  # not reachable after from_dict


def _items(obj: Any, compact: bool) -> list[tuple[str, Any]]:
    """(key, value) pairs to write: None is absent; in compact form, defaults are too."""
    out = []
    ordered = sorted(fields(obj), key=lambda f: f.name not in _FIRST)  # stable sort
    for f in ordered:
        v = getattr(obj, f.name)
        if v is None:
            continue
        if compact and f.name not in _ALWAYS:
            default = field_default(type(obj), f.name)
            # Compare the written text, so that e.g. -0.0 is not taken for the default 0.0.
            if default is not None and _value(v) == _value(default):
                continue
        out.append((f.name, v))
    return out


def _is_table_list(v: Any) -> bool:
    return isinstance(v, list) and all(is_dataclass(x) for x in v)


def _table(lines: list[str], header: str, obj: Any, array: bool) -> None:
    """Write ``obj`` under ``[header]`` (or ``[[header]]``): its plain keys first, then its
    sub-tables and arrays of tables, in field order."""
    compact = isinstance(obj, _COMPACT)
    items = _items(obj, compact)
    if header:
        if lines and lines[-1] != "":
            lines.append("")
        lines.append(f"[[{header}]]" if array else f"[{header}]")
    nested = []
    for k, v in items:
        if (is_dataclass(v) and not compact) or (_is_table_list(v) and v):
            nested.append((k, v))
        elif _is_table_list(v):
            continue  # an empty list of tables is the default: leave it out
        else:
            lines.append(f"{k} = {_value(v)}")
    for k, v in nested:
        sub = f"{header}.{k}" if header else k
        if is_dataclass(v):
            _table(lines, sub, v, array=False)
        else:
            for item in v:
                _table(lines, sub, item, array=True)


def dumps_scene(scene: Scene) -> str:
    """The text of a TOML scene file holding ``scene``.

    Raises:
        beltrs.SceneError: a field holds a value of the wrong type (checked by reading the
            scene's dict form back with :meth:`Scene.from_dict`).
    """
    canonical = Scene.from_dict(scene.to_dict())
    lines = [
        f"# beltrs {__version__} scene file. SI units; every key is described in docs/scene-format.md.",
        "",
    ]
    _table(lines, "", canonical, array=False)
    return "\n".join(lines) + "\n"


def atomic_write(path: PathLike, data: Any, binary: bool) -> None:
    """Write ``data`` (text or bytes, or a callable taking the open file) to ``path`` via a
    temporary file in the same directory and a rename, so that a crash never leaves a
    partial file. The file gets the usual permissions (0666 less the umask)."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)  # mkstemp makes 0600 files
        mode = "wb" if binary else "w"
        kw = {} if binary else {"encoding": "utf-8", "newline": "\n"}
        with os.fdopen(fd, mode, **kw) as fh:
            if callable(data):
                data(fh)
            else:
                fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def save_scene(scene: Scene, path: PathLike) -> None:
    """Write ``scene`` to ``path`` as TOML, atomically (temporary file, then rename)."""
    atomic_write(path, dumps_scene(scene), binary=False)
