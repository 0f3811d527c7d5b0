"""OGRE material scripts as explicit values: SDF <material> blocks or JSON (``myrabot-desc materials``)."""

from __future__ import annotations

import json
import re
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.materials import scripts
from myrabot_desc.materials import stock as stock_mod
from myrabot_desc.materials.resolve import MaterialResolver, find_texture, resolved
from myrabot_desc.materials.stock import gz_sim_values, stock_material


def _num(v: float) -> str:
    s = format(float(v), ".6g")
    return "0" if s == "-0" else s


def _vec(v) -> str:
    return " ".join(_num(x) for x in v)


def _xml_comment(text: str) -> str:
    return text.replace("--", "- -")


_NUM_LIST = re.compile(r"\[\s+(-?[\d.eE+-]+(?:,\s+-?[\d.eE+-]+)*)\s+\]")


def _compact_vectors(text: str) -> str:
    """Colours on one line: [0.3, 0.3, 0.3, 1.0] instead of six lines."""
    return _NUM_LIST.sub(lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]", text)


def sdf_block(res, texture_uri: str | None) -> str:
    """One SDF <material> for a ResolvedMaterial (explicit colours; texture as PBR albedo map)."""
    m = res.material
    notes = []
    if m.transparency > 0:
        notes.append(f"transparency {_num(m.transparency)}: put <transparency>{_num(m.transparency)}"
                     "</transparency> on the visual")
    if m.texture and res.texture_path is None and not res.is_stock:
        notes.append(f"texture {m.texture} not found in ../textures or next to the script")
    lines = [f"<!-- {_xml_comment(m.name)} ({_xml_comment(res.source)}) -->"]
    lines += [f"<!-- {_xml_comment(n)} -->" for n in notes]
    lines += ["<material>",
             f"  <ambient>{_vec(m.ambient)}</ambient>",
             f"  <diffuse>{_vec(m.diffuse)}</diffuse>",
             f"  <specular>{_vec(m.specular)}</specular>",
             f"  <emissive>{_vec(m.emissive)}</emissive>"]
    if not m.lighting:
        lines.append("  <lighting>false</lighting>")
    if texture_uri:
        lines += ["  <pbr>", "    <metal>", f"      <albedo_map>{texture_uri}</albedo_map>",
                  "    </metal>", "  </pbr>"]
    lines.append("</material>")
    return "\n".join(lines)


def _texture_uri(res, prefix: str | None) -> str | None:
    if not res.texture:
        return None
    if prefix is not None:
        return prefix + res.texture
    return str(res.texture_path.resolve()) if res.texture_path else res.texture


def export(file: str | None, fmt: str = "sdf", names=(), texture_prefix: str | None = None,
           stock: bool = False) -> tuple[str, list[str]]:
    """The text ``materials`` writes (SDF <material> blocks or JSON) for a script FILE, or for Gazebo's
    stock table with ``stock``, and the script's warnings. InputError for an unknown ``names``."""
    if stock:
        path, warnings = None, []
        available = {n: stock_material(n) for n in stock_mod.names()}
        where = "Gazebo's stock table"
    else:
        path = Path(file)
        siblings = MaterialResolver([path.parent])

        def parents(name: str):
            own = siblings._load().get(name)      # noqa: SLF001 (same package)
            return own if own is not None else stock_material(name)

        script = scripts.parse_file(path, parents=parents)
        available, warnings, where = script.materials, script.warnings, "this file"
    mats = list(available.values())
    if names:
        missing = [n for n in names if n not in available]
        if missing:
            raise InputError(f"no material named {', '.join(map(repr, missing))} in {where} "
                             f"(it has {len(mats)}: {', '.join(m.name for m in mats[:8])}"
                             f"{'...' if len(mats) > 8 else ''})", Loc(str(path)) if path else None)
        mats = [available[n] for n in names]
    results = [resolved(m, find_texture(path, m.texture) if (m.texture and path) else None) for m in mats]
    source = str(path) if path else "stock"
    if fmt == "json":
        doc = {"file": source, "materials": [], "warnings": warnings}
        for r in results:
            d = r.material.as_dict()
            d["texture_path"] = str(r.texture_path.resolve()) if r.texture_path else None
            if stock:
                gz = gz_sim_values(r.name)
                d["gz_sim_lookup"] = {k: list(v) for k, v in gz.items()} if gz else None
            doc["materials"].append(d)
        text = _compact_vectors(json.dumps(doc, indent=2)) + "\n"
    else:
        head = [f"<!-- {len(results)} material(s) from {_xml_comment(source)}; explicit values for "
                "gz-sim, which cannot read OGRE scripts -->"]
        head += [f"<!-- warning: {_xml_comment(w)} -->" for w in warnings]
        text = "\n".join(head + [sdf_block(r, _texture_uri(r, texture_prefix)) for r in results]) + "\n"
    return text, warnings
