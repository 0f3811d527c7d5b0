"""What keeps hostile model files in check: every limit (one table), the safe XML parser, and
how paths are shown in messages.

Model files and every file they name are untrusted input. Each limit has a default, an
environment variable (read by every command) and, for some, a ``build`` flag.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError


def _env_int(name: str, default: int) -> int:
    import os

    raw = os.environ.get(name, "").strip()
    if not raw:
        return default
    try:
        value = int(raw.replace("_", ""))
    except ValueError:
        raise InputError(f"{name}={raw!r} is not a whole number") from None
    if value <= 0:
        raise InputError(f"{name}={raw!r} must be positive")
    return value


class Limit(NamedTuple):
    field: str          # attribute of Limits
    env: str            # environment variable (every command reads it)
    default: int
    flag: str | None    # ``build`` flag, where there is one
    help: str


# THE table of limits: every reader of a limit asks Limits (or limit()), none reads the environment itself.
LIMITS: tuple[Limit, ...] = (
    Limit("max_input_bytes", "MYRABOT_DESC_MAX_INPUT_BYTES", 20_000_000, "--max-input-bytes",
          "largest model file (URDF, xacro, YAML) read"),
    Limit("max_include_depth", "MYRABOT_DESC_MAX_INCLUDE_DEPTH", 32, "--max-include-depth",
          "deepest include nesting"),
    Limit("max_macro_depth", "MYRABOT_DESC_MAX_MACRO_DEPTH", 200, "--max-macro-depth",
          "deepest macro call nesting (xacro itself dies near 400)"),
    Limit("max_macro_calls", "MYRABOT_DESC_MAX_MACRO_CALLS", 20_000, "--max-macro-calls",
          "most macro calls in one build (5x the 4,000-call benchmark)"),
    Limit("max_output_elements", "MYRABOT_DESC_MAX_ELEMENTS", 200_000, "--max-elements",
          "most elements a build may produce, counted as macros expand"),
    Limit("max_mesh_bytes", "MYRABOT_DESC_MAX_MESH_BYTES", 50_000_000, None, "largest mesh file read"),
    Limit("max_mesh_triangles", "MYRABOT_DESC_MAX_MESH_TRIANGLES", 2_000_000, None, "most triangles in one mesh"),
    Limit("max_material_bytes", "MYRABOT_DESC_MAX_MATERIAL_BYTES", 5 * 1024 * 1024, None,
          "largest OGRE material script (Gazebo's own gazebo.material is 24 kB)"),
)
LIMIT_ENV = {lim.field: lim.env for lim in LIMITS}


def limit(field: str) -> int:
    """One limit's value now: its environment variable, else the default."""
    lim = next(lim for lim in LIMITS if lim.field == field)
    return _env_int(lim.env, lim.default)


class Limits:
    """The limits of one run: the table's defaults, the environment over them, flags over both."""

    __slots__ = tuple(lim.field for lim in LIMITS)

    def __init__(self, **overrides):
        for lim in LIMITS:
            value = overrides.pop(lim.field, None)
            setattr(self, lim.field, value if value else _env_int(lim.env, lim.default))
        if overrides:
            raise TypeError(f"unknown limits: {', '.join(overrides)}")


def limits_help() -> str:
    """The table as ``--help`` shows it: one ``VARIABLE [default]  what`` line per limit."""
    width = max(len(lim.env) + len(str(lim.default)) for lim in LIMITS) + 3
    return "\n".join(f"  {f'{lim.env} [{lim.default}]':<{width}}  {lim.help}" for lim in LIMITS)


def display(path) -> str:
    """A path as users like to read it: relative to the working folder when inside it."""
    import os

    p = Path(path)
    try:
        rel = os.path.relpath(p.resolve(), Path.cwd())
    except ValueError:
        return str(p)
    return rel if not rel.startswith("..") else str(p.resolve())


def _short(text: str, n: int = 200) -> str:
    """Hostile inputs carry huge expressions: keep error messages to one readable line."""
    return text if len(text) <= n else text[:n] + f"... ({len(text)} characters)"


def safe_parser():
    from lxml import etree

    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                           huge_tree=False, remove_blank_text=False, collect_ids=False)


def parse_xml_bytes(data: bytes, name: str):
    """Parse XML bytes safely; refuse DTDs/entities; InputError with file:line on failure."""
    from lxml import etree

    if not data.strip():
        raise InputError("empty file", Loc(name))
    head = data[:4096].lstrip()
    if b"<!DOCTYPE" in data[:65536] or b"<!ENTITY" in data[:65536]:
        line = data[:data.find(b"<!")].count(b"\n") + 1 if b"<!" in data else 1
        raise InputError("DTDs and entity declarations are not allowed in model files", Loc(name, line))
    if head.startswith(b"\x00") or b"\x00" in data[:1024]:
        raise InputError("not an XML file (binary data)", Loc(name, 1))
    try:
        root = etree.fromstring(data, parser=safe_parser())
    except etree.XMLSyntaxError as exc:
        line = exc.position[0] if exc.position else None
        msg = exc.msg or str(exc)
        msg = re.sub(r", line \d+, column \d+$", "", msg)
        raise InputError(f"malformed XML: {msg}", Loc(name, line)) from None
    except ValueError as exc:
        raise InputError(f"malformed XML: {exc}", Loc(name)) from None
    except RecursionError:
        raise InputError("malformed XML: elements nest too deeply", Loc(name)) from None
    # The byte check above misses a DOCTYPE behind 64 kB of comment or in another encoding (UTF-7)
    info = root.getroottree().docinfo
    if info.internalDTD is not None or info.externalDTD is not None or info.doctype:
        raise InputError("DTDs and entity declarations are not allowed in model files", Loc(name, 1))
    return root

