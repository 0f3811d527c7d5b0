"""Find ROS packages without ROS, for ``$(find pkg)`` and ``package://pkg/...``.

Search order (first match wins):
  1. explicit ``-p NAME=PATH`` mappings;
  2. the input file's own package: walk up to a ``package.xml`` (its <name>) or a
     rosbuild ``manifest.xml`` (the folder's name);
  3. packages under ``--package-path DIR`` (repeatable), then ``ROS_PACKAGE_PATH``,
     then ``AMENT_PREFIX_PATH`` (``<prefix>/share/<name>``);
  4. packages installed in Python: ament indexes under site-packages prefixes
     (example-robot-data ships one) and the bundled ``myrabot_description``.
"""

from __future__ import annotations

import functools
import os
import re
import sys
from pathlib import Path
from urllib.parse import unquote

from myrabot_desc.errors import InputError
from myrabot_desc.safety import PSEUDO_FOLDERS, check_path, is_pseudo_folder, limit, may_open, read_checked, real_root

_NAME_RE = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
MAX_SCAN_DEPTH = 6  # how deep --package-path folders are searched


def package_name(folder: Path) -> str | None:
    """Name of the package rooted at ``folder`` (package.xml or manifest.xml), else None."""
    pxml = folder / "package.xml"
    if pxml.is_file():
        # through the path gate: a regular file inside the package folder (a symlink out of it, to
        # a file elsewhere on the machine, is not read), read no further than the manifest limit
        try:
            data = read_checked(pxml, [folder], limit("max_manifest_bytes"), what="package.xml")
        except InputError:
            return folder.name
        m = _NAME_RE.search(data[:20000].decode("utf-8", errors="replace"))
        return m.group(1) if m else folder.name
    if (folder / "manifest.xml").is_file():
        return folder.name
    return None


def own_package(path: Path) -> tuple[str, Path] | None:
    """The package that contains ``path``: walk up to the nearest package.xml/manifest.xml."""
    for folder in [path if path.is_dir() else path.parent, *path.parents]:
        name = package_name(folder)
        if name:
            return name, folder
    return None


MAX_SCAN_FOLDERS = 5_000  # folders one search path may make us look at (``--package-path /``)


def _scan(root: Path, found: dict[str, Path], depth: int = 0, budget: list | None = None) -> None:
    """Collect packages under ``root`` (a package folder is not descended into). Bounded in depth
    and in folders visited; /proc, /sys and /dev are never entered; symlinked folders are not followed."""

    budget = [MAX_SCAN_FOLDERS] if budget is None else budget
    if depth > MAX_SCAN_DEPTH or budget[0] <= 0 or not root.is_dir():
        return
    budget[0] -= 1
    if str(root) in PSEUDO_FOLDERS:
        return
    name = package_name(root)
    if name:
        found.setdefault(name, root)
        return
    try:
        children = sorted(p for p in root.iterdir() if not p.name.startswith(".") and not p.is_symlink()
                          and p.is_dir())
    except OSError:
        return
    for child in children:
        if budget[0] <= 0:
            return
        _scan(child, found, depth + 1, budget)


def _python_prefix_shares() -> list[Path]:
    """``share`` folders of prefixes installed in Python (cmeel wheels, the venv)."""
    out = []
    for p in sys.path:
        if p.endswith("site-packages"):
            cand = Path(p) / "cmeel.prefix" / "share"
            if cand.is_dir():
                out.append(cand)
    out.append(Path(sys.prefix) / "share")
    return out


BUNDLED_ASSEMBLY = "xacro/myrabot.urdf.xacro"


def data_root() -> Path:
    """Folder of the bundled ROS package ``myrabot_description``.

    In a source checkout it is the repository top (package.xml beside the
    package folder); in an installed wheel it is ``myrabot_desc/share/...``.
    """
    here = Path(__file__).resolve().parent.parent   # myrabot_desc/
    shipped = here / "share" / "myrabot_description"
    if (shipped / "package.xml").is_file():
        return shipped
    return here.parent


def bundled_path(relative: str = BUNDLED_ASSEMBLY) -> Path:
    return data_root() / relative



class PackageResolver:
    """Resolves package names to folders; remembers what it resolved (``used``)."""

    def __init__(self, packages: dict[str, str] | None = None, package_paths=(), input_file: Path | None = None,
                 use_environment: bool = True):
        self.explicit = {k: Path(v).expanduser().resolve() for k, v in (packages or {}).items()}
        for name, path in self.explicit.items():
            if not path.is_dir():
                raise InputError(f"-p {name}={path}: no such folder")
        self.own = own_package(input_file.resolve()) if input_file else None
        self.package_paths = [Path(p).expanduser().resolve() for p in package_paths]
        self.use_environment = use_environment
        self._index: dict[str, Path] | None = None
        self.used: dict[str, Path] = {}

    def _build_index(self) -> dict[str, Path]:
        found: dict[str, Path] = {}
        for d in self.package_paths:
            _scan(d, found)
        if self.use_environment:
            for d in filter(None, os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep)):
                _scan(Path(d), found)
            for prefix in filter(None, os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep)):
                share = Path(prefix) / "share"
                if share.is_dir():
                    for child in sorted(share.iterdir()):
                        if child.is_dir() and package_name(child):
                            found.setdefault(package_name(child), child)
        # Python-installed prefixes with an ament index (example-robot-data ships one).
        for share in _python_prefix_shares():
            index = share / "ament_index" / "resource_index" / "packages"
            if index.is_dir():
                for marker in sorted(index.iterdir()):
                    if (share / marker.name).is_dir():
                        found.setdefault(marker.name, share / marker.name)
        found.setdefault("myrabot_description", data_root())
        return found

    def find(self, name: str) -> Path | None:
        if name in self.explicit:
            path = self.explicit[name]
        elif self.own and self.own[0] == name:
            path = self.own[1]
        else:
            if self._index is None:
                self._index = self._build_index()
            path = self._index.get(name)
        if path is not None:
            self.used[name] = path
        return path

    def roots(self) -> list[Path]:
        """Folders files may be read from: every package resolved so far."""
        return list(dict.fromkeys(self.used.values()))


def split_package_uri(uri: str) -> tuple[str, str] | None:
    """``package://pkg/rest`` (also ``package:///pkg/rest``) -> (pkg, rest)."""
    if not uri.startswith("package://"):
        return None
    rest = uri[len("package://"):].lstrip("/")
    pkg, _, tail = rest.partition("/")
    return (pkg, tail) if pkg else None


def resource_roots(base: Path, package_roots: dict[str, Path], extra=()) -> list[Path]:
    """Folders a model's meshes and textures may come from: the model's own package (else the
    folder above the model, for the common urdf/ + meshes/ layout), the packages its URIs
    name, and the bundled package. A model from a stranger cannot make us read /etc/passwd
    or ~/.ssh through ``file://``, an absolute path, ``../..`` or a symlink. ``extra``: the folders
    the user allowed (``--allow-path``), which cover meshes as they cover includes."""

    return list(_base_roots(real_root(base))) + [real_root(r) for r in package_roots.values()] + \
        [real_root(Path(r)) for r in extra]


@functools.lru_cache(maxsize=256)
def _base_roots(base: Path) -> tuple[Path, ...]:
    if is_pseudo_folder(base):      # a model from /dev/stdin: no folder of its own, nothing "above" it
        return (data_root().resolve(),)
    own = own_package(base)
    # the folder above the model, but never the whole disk
    return tuple(Path(r).resolve() for r in (own[1] if own else base.parent, base, data_root())
                 if not is_pseudo_folder(r) or Path(r).resolve() == data_root().resolve())


def _locate(uri: str, package_roots: dict[str, Path], base: Path, extra=()) -> tuple[Path | None, bool]:
    """(the file ``uri`` names or None, whether it lies inside :func:`resource_roots`).

    A path outside the roots is returned (not inside) whether or not it exists: nothing about it is
    looked at, so no message can tell a file that exists outside the roots from one that does not."""
    try:
        path = _resolve_any(uri, package_roots, base, exists=False)
        if path is None:
            return None, False
        roots = resource_roots(base, package_roots, extra)
        real = path.resolve()
        if not any(real == real_root(r) or real.is_relative_to(real_root(r)) for r in roots):
            return path, False
        if not path.is_file():
            return None, False
        return path, may_open(path, roots)   # symlinks resolved, regular files
    except (OSError, ValueError, RuntimeError):   # a 5000-character name (ENAMETOOLONG), a NUL byte: no such file
        return None, False


def outside_roots(uri: str, package_roots: dict[str, Path], base: Path, extra=()) -> Path | None:
    """The path ``uri`` names when it lies outside :func:`resource_roots`, existing or not (else None)."""
    path, inside = _locate(uri, package_roots, base, extra)
    return path if path is not None and not inside and _outside(path, package_roots, base, extra) else None


def _outside(path: Path, package_roots, base, extra=()) -> bool:
    real = path.resolve()
    return not any(real == real_root(r) or real.is_relative_to(real_root(r))
                   for r in resource_roots(base, package_roots, extra))


def unresolved_reason(uri: str, package_roots: dict[str, Path], base: Path, extra=()) -> str | None:
    """Why a URI that does not resolve does not (for messages): "outside the allowed folders" (never
    whether such a file exists), "not a regular file", or None when it simply names no file."""

    path, inside = _locate(uri, package_roots, base, extra)
    if path is not None and not inside:
        if _outside(path, package_roots, base, extra):
            return "outside the allowed folders"
        try:
            check_path(path, resource_roots(base, package_roots, extra))
        except InputError as exc:
            return exc.message.split(": ", 1)[-1]
    return None


def resolve_resource_uri(uri: str, package_roots: dict[str, Path], base: Path, extra=()) -> Path | None:
    """Resolve a mesh/texture URI to a file inside :func:`resource_roots`, or None."""
    path, inside = _locate(uri, package_roots, base, extra)
    return path if inside else None


def _resolve_any(uri: str, package_roots: dict[str, Path], base: Path, exists: bool = True) -> Path | None:
    """Resolve a mesh/texture URI to a file. Never leaves the package root it names."""

    uri = uri.strip()
    if uri.startswith("package://"):
        parts = split_package_uri(uri)
        if not parts or parts[0] not in package_roots:
            return None
        root = real_root(package_roots[parts[0]])
        path = (root / unquote(parts[1])).resolve()
        if not path.is_relative_to(root):
            return None
    elif uri.startswith("file://"):
        path = Path(unquote(uri[len("file://"):]))
    elif uri.startswith("model://"):
        parts = split_package_uri("package://" + uri[len("model://"):])
        if not parts or parts[0] not in package_roots:
            return None
        root = real_root(package_roots[parts[0]])
        path = (root / parts[1]).resolve()
        if not path.is_relative_to(root):
            return None
    elif "://" in uri:
        return None
    else:
        path = (base / uri)
    return path if not exists or path.is_file() else None


_PACKAGE_FILENAME = re.compile(r'(filename=)"(package://[^"]+)"')


def file_uris(text: str, package_roots: dict[str, Path], base: Path) -> str:
    """``filename="package://pkg/x"`` -> ``filename="file:///abs/x"`` for every resolvable URI of a
    built document (``build --resolve-uris``); the others stay as they are."""

    def sub(m):
        p = resolve_resource_uri(m.group(2), package_roots, base)
        return f'{m.group(1)}"file://{p}"' if p else m.group(0)

    return _PACKAGE_FILENAME.sub(sub, text)
