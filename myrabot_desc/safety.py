"""What keeps hostile model files in check: every limit (one table), the safe XML parser, and
how paths are shown in messages.

Model files and every file they name are untrusted input. Each limit has a default, an
environment variable (read by every command) and, for some, a ``build`` flag.
"""

from __future__ import annotations

import re
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.records import Struct


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


class Limit(Struct):
    """One limit. field: attribute of Limits; env: environment variable (every command reads
    it); default (int); flag: ``build`` flag, where there is one (else None); help."""

    field: str
    env: str
    default: int
    flag: str | None
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
    Limit("max_includes", "MYRABOT_DESC_MAX_INCLUDES", 1_000, "--max-includes",
          "most includes one build processes, repeats counted (a file including the next twice, 25 deep: 2^25)"),
    Limit("max_eval_seconds", "MYRABOT_DESC_MAX_EVAL_SECONDS", 3, None,
          "CPU seconds all ${} expressions of one build may take together"),
    Limit("max_manifest_bytes", "MYRABOT_DESC_MAX_MANIFEST_BYTES", 1_000_000, None,
          "largest package.xml / manifest.xml read"),
    Limit("max_mesh_bytes", "MYRABOT_DESC_MAX_MESH_BYTES", 50_000_000, None,
          "largest mesh file read, and the most a compressed mesh (zip, gz, bz2, xz) may inflate to"),
    Limit("max_mesh_triangles", "MYRABOT_DESC_MAX_MESH_TRIANGLES", 2_000_000, None,
          "most triangles (and polygon corners) in one mesh, counted while reading"),
    Limit("max_mesh_elements", "MYRABOT_DESC_MAX_MESH_ELEMENTS", 500_000, None,
          "most XML elements in one COLLADA mesh"),
    Limit("max_texture_pixels", "MYRABOT_DESC_MAX_TEXTURE_PIXELS", 16_777_216, None,
          "largest texture image read (pixels: 4096x4096)"),
    Limit("max_material_bytes", "MYRABOT_DESC_MAX_MATERIAL_BYTES", 5 * 1024 * 1024, None,
          "largest OGRE material script (Gazebo's own gazebo.material is 24 kB)"),
    Limit("max_mjcf_bodies", "MYRABOT_DESC_MAX_MJCF_BODIES", 2_000, None,
          "most links `convert --to mjcf` takes (2,000 links: ~2 s, 400 MB; 5,000: 12 s, 2 GB)"),
    Limit("max_sim_steps", "MYRABOT_DESC_MAX_SIM_STEPS", 1_000_000, None,
          "most time steps of one `sim` run (--duration x --rate)"),
    Limit("max_render_pixels", "MYRABOT_DESC_MAX_RENDER_PIXELS", 4_194_304, None,
          "largest `render --size` (pixels: 2048x2048)"),
    Limit("max_render_frames", "MYRABOT_DESC_MAX_RENDER_FRAMES", 500, None,
          "most link frames `render --frames` draws"),
    Limit("max_physics_steps", "MYRABOT_DESC_MAX_PHYSICS_STEPS", 1_000_000, None,
          "most MuJoCo steps one `sim settle`/`sweep`/`drive --engine mujoco` takes (2,000 s at 2 ms)"),
    Limit("max_sweep_poses", "MYRABOT_DESC_MAX_SWEEP_POSES", 100_000, None,
          "most poses one `sim sweep` visits (joints x samples)"),
    Limit("max_collision_pairs", "MYRABOT_DESC_MAX_COLLISION_PAIRS", 20_000, None,
          "most pairs of collision shapes whose bounding spheres meet that self-collision (P005, settle, "
          "sweep) tests one by one"),
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


def sim_steps(duration: float, rate: float) -> int:
    """The time steps of a simulation of ``duration`` s at ``rate`` Hz, refused (InputError) past
    ``max_sim_steps``: the programs keep every step's state (86,400 s at 100 kHz: out of memory),
    and a default duration can come from the model (an arm that moves at 1e-9 rad/s)."""
    import math

    if not (math.isfinite(duration) and math.isfinite(rate)) or duration < 0 or rate <= 0:
        raise InputError(f"a simulation of {duration:g} s at {rate:g} Hz cannot be run")
    most = limit("max_sim_steps")
    steps = duration * rate
    if steps > most:
        raise InputError(f"a simulation of {duration:g} s at {rate:g} Hz is {steps:.0f} steps, over the {most}-step "
                         "limit (lower --duration or --rate, or raise MYRABOT_DESC_MAX_SIM_STEPS)")
    return int(round(steps))


def limits_help() -> str:
    """The table as ``--help`` shows it: one ``VARIABLE [default]  what`` line per limit."""
    width = max(len(lim.env) + len(str(lim.default)) for lim in LIMITS) + 3
    return "\n".join(f"  {f'{lim.env} [{lim.default}]':<{width}}  {lim.help}" for lim in LIMITS)


def display(path) -> str:
    """A path as users like to read it: relative to the working folder when inside it.

    Remembered per path and working folder: a build names each file in every location it
    records (Husky: 55 calls for 20 files, 4 ms of its 60 ms resolving symlinks)."""
    import os

    key = (os.fspath(path), os.getcwd())
    shown = _DISPLAYED.get(key)
    if shown is None:
        if len(_DISPLAYED) >= 4096:      # a long-lived process (the viewer, a test run) stays bounded
            _DISPLAYED.clear()
        p = Path(path)
        try:
            rel = os.path.relpath(p.resolve(), key[1])
            shown = rel if not rel.startswith("..") else str(p.resolve())
        except ValueError:
            shown = str(p)
        _DISPLAYED[key] = shown
    return shown


_DISPLAYED: dict = {}


def _short(text: str, n: int = 200) -> str:
    """Hostile inputs carry huge expressions: keep error messages to one readable line."""
    return text if len(text) <= n else text[:n] + f"... ({len(text)} characters)"


def safe_parser(huge_tree: bool = False, **options):
    """lxml's parser with no entities, DTDs or network. ``huge_tree`` only for files whose size
    another limit bounds (meshes: a COLLADA float array is often one text node over 10 MB)."""
    from lxml import etree

    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                           huge_tree=huge_tree, remove_blank_text=False, collect_ids=False, **options)


def check_xml_bytes(data: bytes, name: str) -> None:
    """The checks before any XML parser sees the bytes: empty, a DTD or entity declaration
    near the start, binary data. (The parsers refuse a DTD found later themselves.)"""
    if not data or data.isspace():      # (strip() would copy the whole file)
        raise InputError("empty file", Loc(name))
    head = data[:4096].lstrip()
    if b"<!DOCTYPE" in data[:65536] or b"<!ENTITY" in data[:65536]:
        line = data[:data.find(b"<!")].count(b"\n") + 1 if b"<!" in data else 1
        raise InputError("DTDs and entity declarations are not allowed in model files", Loc(name, line))
    if head.startswith(b"\x00") or b"\x00" in data[:1024]:
        raise InputError("not an XML file (binary data)", Loc(name, 1))


def parse_xml_bytes(data: bytes, name: str):
    """Parse XML bytes safely; refuse DTDs/entities; InputError with file:line on failure."""
    from lxml import etree

    check_xml_bytes(data, name)
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



# ------------------------------------------------------------------ may I open this path?
class PathRefused(InputError):
    """A path outside the allowed folders, or not a regular file (code X006)."""

    def __init__(self, message: str, loc: Loc | None = None, stack=None):
        super().__init__(message, loc, stack, code="X006")


def is_pseudo(path) -> bool:
    """A path that names no folder of files: /dev/stdin, /proc/self/fd/0, a pipe, ``-``."""
    s = str(path)
    return s == "-" or s.startswith(("/dev/", "/proc/")) or not Path(s).resolve().parent.is_dir() \
        or Path(s).resolve() == Path("/") or str(Path(s).resolve().parent) in ("/dev", "/proc")


def check_path(path, roots=None, what: str = "file") -> Path:
    """THE answer to "may I open this path?" for every reader of model-named files.

    Symlinks are resolved and the real path must lie inside one of ``roots`` (when given); it
    must be a regular file (no FIFO, device, socket or folder: those block or never end).
    Returns the resolved path; raises PathRefused (outside / not a regular file) or InputError
    (no such file)."""
    import os
    import stat

    p = Path(path)
    try:
        real = p.resolve()
    except (OSError, RuntimeError, ValueError):
        raise InputError(f"cannot read {_short(str(p), 120)}: unresolvable path") from None
    if roots is not None and not any(real == r or real.is_relative_to(r) for r in _real_roots(roots)):
        # the same answer whether or not the path exists: no message tells which files exist there
        raise PathRefused(f"refusing to read {_short(str(p), 200)}: outside the allowed folders (the input's "
                          "folder and package roots; use --allow-path DIR or -p NAME=DIR to allow it)")
    try:
        st = os.stat(real)
    except (OSError, ValueError) as exc:
        if isinstance(exc, FileNotFoundError):
            raise InputError(f"no such {what}: {_short(str(p), 200)}") from None
        raise InputError(f"cannot read {_short(str(p), 200)}: {getattr(exc, 'strerror', None) or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        kind = "a folder" if stat.S_ISDIR(st.st_mode) else "a FIFO" if stat.S_ISFIFO(st.st_mode) else \
            "a device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode) else "a socket or special file"
        raise PathRefused(f"refusing to read {_short(str(p), 200)}: {kind}, not a regular file")
    return real


def _exists(p: Path) -> bool:
    try:
        return p.exists()
    except (OSError, ValueError):
        return False


def _real_roots(roots) -> list[Path]:
    out = []
    for r in roots:
        try:
            out.append(real_root(r))
        except (OSError, RuntimeError):
            continue
    return out


_ROOTS: dict = {}


def real_root(folder) -> Path:
    """A root folder (a package, the model's folder) with its symlinks resolved, once per
    process: every mesh and texture a run checks asks for the same few roots (69 robots:
    ~12,000 resolves, 1.5 s). The files themselves are still resolved on every check; what a
    folder resolves to is the user's file system, which no model file can change."""
    import os

    key = str(folder)
    if not os.path.isabs(key):      # relative to the working folder, which may change (library use)
        key = (os.getcwd(), key)
    real = _ROOTS.get(key)
    if real is None:
        real = Path(folder).resolve()
        if len(_ROOTS) < 4096:
            _ROOTS[key] = real
    return real


def may_open(path, roots=None) -> bool:
    """check_path as a yes/no (for scans that skip what they may not read)."""
    try:
        check_path(path, roots)
        return True
    except InputError:
        return False


def open_checked(path, roots=None, what: str = "file"):
    """Open a checked path for binary reading without following a swap to a FIFO (O_NONBLOCK,
    then fstat): the check and the open see the same regular file."""
    import os
    import stat

    real = check_path(path, roots, what)
    try:
        fd = os.open(real, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise InputError(f"cannot read {_short(str(path), 200)}: {exc.strerror}") from None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise PathRefused(f"refusing to read {_short(str(path), 200)}: not a regular file")
    return os.fdopen(fd, "rb")


def read_bounded(f, max_bytes: int) -> bytes:
    """Up to ``max_bytes`` + 1 bytes of the binary file ``f``, as ``f.read(max_bytes + 1)`` gives
    them, without allocating that much first (a 684-byte mesh read against the 50 MB limit took 3x
    as long): pieces the size the file says it has, then doubling, since its size is only a hint
    (/proc files say 0 and a file may grow)."""
    import os

    want = max_bytes + 1
    try:
        step = os.fstat(f.fileno()).st_size + 1
    except (OSError, ValueError):
        step = 0
    step = min(want, max(step, 1 << 16))
    parts, got = [], 0
    while got < want:
        n = min(step, want - got)
        piece = f.read(n)
        parts.append(piece)
        got += len(piece)
        if len(piece) < n:          # the end (a regular file or a closed pipe)
            break
        step *= 2
    return parts[0] if len(parts) == 1 else b"".join(parts)


def read_checked(path, roots=None, max_bytes: int | None = None, what: str = "file") -> bytes:
    """Read a whole checked file, refusing it past ``max_bytes`` (read as it grows, not trusted
    from stat: /proc files report 0 bytes)."""
    with open_checked(path, roots, what) as f:
        if max_bytes is None:
            return f.read()
        data = read_bounded(f, max_bytes)
    if len(data) > max_bytes:
        raise InputError(f"{display(path)} is over the {max_bytes}-byte limit "
                         "(see MYRABOT_DESC_MAX_INPUT_BYTES)")
    return data


PSEUDO_FOLDERS = ("/dev", "/proc", "/sys", "/run")


def is_pseudo_folder(folder) -> bool:
    """A folder that holds no model files of anyone's package: the root of the disk, /dev (where
    /dev/stdin lives), /proc, /sys. A model read from there gets no folder root at all."""
    real = Path(folder).resolve()
    return real == Path("/") or any(real == Path(p) or real.is_relative_to(p) for p in PSEUDO_FOLDERS)


def read_input(path, max_bytes: int) -> bytes:
    """The model file the user named (a pipe such as /dev/stdin is fine: the user chose it), read
    up to ``max_bytes`` + 1 so that /dev/zero or an endless pipe stops at the limit."""
    p = Path(path)
    try:
        with open(p, "rb") as f:
            data = read_bounded(f, max_bytes)
    except OSError as exc:
        raise InputError(f"cannot read {p}: {exc.strerror}") from None
    if len(data) > max_bytes:
        raise InputError(f"{p} is over the {max_bytes}-byte limit (see MYRABOT_DESC_MAX_INPUT_BYTES)")
    return data


# ------------------------------------------------------------------ linear scans of untrusted text
def scan_tag_attr(text: str, tag: str, attr: str) -> list[str]:
    """Values of ``attr`` on every ``<tag ...>`` / ``<xacro:tag ...>`` start tag of ``text``.

    One pass, no regular expression (``<include\\s[^>]*filename...`` is quadratic on a file of
    unclosed tags: 49 s on 560 kB): each character is looked at a bounded number of times."""
    out: list[str] = []
    n, pos, k = len(text), 0, len(tag)
    while True:
        i = text.find("<", pos)
        if i < 0:
            return out
        j = i + 1
        if text.startswith("xacro:", j):
            j += 6
        if not text.startswith(tag, j) or j + k >= n or text[j + k] not in " \t\r\n":
            pos = i + 1
            continue
        gt = text.find(">", j + k)
        if gt < 0:
            return out
        value = _attr_value(text, j + k, gt, attr)
        if value is not None:
            out.append(value)
        pos = gt + 1


def _attr_value(text: str, start: int, end: int, attr: str) -> str | None:
    pos = start
    while True:
        a = text.find(attr, pos, end)
        if a < 0:
            return None
        pos = a + len(attr)
        if text[a - 1] not in " \t\r\n":
            continue
        p = pos
        while p < end and text[p] in " \t\r\n":
            p += 1
        if p >= end or text[p] != "=":
            continue
        p += 1
        while p < end and text[p] in " \t\r\n":
            p += 1
        if p >= end or text[p] not in "\"'":
            continue
        close = text.find(text[p], p + 1, end)
        return text[p + 1:close] if close >= 0 else None


MAX_WALK_FILES = 20_000      # model files a folder walk lists
MAX_WALK_DIRS = 50_000       # folders it visits


# Folders a repository walk never enters (build trees, VCS, environments): check -r and its cache.
SKIP_DIRS = {".git", ".hg", ".svn", "build", "install", "log", "devel", "node_modules", "__pycache__",
             ".venv", "venv", ".tox"}


def walk_models(folder, recursive: bool, suffixes=(".urdf", ".xacro"), skip_dirs=()) -> list[Path]:
    """Model files of ``folder`` (``recursive``: below it too; hidden and ``skip_dirs`` folders
    skipped), each one :func:`check_path`-ed against the folder: a symlink leaving it, a FIFO or
    a device is left out. Symlinked folders are not followed (no loops); the walk is bounded."""
    import os

    top = Path(folder)
    root = [top.resolve()]
    out: list[Path] = []
    if not recursive:
        names = sorted(c for c in top.iterdir() if c.name.endswith(tuple(suffixes)))
        return [c for c in names if may_open(c, root)][:MAX_WALK_FILES]
    dirs_seen = 0
    for here, dirs, names in os.walk(top):
        dirs_seen += 1
        if dirs_seen > MAX_WALK_DIRS or len(out) >= MAX_WALK_FILES:
            break
        dirs[:] = sorted(d for d in dirs if d not in skip_dirs and not d.startswith("."))
        out.extend(p for p in (Path(here) / n for n in sorted(names) if n.endswith(tuple(suffixes)))
                   if may_open(p, root))
    return out[:MAX_WALK_FILES]


def included_names(path, max_bytes: int = 2_000_000) -> set[str]:
    """File names a xacro file includes (``<xacro:include filename=...>``), by a linear scan;
    a file that may not be read, or is over ``max_bytes``, includes nothing."""
    try:
        text = read_checked(path, None, max_bytes).decode("utf-8", errors="replace")
    except InputError:
        return set()
    return {Path(f).name for f in scan_tag_attr(text, "include", "filename")}
