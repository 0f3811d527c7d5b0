"""What keeps hostile model files in check: every limit (one table), the safe XML parser, and
how paths are shown in messages.

Model files and every file they name are untrusted input. Each limit has a default, an
environment variable (read by every command) and, for some, a ``build`` flag.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

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


# Every limit can be set from the environment (any command) and some by ``build`` flags.
LIMIT_ENV = {
    "max_input_bytes": "MYRABOT_DESC_MAX_INPUT_BYTES",
    "max_include_depth": "MYRABOT_DESC_MAX_INCLUDE_DEPTH",
    "max_macro_depth": "MYRABOT_DESC_MAX_MACRO_DEPTH",
    "max_macro_calls": "MYRABOT_DESC_MAX_MACRO_CALLS",
    "max_output_elements": "MYRABOT_DESC_MAX_ELEMENTS",
}


@dataclass
class Limits:
    """Guards against hostile input; each is configurable (``build`` flags, or the environment
    variables of LIMIT_ENV for every command). Mesh limits live in meshio.py."""

    max_input_bytes: int = 20_000_000      # one file
    max_include_depth: int = 32
    max_macro_depth: int = 200             # nested macro calls (xacro dies near 400)
    max_macro_calls: int = 20_000          # macro calls in one build (5x the 4,000-call benchmark)
    max_output_elements: int = 200_000     # counted while macros expand (2^n call bombs stop early)

    def __post_init__(self):
        for attr, env in LIMIT_ENV.items():
            setattr(self, attr, _env_int(env, getattr(self, attr)))


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

