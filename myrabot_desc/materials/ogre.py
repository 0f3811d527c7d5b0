"""Read OGRE 1.x material scripts (the ``.material`` files of Gazebo classic).

Grammar covered (Ogre manual, "Material Scripts")::

    import * from "other.material"
    vertex_program Name glsl { ... }              // skipped, as are fragment/geometry programs
    material Name [: Parent]
    {
        receive_shadows on
        technique [name]
        {
            pass [name]
            {
                lighting on|off
                ambient r g b [a]                 // also diffuse, emissive; 'vertexcolour' ignored
                specular r g b [a] shininess
                scene_blend alpha_blend
                depth_write on|off
                alpha_rejection greater 128
                vertex_program_ref X { }          // skipped
                texture_unit [name]
                {
                    texture file.png
                    rotate 180
                    scale 1 1
                    colour_op_ex source1 src_manual src_current r g b
                    alpha_op_ex source1 src_manual src_current a
                }
            }
        }
    }

``abstract material`` templates with ``set $name "value"`` variables (filled in by children; a
template itself is never output). ``//`` and ``/* */`` comments. Inheritance follows Ogre: the child starts from a copy of its
parent's techniques; a child technique, pass or texture_unit overrides the parent's one with the
same name, or, when unnamed, the one at the same position; otherwise it is appended.

Public functions: :func:`parse_text`, :func:`parse_file`, :func:`parse_raw` plus
:func:`build_materials` (used by the resolver to link parents across files).
Every error is an :class:`~myrabot_desc.errors.InputError` with the file:line.

The records are :mod:`myrabot_desc.records` structs (immutable) or records (mutable), not
dataclasses or NamedTuples, whose definition ``check`` would pay at every start.
"""

import math
import re
from collections.abc import Callable, Iterable
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.records import Record, Struct
from myrabot_desc.safety import limit as table_limit
from myrabot_desc.safety import read_checked

RGBA = tuple[float, float, float, float]

ENV_BYTES = "MYRABOT_DESC_MAX_MATERIAL_BYTES"
MAX_DEPTH = 32                # brace nesting; real scripts use 4 (material/technique/pass/unit)
MAX_IMPORT_DEPTH = 8

# Ogre's defaults for a pass that does not set a colour.
DEFAULTS: dict[str, object] = {
    "ambient": (1.0, 1.0, 1.0, 1.0),
    "diffuse": (1.0, 1.0, 1.0, 1.0),
    "specular": (0.0, 0.0, 0.0, 0.0),
    "emissive": (0.0, 0.0, 0.0, 0.0),
    "shininess": 0.0,
    "lighting": True,
    "depth_write": True,
}

# Top-level objects other than materials: skipped whole (their bodies are not materials).
_SKIPPED_TOP = {"vertex_program", "fragment_program", "geometry_program", "tesselation_hull_program",
                "tesselation_domain_program", "compute_program", "shared_params", "sampler",
                "compositor", "particle_system", "overlay_template", "font"}

# Patterns as text: re compiles them on first use and keeps them, so importing this module
# (check always does) does not pay ~0.6 ms of compiling for scripts most robots do not have.
_NUMBER = r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$"
_TOKEN = r'"[^"\n]*"|[{}]|[^\s{}"]+|"'


# ------------------------------------------------------------------ result types
class TextureUnit(Struct):
    name: str | None = None
    texture: str | None = None
    rotate: float = 0.0                           # degrees
    scale: tuple[float, float] = (1.0, 1.0)
    tex_coord_set: int = 0
    colour_op: str | None = None
    manual_colour: tuple[float, float, float] | None = None   # colour_op_ex source1 src_manual
    manual_alpha: float | None = None                         # alpha_op_ex source1 src_manual
    line: int | None = None


class _PassFields(Struct):
    name: str | None
    props: dict                                   # only what the script sets (see DEFAULTS)
    texture_units: tuple[TextureUnit, ...]
    line: int | None


class Pass(_PassFields):
    __slots__ = ()

    def __new__(cls, name=None, props=None, texture_units=(), line=None):
        # A new dict per pass: a NamedTuple default would be one dict shared by all.
        return _PassFields.__new__(cls, name, {} if props is None else props, texture_units, line)


class Technique(Struct):
    name: str | None = None
    passes: tuple[Pass, ...] = ()
    line: int | None = None


class _MaterialFields(Struct):
    name: str
    parent: str | None
    ambient: RGBA
    diffuse: RGBA
    specular: RGBA
    emissive: RGBA
    shininess: float
    lighting: bool
    scene_blend: str | None
    depth_write: bool
    alpha_rejection: str | None
    transparency: float            # 0 opaque .. 1 invisible (alpha_blend with a manual alpha)
    texture: str | None            # image file name as written
    texture_rotate: float
    texture_scale: tuple[float, float]
    explicit: frozenset
    techniques: tuple[Technique, ...]
    loc: Loc | None
    variables: dict                # `set $name value`, parents' included
    abstract: bool                 # `abstract material`: a template, not output


class Material(_MaterialFields):
    """One material after inheritance, plus a flat summary for SDF/MJCF.

    The summary takes, for each property, the first pass of the first technique that sets
    it (so a two-pass "ambient" + "light" material gets its ambient from the first and its
    diffuse from the second), falling back to Ogre's defaults. ``explicit`` names the
    properties some pass sets.
    """

    __slots__ = ()

    def __new__(cls, name, parent, ambient, diffuse, specular, emissive, shininess, lighting, scene_blend,
                depth_write, alpha_rejection, transparency, texture, texture_rotate, texture_scale, explicit,
                techniques, loc=None, variables=None, abstract=False):
        # A new dict per material: a NamedTuple default would be one dict shared by all.
        return _MaterialFields.__new__(
            cls, name, parent, ambient, diffuse, specular, emissive, shininess, lighting, scene_blend,
            depth_write, alpha_rejection, transparency, texture, texture_rotate, texture_scale, explicit,
            techniques, loc, {} if variables is None else variables, abstract)

    def as_dict(self) -> dict:
        return {
            "name": self.name, "parent": self.parent,
            "ambient": list(self.ambient), "diffuse": list(self.diffuse),
            "specular": list(self.specular), "emissive": list(self.emissive),
            "shininess": self.shininess, "lighting": self.lighting,
            "scene_blend": self.scene_blend, "depth_write": self.depth_write,
            "alpha_rejection": self.alpha_rejection, "transparency": self.transparency,
            "texture": self.texture, "texture_rotate": self.texture_rotate,
            "texture_scale": list(self.texture_scale),
            "passes": sum(len(t.passes) for t in self.techniques[:1]),
            "explicit": sorted(self.explicit),
            "loc": str(self.loc) if self.loc else None,
        }


class RawMaterial(Record):
    """A material as written, before its parent is applied."""

    __slots__ = ("name", "parent", "techniques", "loc", "variables", "abstract")

    def __init__(self, name: str, parent: str | None, techniques: list, loc: Loc,
                 variables: dict | None = None, abstract: bool = False):
        self.name = name
        self.parent = parent
        self.techniques = techniques          # list[Technique] (child overrides)
        self.loc = loc
        self.variables = {} if variables is None else variables   # $name -> [tokens]
        self.abstract = abstract


class Script(Record):
    __slots__ = ("path", "materials", "imports", "warnings")

    def __init__(self, path: str, materials: dict[str, Material], imports: list[str] | None = None,
                 warnings: list[str] | None = None):
        self.path = path
        self.materials = materials        # in file order
        self.imports = [] if imports is None else imports
        self.warnings = [] if warnings is None else warnings


class _Var(Struct):
    """A value written with $variables, parsed once the material's variables are known."""

    key: str
    args: tuple
    file: str
    line: int


def _has_var(args) -> bool:
    return any(a.startswith("$") for a in args)


# ------------------------------------------------------------------ tokens and blocks
class _Node:
    __slots__ = ("key", "args", "line", "children", "end_line")

    def __init__(self, key: str, args: list[str], line: int, children: list | None = None,
                 end_line: int | None = None):
        self.key = key
        self.args = args
        self.line = line
        self.children = children      # None for a plain statement
        self.end_line = end_line


_COMMENT_OR_STRING = r'(?s)"[^"\n]*"|//[^\n]*|/\*(?:.*?\*/|.*)'


def _strip_comments(text: str, file: str) -> str:
    """Blank out // and /* */ comments (not inside "strings"), keeping newlines for line numbers."""

    def repl(m: re.Match) -> str:
        s = m.group(0)
        if s[0] == '"':
            return s
        if s.startswith("/*") and not (len(s) >= 4 and s.endswith("*/")):
            line = text.count("\n", 0, m.start()) + 1
            raise InputError("'/*' comment is never closed (truncated file?)", Loc(file, line))
        return "\n" * s.count("\n")

    return re.sub(_COMMENT_OR_STRING, repl, text)


def _tokens(text: str, file: str):
    for lineno, line in enumerate(text.split("\n"), 1):
        for m in re.finditer(_TOKEN, line):
            tok = m.group(0)
            if tok == '"':
                raise InputError("unterminated string (a '\"' without its closing quote)", Loc(file, lineno))
            if len(tok) >= 2 and tok[0] == '"' and tok[-1] == '"':
                tok = tok[1:-1]
            yield tok, lineno


def _tree(text: str, file: str, max_depth: int) -> list[_Node]:
    root = _Node("<root>", [], 0, [])
    stack = [root]
    pending: _Node | None = None

    def flush():
        nonlocal pending
        if pending is not None:
            stack[-1].children.append(pending)
            pending = None

    for tok, line in _tokens(_strip_comments(text, file), file):
        if tok == "{":
            if pending is None:
                raise InputError("'{' without a block name before it", Loc(file, line))
            node, pending = pending, None
            node.children = []
            if node.key in ("material", "abstract") and len(stack) > 1:
                opener = stack[-1]
                raise InputError(
                    f"'{node.key}' inside the '{opener.key}' block opened at line {opener.line}: "
                    f"a '}}' is missing before line {line}", Loc(file, line))
            stack[-1].children.append(node)
            stack.append(node)
            if len(stack) - 1 > max_depth:
                raise InputError(f"blocks nest deeper than {max_depth} levels", Loc(file, line))
        elif tok == "}":
            flush()
            if len(stack) == 1:
                raise InputError("unexpected '}' (no block is open here)", Loc(file, line))
            stack[-1].end_line = line
            stack.pop()
        elif pending is not None and pending.line == line:
            pending.args.append(tok)
        else:
            flush()
            pending = _Node(tok, [], line)
    flush()
    if len(stack) > 1:
        node = stack[-1]
        name = " ".join([node.key] + node.args)
        last = text.count("\n") + (0 if text.endswith("\n") else 1)
        raise InputError(f"'{name}' block opened here is never closed: the file ends at line {last} "
                         f"with {len(stack) - 1} block(s) open (truncated, or a '}}' is missing)",
                         Loc(file, node.line))
    return root.children


# ------------------------------------------------------------------ values
def _num(tok: str, what: str, file: str, line: int) -> float:
    if not re.match(_NUMBER, tok):
        raise InputError(f"{what}: {tok!r} is not a number", Loc(file, line))
    v = float(tok)
    if not math.isfinite(v):
        raise InputError(f"{what}: {tok!r} is not a finite number", Loc(file, line))
    return v


def _colour(node: _Node, file: str) -> RGBA | None:
    if node.args and node.args[0] == "vertexcolour":
        return None
    if len(node.args) not in (3, 4):
        raise InputError(f"{node.key} takes 3 or 4 numbers (r g b [a]), got {len(node.args)}",
                         Loc(file, node.line))
    vals = [_num(t, node.key, file, node.line) for t in node.args]
    if len(vals) == 3:
        vals.append(1.0)
    return tuple(vals)  # type: ignore[return-value]


def _specular(node: _Node, file: str) -> tuple[RGBA | None, float | None]:
    args = node.args
    if args and args[0] == "vertexcolour":
        return None, (_num(args[1], "specular shininess", file, node.line) if len(args) > 1 else None)
    vals = [_num(t, "specular", file, node.line) for t in args]
    if len(vals) == 3:                 # lenient: Ogre wants a shininess too
        return (vals[0], vals[1], vals[2], 1.0), None
    if len(vals) == 4:                 # r g b shininess
        return (vals[0], vals[1], vals[2], 1.0), vals[3]
    if len(vals) == 5:                 # r g b a shininess
        return (vals[0], vals[1], vals[2], vals[3]), vals[4]
    raise InputError(f"specular takes r g b [a] shininess (4 or 5 numbers), got {len(vals)}",
                     Loc(file, node.line))


def _on_off(node: _Node, file: str) -> bool:
    if len(node.args) != 1 or node.args[0] not in ("on", "off", "true", "false"):
        raise InputError(f"{node.key} takes 'on' or 'off', got {' '.join(node.args) or 'nothing'!r}",
                         Loc(file, node.line))
    return node.args[0] in ("on", "true")


def _name_arg(node: _Node) -> str | None:
    return " ".join(node.args) if node.args else None


# ------------------------------------------------------------------ blocks -> objects
def _texture_unit(node: _Node, file: str) -> TextureUnit:
    kw: dict = {"name": _name_arg(node), "line": node.line}
    for c in node.children or []:
        if c.children is not None:
            continue                       # nested blocks (program refs...) are not texture data
        a = c.args
        if c.key == "texture" and a:
            kw["texture"] = a[0]
        elif c.key == "rotate" and a:
            kw["rotate"] = _num(a[0], "rotate", file, c.line)
        elif c.key == "scale":
            if len(a) != 2:
                raise InputError(f"scale takes 2 numbers (u v), got {len(a)}", Loc(file, c.line))
            kw["scale"] = (_num(a[0], "scale", file, c.line), _num(a[1], "scale", file, c.line))
        elif c.key == "tex_coord_set" and a:
            kw["tex_coord_set"] = int(_num(a[0], "tex_coord_set", file, c.line))
        elif c.key == "colour_op" and a:
            kw["colour_op"] = a[0]
        elif c.key == "colour_op_ex" and len(a) >= 6 and a[0] == "source1" and a[1] == "src_manual":
            kw["manual_colour"] = tuple(_num(t, "colour_op_ex", file, c.line) for t in a[3:6])
        elif c.key == "alpha_op_ex" and len(a) >= 4 and a[0] == "source1" and a[1] == "src_manual":
            kw["manual_alpha"] = _num(a[3], "alpha_op_ex", file, c.line)
    return TextureUnit(**kw)


def _pass(node: _Node, file: str) -> Pass:
    props: dict = {}
    units: list[TextureUnit] = []
    for c in node.children or []:
        if c.children is not None:
            if c.key == "texture_unit":
                units.append(_texture_unit(c, file))
            continue                       # vertex_program_ref { } and friends: skipped
        if c.key in ("ambient", "diffuse", "emissive", "specular") and _has_var(c.args):
            props[c.key] = _Var(c.key, tuple(c.args), file, c.line)
        elif c.key in ("ambient", "diffuse", "emissive"):
            col = _colour(c, file)
            if col is not None:
                props[c.key] = col
        elif c.key == "specular":
            col, shin = _specular(c, file)
            if col is not None:
                props["specular"] = col
            if shin is not None:
                props["shininess"] = shin
        elif c.key in ("lighting", "depth_write"):
            props[c.key] = _on_off(c, file)
        elif c.key == "scene_blend":
            if not c.args:
                raise InputError("scene_blend needs a value (e.g. alpha_blend)", Loc(file, c.line))
            props["scene_blend"] = " ".join(c.args)
        elif c.key == "alpha_rejection":
            if len(c.args) != 2:
                raise InputError("alpha_rejection takes a function and a value (e.g. greater 128)",
                                 Loc(file, c.line))
            _num(c.args[1], "alpha_rejection", file, c.line)
            props["alpha_rejection"] = " ".join(c.args)
    return Pass(name=_name_arg(node), props=props, texture_units=tuple(units), line=node.line)


def _technique(node: _Node, file: str) -> Technique:
    passes = [_pass(c, file) for c in node.children or [] if c.key == "pass" and c.children is not None]
    return Technique(name=_name_arg(node), passes=tuple(passes), line=node.line)


def _variables(node: _Node, file: str, out: dict) -> dict:
    """Every `set $name value` in a material, any depth (a simplification of Ogre's scopes)."""
    for c in node.children or []:
        if c.key == "set" and c.children is None:
            if len(c.args) < 2 or not c.args[0].startswith("$"):
                raise InputError("set takes: set $name value", Loc(file, c.line))
            out[c.args[0]] = " ".join(c.args[1:]).split()
        elif c.children is not None:
            _variables(c, file, out)
    return out


def _split_header(node: _Node, file: str) -> tuple[str, str | None]:
    toks: list[str] = []
    for t in node.args:                       # "A : B", "A: B", "A :B", "A:B"
        if t != ":" and ":" in t.strip(":") and ":" not in toks:
            a, b = t.split(":", 1)
            toks += [a, ":", b]
        elif t != ":" and t.endswith(":"):
            toks += [t[:-1], ":"]
        elif t != ":" and t.startswith(":"):
            toks += [":", t[1:]]
        else:
            toks.append(t)
    if ":" in toks:
        i = toks.index(":")
        name, parent = " ".join(toks[:i]), " ".join(toks[i + 1:])
        if not parent:
            raise InputError(f"material {name!r}: ':' without a parent name", Loc(file, node.line))
    else:
        name, parent = " ".join(toks), None
    if not name:
        raise InputError("material without a name", Loc(file, node.line))
    return name, parent


def limit(max_bytes: int | None = None) -> int:
    """The size limit for one script: ``max_bytes`` if given, else $MYRABOT_DESC_MAX_MATERIAL_BYTES, else 5 MB."""

    return max_bytes if max_bytes is not None else table_limit("max_material_bytes")


def parse_raw(text: str, file: str = "<string>", *, max_bytes: int | None = None,
              max_depth: int = MAX_DEPTH) -> tuple[list[RawMaterial], list[tuple[str, int]], list[str]]:
    """Parse one script without linking parents.

    Returns (materials, imports as (file name, line), warnings).
    """
    max_bytes = limit(max_bytes)
    if len(text) > max_bytes:
        raise InputError(f"material script is {len(text)} bytes, over the {max_bytes}-byte limit ({ENV_BYTES})",
                         Loc(file))
    mats: list[RawMaterial] = []
    imports: list[tuple[str, int]] = []
    warnings: list[str] = []
    seen: dict[str, int] = {}
    for node in _tree(text, file, max_depth):
        key, args = node.key, node.args
        abstract = key == "abstract" and bool(args) and args[0] == "material"
        if abstract:
            key, args = "material", args[1:]
            node = _Node(key, args, node.line, node.children, node.end_line)
        if key == "import":
            if node.children is not None or "from" not in args or args.index("from") + 1 >= len(args):
                raise InputError("import takes: import NAME from \"file.material\"", Loc(file, node.line))
            imports.append((args[args.index("from") + 1], node.line))
        elif key == "material":
            if node.children is None:
                raise InputError(f"'material {' '.join(args)}' has no '{{ ... }}' body",
                                 Loc(file, node.line))
            name, parent = _split_header(node, file)
            if name in seen:
                warnings.append(f"{file}:{node.line}: material {name!r} already defined at line "
                                f"{seen[name]}; the later one wins")
            seen[name] = node.line
            techs = [_technique(c, file) for c in node.children
                     if c.key == "technique" and c.children is not None]
            mats.append(RawMaterial(name, parent, techs, Loc(file, node.line),
                                    _variables(node, file, {}), abstract))
        elif key in _SKIPPED_TOP or node.children is not None:
            continue
        else:
            raise InputError(f"unexpected {key!r} outside any block (expected 'material', 'import' "
                             "or a program definition)", Loc(file, node.line))
    return mats, imports, warnings


# ------------------------------------------------------------------ inheritance
def _merge_list(base: list, over: Iterable, merge: Callable) -> list:
    """Ogre's override rule: same name, or same position when unnamed; else append."""
    out = list(base)
    for i, item in enumerate(over):
        j = None
        if item.name is not None:
            j = next((k for k, b in enumerate(out) if b.name == item.name), None)
        elif i < len(out):
            j = i
        if j is None:
            out.append(item)
        else:
            out[j] = merge(out[j], item)
    return out


def _merge_unit(a: TextureUnit, b: TextureUnit) -> TextureUnit:
    changes = {k: getattr(b, k) for k in ("texture", "colour_op", "manual_colour", "manual_alpha")
               if getattr(b, k) is not None}
    for k, default in (("rotate", 0.0), ("scale", (1.0, 1.0)), ("tex_coord_set", 0)):
        if getattr(b, k) != default:
            changes[k] = getattr(b, k)
    return a._replace(**changes)


def _merge_pass(a: Pass, b: Pass) -> Pass:
    return a._replace(props={**a.props, **b.props},
                      texture_units=tuple(_merge_list(list(a.texture_units), b.texture_units, _merge_unit)))


def _merge_technique(a: Technique, b: Technique) -> Technique:
    return a._replace(passes=tuple(_merge_list(list(a.passes), b.passes, _merge_pass)))


def _substitute(techs: tuple[Technique, ...], variables: dict, owner: str) -> tuple[Technique, ...]:
    """Replace $variables in pass values and texture names (Ogre's `set $x ...`)."""

    def expand(args, file, line):
        out = []
        for a in args:
            if a.startswith("$"):
                if a not in variables:
                    raise InputError(f"material {owner!r}: variable {a} is not set (add `set {a} ...` "
                                     "to the material or its parent)", Loc(file, line))
                out.extend(variables[a])
            else:
                out.append(a)
        return out

    def fix_pass(p: Pass) -> Pass:
        props = dict(p.props)
        for k, v in p.props.items():
            if not isinstance(v, _Var):
                continue
            node = _Node(v.key, expand(v.args, v.file, v.line), v.line)
            del props[k]
            if k == "specular":
                col, shin = _specular(node, v.file)
                if col is not None:
                    props["specular"] = col
                if shin is not None:
                    props["shininess"] = shin
            else:
                col = _colour(node, v.file)
                if col is not None:
                    props[k] = col
        units = tuple(u._replace(texture=expand([u.texture], "", u.line or 0)[0])
                      if u.texture and u.texture.startswith("$") and u.texture in variables else u
                      for u in p.texture_units)
        return p._replace(props=props, texture_units=units)

    return tuple(t._replace(passes=tuple(fix_pass(p) for p in t.passes)) for t in techs)


def summarize(name: str, parent: str | None, techniques: tuple[Technique, ...], loc: Loc | None,
              variables: dict | None = None, abstract: bool = False) -> Material:
    """Flatten techniques into the colour summary (see :class:`Material`)."""
    passes = techniques[0].passes if techniques else ()
    got: dict = {}
    for p in passes:
        for k, v in p.props.items():
            if not isinstance(v, _Var):          # unresolved only in abstract templates
                got.setdefault(k, v)
    units = [u for p in passes for u in p.texture_units]
    tex_unit = next((u for u in units if u.texture), None)
    manual_colour = next((u.manual_colour for u in units if u.manual_colour is not None), None)
    manual_alpha = next((u.manual_alpha for u in units if u.manual_alpha is not None), None)
    explicit = set(got)
    if manual_colour is not None:          # e.g. Gazebo/RedTransparent: a flat colour, no lighting terms
        for k in ("ambient", "diffuse"):
            if k not in got:
                got[k] = (*manual_colour, 1.0)
                explicit.add(k)
    vals = {**DEFAULTS, **got}
    blend = got.get("scene_blend")
    transparency = 0.0
    if blend == "alpha_blend":
        alpha = manual_alpha if manual_alpha is not None else vals["diffuse"][3]
        transparency = round(min(1.0, max(0.0, 1.0 - alpha)), 6)
    return Material(
        name=name, parent=parent,
        ambient=vals["ambient"], diffuse=vals["diffuse"], specular=vals["specular"],
        emissive=vals["emissive"], shininess=vals["shininess"], lighting=vals["lighting"],
        scene_blend=blend, depth_write=vals["depth_write"], alpha_rejection=got.get("alpha_rejection"),
        transparency=transparency,
        texture=tex_unit.texture if tex_unit else None,
        texture_rotate=tex_unit.rotate if tex_unit else 0.0,
        texture_scale=tex_unit.scale if tex_unit else (1.0, 1.0),
        explicit=frozenset(explicit), techniques=tuple(techniques), loc=loc,
        variables=dict(variables or {}), abstract=abstract)


def _did_you_mean(name: str, local, known=()) -> str:
    import difflib

    close = difflib.get_close_matches(name, sorted(set(local) | set(known)), n=2, cutoff=0.75)
    return f"; did you mean {' or '.join(map(repr, close))}?" if close else ""


def build_materials(raws: list[RawMaterial], external: "Callable[[str], Material | None] | None" = None,
                    on_error: "Callable[[InputError], None] | None" = None, known=()) -> dict[str, Material]:
    """Apply inheritance. Parents are looked up among ``raws`` first, then ``external(name)``
    (``known``: the names ``external`` knows, for did-you-mean hints).

    An unknown parent or a cycle raises InputError at the child's line, or, when ``on_error``
    is given, is passed to it and the material is left out.
    """
    by_name: dict[str, RawMaterial] = {}
    for r in raws:
        by_name[r.name] = r                # the later definition wins, as in Ogre
    done: dict[str, Material] = {}

    def build(raw: RawMaterial, chain: tuple[str, ...]) -> Material:
        if raw.name in done:
            return done[raw.name]
        base: tuple[Technique, ...] = ()
        base_vars: dict = {}
        if raw.parent is not None:
            if raw.parent in chain or raw.parent == raw.name:
                raise InputError(f"material {raw.name!r}: inheritance cycle "
                                 f"{' -> '.join(chain + (raw.name, raw.parent))}", raw.loc)
            if raw.parent in by_name:
                pm = build(by_name[raw.parent], chain + (raw.name,))
                base, base_vars = pm.techniques, pm.variables
            else:
                ext = external(raw.parent) if external else None
                if ext is None:
                    raise InputError(f"material {raw.name!r}: parent {raw.parent!r} is not defined "
                                     "(not in this script, its imports, or Gazebo's stock materials)"
                                     + _did_you_mean(raw.parent, by_name, known), raw.loc)
                base, base_vars = ext.techniques, ext.variables
        techs = tuple(_merge_list(list(base), raw.techniques, _merge_technique))
        variables = {**base_vars, **raw.variables}
        if not raw.abstract:
            techs = _substitute(techs, variables, raw.name)
        mat = summarize(raw.name, raw.parent, techs, raw.loc, variables, raw.abstract)
        done[raw.name] = mat
        return mat

    out: dict[str, Material] = {}
    for r in raws:
        if by_name[r.name] is not r or r.abstract:
            continue
        try:
            out[r.name] = build(r, ())
        except InputError as exc:
            if on_error is None:
                raise
            on_error(exc)
    return out


# ------------------------------------------------------------------ entry points
def parse_text(text: str, file: str = "<string>", *, parents: "Callable[[str], Material | None] | None" = None,
               known=(), max_bytes: int | None = None, max_depth: int = MAX_DEPTH) -> Script:
    """Parse a script held in memory. Imports are not followed (see :func:`parse_file`).

    ``parents`` finds parents defined elsewhere (``materials.scripts`` passes Gazebo's stock
    materials); ``known`` names them for did-you-mean hints.
    """
    raws, imports, warnings = parse_raw(text, file, max_bytes=max_bytes, max_depth=max_depth)
    mats = build_materials(raws, parents, known=known)
    return Script(file, mats, [i for i, _ in imports], warnings)


def read_script_text(path: Path, file: str, max_bytes: int | None = None) -> str:
    max_bytes = limit(max_bytes)
    try:
        size = path.stat().st_size
        if size > max_bytes:
            raise InputError(f"material script is {size} bytes, over the {max_bytes}-byte limit ({ENV_BYTES})",
                             Loc(file))

        data = read_checked(path, None, max_bytes)     # regular files only: a FIFO would block
    except InputError as exc:
        raise InputError(exc.message, Loc(file), code=exc.code) from None
    except IsADirectoryError:
        raise InputError("is a folder, not a .material file", Loc(file)) from None
    except FileNotFoundError:
        raise InputError("no such file", Loc(file)) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror}", Loc(file)) from None
    if b"\0" in data:  # UTF-16/32 or binary: nothing an OGRE script holds
        raise InputError("not a material script (binary data: NUL bytes)",
                         Loc(file, data[:data.index(b"\0")].count(b"\n") + 1))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")     # old scripts (Spanish comments) are often Latin-1


def parse_file(path: str | Path, *, parents: "Callable[[str], Material | None] | None" = None,
               known=(), max_bytes: int | None = None, max_depth: int = MAX_DEPTH) -> Script:
    """Parse a .material file, following ``import ... from "x.material"`` next to it.

    Imported materials serve as parents only; ``Script.materials`` holds this file's own.
    A missing import is a warning (Ogre logs it and goes on); an unknown parent is an error.
    """
    path = Path(path)
    file = str(path)
    text = read_script_text(path, file, max_bytes)
    raws, imports, warnings = parse_raw(text, file, max_bytes=max_bytes, max_depth=max_depth)
    imported: list[RawMaterial] = []
    seen = {path.resolve()}
    top = path.resolve().parent

    def follow(items, base: Path, depth: int):
        for name, line in items:
            target = (base / name).resolve()
            if target in seen:
                continue
            if not target.is_relative_to(top):  # ../../etc/passwd, /abs, a symlink out: never read
                raise InputError(f"import {name!r} lies outside the script's folder: refusing to read it",
                                 Loc(file, line))
            seen.add(target)
            if depth > MAX_IMPORT_DEPTH:
                raise InputError(f"imports nest deeper than {MAX_IMPORT_DEPTH} files", Loc(file, line))
            if not target.is_file():
                warnings.append(f"{file}:{line}: imported script {name!r} not found next to it; ignored")
                continue
            sub_file = str(target)
            sub_raws, sub_imports, sub_warn = parse_raw(read_script_text(target, sub_file, max_bytes),
                                                        sub_file, max_bytes=max_bytes, max_depth=max_depth)
            imported.extend(sub_raws)
            warnings.extend(sub_warn)
            follow(sub_imports, target.parent, depth + 1)

    follow(imports, path.parent, 1)
    pool = {r.name: r for r in imported}
    built_imports: dict[str, Material] = {}

    def external(name: str) -> Material | None:
        if name in pool:
            if name not in built_imports:
                built_imports.update(build_materials(list(pool.values()), parents, known=known))
            return built_imports.get(name)
        return parents(name) if parents else None

    mats = build_materials(raws, external, known=set(known) | set(pool))
    return Script(file, mats, [i for i, _ in imports], warnings)
