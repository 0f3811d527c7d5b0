"""Material-name resolution shared by ``check`` and ``convert``.

A URDF ``<gazebo reference="link"><material>brazo_fer/White</material>`` names an OGRE material
that Gazebo classic found in a script on its media path. gz-sim and MuJoCo cannot read scripts,
so we resolve the name here and emit explicit colours.

Usage::

    from myrabot_desc.materials.resolve import resolver_for
    res = resolver_for(robot)              # or MaterialResolver([Path("pkg_dir"), ...])
    m = res.lookup("Gazebo/Grey")          # ResolvedMaterial | None
    m.diffuse, m.source                    # (0.7, 0.7, 0.7, 1.0), 'stock'
    res.errors                             # scripts that could not be read (InputError each)
    res.similar("material_fer/CocaCola")   # ['Gazebo/CocaCola']: hints for an unresolved name
    stock.gz_sim_values("Gazebo/Grey")     # what gz-sim's substring lookup would show instead

Scripts are searched, for each search dir D, in ``D``, ``D/materials/scripts``, ``D/materials``,
``D/Media/materials/scripts`` and ``D/media/materials/scripts`` (ROS 1 ``gazebo_media_path``
convention; the MYRAbot packages use ``Media/`` in fuerte and ``media/`` later). They are read on
the first lookup. Script materials win over Gazebo's stock table; among scripts the first file
(search-dir order, then file name) wins. Parents may live in any loaded script or in the stock table.
"""

from pathlib import Path

from myrabot_desc.errors import InputError
from myrabot_desc.materials import ogre
from myrabot_desc.materials.stock import names as stock_names
from myrabot_desc.materials.stock import is_stock, stock_material
from myrabot_desc.records import Struct

RGBA = tuple[float, float, float, float]

SCRIPT_SUBDIRS = ("", "materials/scripts", "materials", "Media/materials/scripts", "media/materials/scripts")
MAX_SCRIPTS = 2000          # a search dir that is someone's whole disk should not hang `check`


class ResolvedMaterial(Struct):
    """Explicit values for one material name."""

    name: str
    ambient: RGBA
    diffuse: RGBA
    specular: RGBA
    emissive: RGBA
    shininess: float
    lighting: bool
    transparency: float            # put on the visual (<transparency>); 0 when opaque
    texture: str | None            # image name as written in the script
    texture_path: Path | None      # the image file, when found next to the script
    source: str                    # 'stock' or 'path/to/file.material:LINE'
    material: ogre.Material        # the full parsed material (techniques, passes...)

    @property
    def is_stock(self) -> bool:
        return self.source == "stock"


def find_texture(script: Path, texture: str) -> Path | None:
    """The image for ``texture`` used by ``script``: ../textures, ./textures, or next to it."""
    d = script.parent
    top = d.parent.resolve()    # the materials/ folder: scripts/ and textures/ (never ../../etc/passwd)
    for cand in (d.parent / "textures" / texture, d / "textures" / texture, d / texture):
        if cand.is_file() and cand.resolve().is_relative_to(top):
            return cand
    return None


def resolved(mat: ogre.Material, texture_path: Path | None = None) -> ResolvedMaterial:
    return ResolvedMaterial(
        name=mat.name, ambient=mat.ambient, diffuse=mat.diffuse, specular=mat.specular,
        emissive=mat.emissive, shininess=mat.shininess, lighting=mat.lighting,
        transparency=mat.transparency, texture=mat.texture, texture_path=texture_path,
        source=str(mat.loc) if mat.loc else "stock", material=mat)


class MaterialResolver:
    """Finds material names in the scripts under ``search_dirs`` and in Gazebo's stock table."""

    def __init__(self, search_dirs: list[Path], *, max_bytes: int | None = None):
        self.search_dirs = [Path(d) for d in search_dirs]
        self.max_bytes = max_bytes
        self.errors: list[InputError] = []       # unreadable scripts, unknown parents
        self.warnings: list[str] = []            # duplicates, missing imports...
        self.scripts: list[Path] = []            # every script read, in load order
        self._materials: dict[str, ogre.Material] | None = None

    # ---------------------------------------------------------------- loading
    def script_files(self) -> list[Path]:
        seen: set[Path] = set()
        out: list[Path] = []
        for d in self.search_dirs:
            for sub in SCRIPT_SUBDIRS:
                folder = d / sub
                if not folder.is_dir():
                    continue
                top = folder.resolve()
                for f in sorted(folder.glob("*.material")):
                    key = f.resolve()
                    if not key.is_relative_to(top):   # a symlink out of the folder: not a material script
                        continue
                    if key not in seen and f.is_file():
                        seen.add(key)
                        out.append(f)
                        if len(out) >= MAX_SCRIPTS:
                            self.warnings.append(f"more than {MAX_SCRIPTS} material scripts under the "
                                                 f"search dirs; read the first {MAX_SCRIPTS} only")
                            return out
        return out

    def _load(self) -> dict[str, ogre.Material]:
        if self._materials is not None:
            return self._materials
        raws: list[ogre.RawMaterial] = []
        first_def: dict[str, str] = {}
        for f in self.script_files():
            try:
                text = ogre.read_script_text(f, str(f), self.max_bytes)
                mats, _imports, warns = ogre.parse_raw(text, str(f), max_bytes=self.max_bytes)
            except InputError as exc:
                self.errors.append(exc)
                continue
            self.scripts.append(f)
            self.warnings.extend(warns)
            for m in mats:
                if m.name in first_def and first_def[m.name] != str(m.loc):
                    self.warnings.append(f"{m.loc}: material {m.name!r} also defined at "
                                         f"{first_def[m.name]}; using the first")
                    continue
                first_def.setdefault(m.name, str(m.loc))
                raws.append(m)
        # Imports are implied: every script on the media path is loaded, as Gazebo does.
        self._materials = ogre.build_materials(raws, stock_material, on_error=self.errors.append,
                                               known=stock_names())
        return self._materials

    # ---------------------------------------------------------------- queries
    def material(self, name: str) -> ogre.Material | None:
        """The parsed material ``name`` from the scripts, else from the stock table, else None."""
        return self._load().get(name) or stock_material(name)

    def defines(self, name: str) -> bool:
        """Whether a script or the stock table has ``name``: lookup's test without its values and
        texture files."""
        return name in self._load() or is_stock(name)

    def lookup(self, name: str) -> ResolvedMaterial | None:
        """Explicit values for ``name``, or None when no script nor the stock table has it."""
        mat = self._load().get(name)
        if mat is not None:
            tex = None
            if mat.texture and mat.loc:
                tex = find_texture(Path(mat.loc.file), mat.texture)
            return resolved(mat, tex)
        stock = stock_material(name)
        return resolved(stock) if stock is not None else None

    def names(self, include_stock: bool = False) -> list[str]:
        """Names defined by the loaded scripts (plus the stock table if asked), sorted."""
        found = set(self._load())
        if include_stock:
            found.update(stock_names())
        return sorted(found)


    def similar(self, name: str, n: int = 2) -> list[str]:
        """Likely intended names for an unresolved ``name``: same last part first
        (``material_fer/CocaCola`` -> ``Gazebo/CocaCola``), then close spellings."""
        import difflib

        pool = self.names(include_stock=True)
        tail = name.rsplit("/", 1)[-1].lower()
        same_tail = [c for c in pool if c != name and c.rsplit("/", 1)[-1].lower() == tail]
        close = difflib.get_close_matches(name, pool, n=n + len(same_tail), cutoff=0.75)
        out = same_tail + [c for c in close if c not in same_tail and c != name]
        return out[:n]


def _package_root_of(d: Path) -> bool:
    return (d / "package.xml").is_file() or (d / "manifest.xml").is_file()


def search_dirs_for(robot) -> list[Path]:
    """Package roots the build resolved, then the model's folder and its parents up to its package.

    Without a package root (package.xml / manifest.xml, or a resolved root) above the model
    within 8 levels, only the model's own folder is searched: we read files under the input's
    folder and the resolved package roots, never elsewhere.
    """
    dirs: list[Path] = []

    def add(p: Path):
        p = Path(p)
        if p not in dirs:
            dirs.append(p)

    roots = {Path(p).resolve() for p in (robot.package_roots or {}).values()}
    for p in sorted((robot.package_roots or {}).items()):
        add(Path(p[1]))
    src = getattr(robot, "source", None)
    if src is not None:
        d = Path(src).resolve().parent
        chain = [d]
        while len(chain) < 8 and not (chain[-1] in roots or _package_root_of(chain[-1])) \
                and chain[-1].parent != chain[-1]:
            chain.append(chain[-1].parent)
        if not (chain[-1] in roots or _package_root_of(chain[-1])):
            chain = chain[:1]                # no package above: the model's folder only
        for c in chain:
            add(c)
    return dirs


def resolver_for(robot) -> MaterialResolver:
    """A resolver for a loaded Robot (see :func:`search_dirs_for`)."""
    return MaterialResolver(search_dirs_for(robot))
