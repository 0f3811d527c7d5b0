"""What a conversion did with each element of the source: the conversion report.

Every link, joint, visual, collision, inertial, mimic, transmission, ``<gazebo>`` property,
plugin and sensor of the URDF gets one entry with its fate in the target:

- ``kept``: carried over as it is;
- ``translated``: carried over in another form (``detail`` says from what to what);
- ``approximated``: carried over with changed numbers (``detail`` says how);
- ``dropped``: not in the output (``detail`` says why).

``convert`` prints ``summary()`` on stderr; ``--report FILE`` writes the whole list as JSON
(``.json``) or text (any other suffix). Pure Python: the SDF path must not import numpy.
"""

from __future__ import annotations

from myrabot_desc.records import Struct


FATES = ("kept", "translated", "approximated", "dropped")
SINGULAR = {"gazebo": "Gazebo setting"}
PLURAL = {"gazebo": "Gazebo settings", "gazebo-joint": "gazebo-joints"}


class Entry(Struct):
    kind: str                   # 'link', 'joint', 'visual', 'collision', 'inertial', 'mimic', 'gazebo', ...
    name: str
    fate: str                   # one of FATES
    detail: str = ""
    loc: object = None          # diagnostics.Loc or None


class Report:
    """Entries in source order; the last word on an element wins (``set`` replaces)."""

    def __init__(self, target: str, source: str = ""):
        self.target = target
        self.source = source
        self._entries: dict[tuple[str, str], Entry] = {}

    def set(self, kind: str, name: str, fate: str, detail: str = "", loc=None) -> None:
        if fate not in FATES:
            raise ValueError(f"unknown fate {fate!r}")
        key = (kind, name)
        old = self._entries.get(key)
        self._entries[key] = Entry(kind, name, fate, detail, loc if loc is not None else (old.loc if old else None))

    def get(self, kind: str, name: str) -> Entry | None:
        return self._entries.get((kind, name))

    @property
    def entries(self) -> list[Entry]:
        return list(self._entries.values())

    def counts(self) -> dict[str, int]:
        out = {f: 0 for f in FATES}
        for e in self._entries.values():
            out[e.fate] += 1
        return out

    def summary(self) -> str:
        c = self.counts()
        kinds: dict[str, int] = {}
        for e in self._entries.values():
            if e.fate == "dropped":
                kinds[e.kind] = kinds.get(e.kind, 0) + 1
        dropped = ", ".join(f"{n} {PLURAL.get(k, k + 's') if n > 1 else SINGULAR.get(k, k)}"
                            for k, n in sorted(kinds.items()))
        return (f"{self.target}: {len(self._entries)} source elements: {c['kept']} kept, {c['translated']} "
                f"translated, {c['approximated']} approximated, {c['dropped']} dropped"
                + (f" ({dropped})" if dropped else ""))

    def as_dict(self) -> dict:
        return {"target": self.target, "source": self.source, "counts": self.counts(),
                "elements": [{"kind": e.kind, "name": e.name, "fate": e.fate, "detail": e.detail,
                              "loc": str(e.loc) if e.loc else None} for e in self._entries.values()]}

    def to_json(self) -> str:
        import json

        return json.dumps(self.as_dict(), indent=1) + "\n"

    def to_text(self) -> str:
        lines = [self.summary()]
        for e in self._entries.values():
            where = f"{e.loc}: " if e.loc else ""
            lines.append(f"{where}{e.kind} '{e.name}': {e.fate}{': ' + e.detail if e.detail else ''}")
        return "\n".join(lines) + "\n"

    def render(self, path: str) -> str:
        return self.to_json() if str(path).lower().endswith(".json") else self.to_text()


def seed(report: Report, robot) -> None:
    """Every element of the source, first as 'kept'; the converters then say what changed."""
    entries = report._entries

    def kept(kind, name, loc, detail=""):
        # Report.set's rule without its check of the fate: an entry without a loc keeps the old one
        key = (kind, name)
        if loc is None:
            old = entries.get(key)
            loc = old.loc if old else None
        entries[key] = Entry(kind, name, "kept", detail, loc)

    for link in robot.links.values():
        name = link.name
        kept("link", name, link.loc)
        if link.inertial is not None:
            kept("inertial", name, link.inertial.loc)
        for k, v in enumerate(link.visuals):
            kept("visual", part_name(name, k), v.loc)
        for k, c in enumerate(link.collisions):
            kept("collision", part_name(name, k), c.loc)
    for j in robot.joints.values():
        kept("joint", j.name, j.loc)
        if j.mimic is not None:
            kept("mimic", j.name, j.loc, f"of '{j.mimic.joint}'")
    for t in robot.transmissions:
        kept("transmission", t.name or "?", t.loc)


def part_name(link: str, k: int) -> str:
    """How the report names a link's k-th visual or collision."""
    return link if k == 0 else f"{link}[{k}]"
