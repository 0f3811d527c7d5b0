"""Resource URIs for gz-sim: ``package://`` becomes ``model://`` or an absolute path.

gz-sim resolves ``model://NAME/...`` by looking for a folder called NAME in
``GZ_SIM_RESOURCE_PATH``; an absolute path works with no setup but only on this
machine. ``absolute`` is the default because the output then loads as it is;
``model`` is for models that travel (the CLI prints the resource path to set).
"""

from __future__ import annotations

from pathlib import Path

STYLES = ("absolute", "model")


class UriMapper:
    def __init__(self, robot, style: str, notes):
        self.robot = robot
        self.style = style
        self.notes = notes
        self.resource_dirs: set[str] = set()
        self._unresolved: list[str] = []
        self._renamed: set[str] = set()

    def map(self, uri: str, resolved: Path | None = None) -> str:
        if resolved is None:
            try:
                resolved = self.robot.resolve_uri(uri)
            except Exception:  # a bad URI is reported once, below; it must not stop the conversion
                resolved = None
        if self.style == "model" and uri.startswith("package://"):
            rest = uri[len("package://"):]
            pkg = rest.split("/", 1)[0]
            root = self.robot.package_roots.get(pkg)
            if root is not None:
                root = Path(root)
                self.resource_dirs.add(str(root.parent.resolve()))
                if root.name != pkg and pkg not in self._renamed:
                    self._renamed.add(pkg)
                    self.notes.warn(f"package '{pkg}' lives in folder '{root.name}': model://{pkg}/ resolves only "
                                    f"through a folder named '{pkg}' on GZ_SIM_RESOURCE_PATH (use --uri-style absolute)")
            elif uri not in self._unresolved:
                self._unresolved.append(uri)
            return "model://" + rest
        if resolved is not None:
            return str(Path(resolved).resolve())
        if uri not in self._unresolved:
            self._unresolved.append(uri)
        if uri.startswith("package://"):
            return "model://" + uri[len("package://"):]
        return uri

    def map_file(self, path) -> str:
        """A file found on disk (a texture next to a material script): model:// when it lies in a
        package and the style asks for it, else its absolute path."""
        p = Path(path).resolve()
        if self.style == "model":
            for pkg, root in sorted(self.robot.package_roots.items()):
                root = Path(root).resolve()
                if p.is_relative_to(root):
                    return self.map(f"package://{pkg}/{p.relative_to(root).as_posix()}", p)
        return str(p)

    def finish(self) -> None:
        if self._unresolved:
            shown = ", ".join(self._unresolved[:5]) + (" ..." if len(self._unresolved) > 5 else "")
            self.notes.warn(f"{len(self._unresolved)} resource URI(s) not found on disk, written as model:// "
                            f"for GZ_SIM_RESOURCE_PATH: {shown}")
