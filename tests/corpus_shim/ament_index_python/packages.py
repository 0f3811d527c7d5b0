"""Test-only stand-in for ``ament_index_python.packages`` so the real xacro CLI resolves ``$(find pkg)``.

xacro (ROS 2 branch, on PyPI) calls ``get_package_share_directory(pkg)`` for ``$(find pkg)``.
Put ``tests/corpus_shim`` on ``PYTHONPATH`` and list package folders in ``CORPUS_PACKAGE_PATH``
(``os.pathsep``-separated, like ``ROS_PACKAGE_PATH``): every folder below them holding a
``package.xml`` (named by its ``<name>``) or a rosbuild ``manifest.xml`` (named by the folder)
is a package; the first one found wins, folders searched in sorted order, packages not descended into.
"""

from __future__ import annotations

import os
import re

_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
_MAX_DEPTH = 6


class PackageNotFoundError(KeyError):
    pass


def _name(folder: str) -> str | None:
    pxml = os.path.join(folder, "package.xml")
    if os.path.isfile(pxml):
        with open(pxml, encoding="utf-8", errors="replace") as f:
            m = _NAME.search(f.read(20000))
        return m.group(1) if m else os.path.basename(folder)
    if os.path.isfile(os.path.join(folder, "manifest.xml")):
        return os.path.basename(folder)
    return None


def _scan(folder: str, found: dict, depth: int = 0) -> None:
    if depth > _MAX_DEPTH or not os.path.isdir(folder):
        return
    name = _name(folder)
    if name:
        found.setdefault(name, folder)
        return
    for child in sorted(os.listdir(folder)):
        path = os.path.join(folder, child)
        if not child.startswith(".") and os.path.isdir(path):
            _scan(path, found, depth + 1)


def _index() -> dict:
    found: dict = {}
    for root in filter(None, os.environ.get("CORPUS_PACKAGE_PATH", "").split(os.pathsep)):
        _scan(os.path.abspath(root), found)
    return found


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    path = _index().get(package_name)
    if path is None:
        raise PackageNotFoundError(f"package '{package_name}' not found in CORPUS_PACKAGE_PATH")
    return path


def get_package_prefix(package_name: str) -> str:
    return get_package_share_directory(package_name)
