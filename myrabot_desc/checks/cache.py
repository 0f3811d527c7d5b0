"""The result cache of ``check``: what makes a pre-commit run cheap, and what a pull request
must not be able to plant.

Where: the user's cache folder (``$XDG_CACHE_HOME/myrabot-desc/check``, else
``~/.cache/myrabot-desc/check``), or ``MYRABOT_DESC_CACHE_DIR`` / ``--cache-dir DIR`` (the person
running the check chooses a folder, a repository-local one included). A project opts in with a
configuration file (``cache = false`` opts out); ``--no-cache`` skips it.

What an entry is worth: nothing on its own. Each entry is JSON (never pickle) and is believed only
when all of this holds:

* it is a regular file inside the cache folder, read through the path gate (safety.read_checked:
  no FIFO, device or symlink out, bounded);
* its HMAC-SHA256 verifies with this user's secret, a random key kept in the user's cache folder
  (mode 0600), never in a repository: an entry written by anyone else, or edited, is foreign;
* the entry's name and its recorded key are the hash of everything the result depends on that is
  known before the check: the tool's version and the hash of its own code (an editable install
  changes without a version bump), the libraries' versions, the input's path and *content*, the
  configuration file's content, the options, the limits, the working folder, the environment
  variables packages and limits come from;
* every file the check read (recorded as it ran: model sources, includes, YAML, meshes, material
  scripts, textures, package.xml files, and the mesh files the model names, read or not) still has
  the content hash recorded, and a file recorded as missing is still missing; the file names under
  the model's folder and package roots are the same (a new package.xml or mesh changes what
  resolves); every ``$(env)``/``$(optenv)`` variable the build read has the same value (compared
  by keyed hash: values are never written to the cache);
* the result is well formed: known severities, codes, strings and numbers only.

Anything else (corrupt, foreign, stale, unknown severity) is ignored and rebuilt. Cached messages
are model text like any other: the reports print them through the sanitiser.

Writing never follows a symlink: the cache folders are opened with O_NOFOLLOW, each entry is
written to a new temporary file in the folder (O_EXCL | O_NOFOLLOW) and renamed over the entry by
folder descriptor, and ``.gitignore`` is only ever created, never written through.

hashlib, hmac and json are imported in the functions that use them: a check without the cache
(``--no-cache``, no configuration) does not load OpenSSL or json.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from myrabot_desc import __version__
from myrabot_desc.checks.report import FileResult, _plain
from myrabot_desc.diagnostics import SEVERITIES, Diagnostic, Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import bundled_path
from myrabot_desc.safety import LIMITS, SKIP_DIRS, read_checked

ENTRY_FORMAT = 2
MAX_TREE_FILES = 20_000          # a folder bigger than this (a home folder) is not watched: no caching
MAX_ENTRY_BYTES = 20_000_000
MAX_DEP_BYTES = 200_000_000      # a file the check read that is bigger than this: no caching
MAX_DEPS = 20_000
ENV_KEYS = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")
APP = "myrabot-desc"
SECRET_BYTES = 32
_CODE = re.compile(r"^[A-Z][0-9]{3}$")

_trees: dict[str, str | None] = {}     # folder -> listing signature, once per process (one command run)
_hashes: dict[str, str | None] = {}    # file -> content hash, once per process
_fingerprint: list = []


def reset() -> None:
    _trees.clear()
    _hashes.clear()


# ------------------------------------------------------------------ where
def user_cache_root() -> Path | None:
    """``$XDG_CACHE_HOME/myrabot-desc`` (an absolute XDG_CACHE_HOME only, as the spec says), else
    ``~/.cache/myrabot-desc``; None when there is no home folder."""
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    if xdg and os.path.isabs(xdg):
        return Path(xdg) / APP
    try:
        home = Path.home()
    except (RuntimeError, KeyError, OSError):
        return None
    return home / ".cache" / APP


def default_dir() -> str | None:
    root = user_cache_root()
    return str(root) if root is not None else None


def _open_folder(path: Path, create: bool, parent_fd: int | None = None) -> int | None:
    """A descriptor of folder ``path`` (relative to ``parent_fd`` when given), opened without
    following a symlink at its last component; created (mode 0700) when missing and ``create``."""
    flags = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | getattr(os, "O_CLOEXEC", 0)
    name = str(path)
    for attempt in (0, 1):
        try:
            return os.open(name, flags, dir_fd=parent_fd)
        except FileNotFoundError:
            if not create or attempt:
                return None
            try:
                if parent_fd is None:
                    Path(name).parent.mkdir(parents=True, exist_ok=True)
                os.mkdir(name, 0o700, dir_fd=parent_fd)
            except FileExistsError:
                pass
            except OSError:
                return None
        except OSError:          # a symlink (ELOOP), a file (ENOTDIR), no permission
            return None
    return None


# ------------------------------------------------------------------ the user's secret
_secret_cache: dict[str, bytes | None] = {}


def secret() -> bytes | None:
    """This user's cache key: SECRET_BYTES random bytes in ``<user cache root>/secret`` (created on
    first use, mode 0600, never through a symlink); None when it cannot be had (then no cache)."""
    root = user_cache_root()
    if root is None:
        return None
    key = str(root)
    if key in _secret_cache:
        return _secret_cache[key]
    value = None
    fd = _open_folder(root, create=True)
    if fd is not None:
        try:
            value = _read_secret(fd)
            if value is None:
                try:
                    w = os.open("secret", os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600, dir_fd=fd)
                    try:
                        os.write(w, os.urandom(SECRET_BYTES))
                    finally:
                        os.close(w)
                except OSError:
                    pass
                value = _read_secret(fd)          # ours, or another process's written first
        finally:
            os.close(fd)
    _secret_cache[key] = value
    return value


def _read_secret(folder_fd: int) -> bytes | None:
    import stat

    try:
        fd = os.open("secret", os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=folder_fd)
    except OSError:
        return None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_size != SECRET_BYTES or st.st_uid != os.getuid() \
                or st.st_mode & 0o077:
            return None
        data = os.read(fd, SECRET_BYTES + 1)
        return data if len(data) == SECRET_BYTES else None
    finally:
        os.close(fd)


# ------------------------------------------------------------------ what the result depends on
def code_fingerprint(pkg: Path | None = None) -> str:
    """The tool's own code (every module of the package ``pkg``, by content), its version, Python's
    and the libraries' versions: a result from other code is never reused."""
    import hashlib
    if pkg is None and _fingerprint:
        return _fingerprint[0]
    from importlib import metadata

    h = hashlib.sha256(f"{__version__}\0{sys.version}\0".encode())
    default = pkg is None
    pkg = Path(__file__).resolve().parent.parent if pkg is None else Path(pkg)
    for f in sorted(pkg.rglob("*.py")):
        try:
            h.update(f.relative_to(pkg).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
        except OSError:
            h.update(b"?")
    for dist in ("xacro", "lxml", "numpy", "trimesh", "pin", "pycollada", "PyYAML", "pillow"):
        try:
            h.update(f"{dist}={metadata.version(dist)}\0".encode())
        except Exception:  # not installed (or no metadata): part of the fingerprint as such
            h.update(f"{dist}=-\0".encode())
    if not default:
        return h.hexdigest()
    _fingerprint.append(h.hexdigest())
    return _fingerprint[0]


def file_hash(path: str) -> str | None:
    """sha256 of a regular file's content; None when it does not exist (or is not a regular
    file); raises OSError when it is too big or unreadable (the result is then not cached)."""
    import hashlib
    if path in _hashes:
        return _hashes[path]
    try:
        data = read_checked(path, None, MAX_DEP_BYTES)
        value = hashlib.sha256(data).hexdigest()
    except InputError as exc:
        if "no such" in exc.message or exc.code == "X006":
            value = None
        else:
            raise OSError(exc.message) from None
    _hashes[path] = value
    return value


def _tree_signature(root: str) -> str | None:
    """Hash of the relative path of every file under ``root`` (what may resolve there); None when
    too big."""
    import hashlib
    if root in _trees:
        return _trees[root]
    h = hashlib.sha256()
    n = 0
    for folder, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("."))
        for name in sorted(names):
            n += 1
            if n > MAX_TREE_FILES:
                _trees[root] = None
                return None
            h.update(os.path.relpath(os.path.join(folder, name), root).encode("utf-8", "surrogateescape") + b"\n")
    sig = h.hexdigest()
    _trees[root] = sig
    return sig


class Recorder:
    """The files a check opens for reading while it runs (a Python audit hook: every reader of a
    model-named file opens it through Python), less the interpreter's and the libraries' own."""

    active: "Recorder | None" = None
    _installed = False

    def __init__(self):
        self.paths: set[str] = set()

    def __enter__(self):
        if not Recorder._installed:
            sys.addaudithook(_audit)
            Recorder._installed = True
        Recorder.active = self
        return self

    def __exit__(self, *exc):
        Recorder.active = None
        return False


_SKIP_PREFIXES: list = []


def _skip_prefixes() -> tuple:
    if not _SKIP_PREFIXES:
        import sysconfig

        out = {sys.prefix, sys.base_prefix, sys.exec_prefix, "/proc", "/dev", "/sys", "/usr/lib", "/usr/share",
               "/etc"}
        for key in ("stdlib", "platstdlib", "purelib", "platlib"):
            try:
                out.add(sysconfig.get_path(key))
            except KeyError:
                pass
        _SKIP_PREFIXES.append(tuple(sorted(p.rstrip("/") + "/" for p in out if p)))
    return _SKIP_PREFIXES[0]


def _audit(event, args):
    rec = Recorder.active
    if rec is None or event != "open":
        return
    path, mode, flags = args[0], args[1], args[2]
    if isinstance(path, int):
        return
    if (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
            (isinstance(flags, int) and flags & (os.O_WRONLY | os.O_RDWR | os.O_CREAT)):
        return
    p = os.fsdecode(path) if isinstance(path, bytes) else str(path)
    if p.endswith((".py", ".pyc", ".so")):
        return
    p = os.path.abspath(p)
    if not p.startswith(_skip_prefixes()):
        rec.paths.add(p)


def _model_files(robot) -> set[str]:
    """The files the model names (mesh geometry, textures) and its sources: a later reader of a
    mesh cached in this process does not open it again, so these are always dependencies."""
    out = set()
    for f in robot.source_files():
        if f:
            out.add(os.path.abspath(f))
    if robot.source:
        out.add(os.path.abspath(robot.source))
    for link in robot.links.values():
        for part in list(link.visuals) + list(link.collisions):
            g = part.geometry
            p = getattr(g, "path", None)
            if p is not None:
                out.add(os.path.abspath(p))
    return out


def _env_digest(names, key: bytes) -> dict:
    """name -> keyed hash of its value (None when unset): compared, never revealed."""
    import hmac
    out = {}
    for name in sorted(names):
        v = os.environ.get(name)
        out[name] = None if v is None else hmac.new(key, f"{name}={v}".encode("utf-8", "surrogateescape"),
                                                   "sha256").hexdigest()
    return out


# ------------------------------------------------------------------ the key
def task_key(task) -> str | None:
    """The hash of everything known before the check (see the module docstring); None when the
    input or the configuration cannot be hashed (then no cache)."""
    import hashlib
    import json
    opts = task.options
    src = str(Path(task.path).resolve()) if task.path else str(bundled_path())
    try:
        content = file_hash(src)
        config = file_hash(str(task.config)) if getattr(task, "config", None) else None
    except OSError:
        return None
    env = {k: os.environ.get(k) for k in ENV_KEYS + tuple(lim.env for lim in LIMITS)}
    material = {"format": ENTRY_FORMAT, "code": code_fingerprint(), "cwd": os.getcwd(), "file": src,
                "content": content, "config": config,
                "build": {k: (sorted(v.items()) if isinstance(v, dict) else v) for k, v in sorted(task.build.items())},
                "options": [opts.inertia, opts.suggest, opts.meshes, _file_key(getattr(opts, "srdf", None))],
                "select": list(task.select),
                "ignore": list(task.ignore), "limits": list(task.limits), "env": env}
    return hashlib.sha256(json.dumps(material, sort_keys=True, default=str).encode("utf-8", "surrogateescape")
                          ).hexdigest()


def _file_key(path) -> list | None:
    """An extra input file (--srdf) by its content: its edit changes the key."""
    if not path:
        return None
    try:
        return [str(Path(path).resolve()), file_hash(str(path))]
    except OSError:
        return [str(path)]


def _roots(task, robot) -> list[str]:
    src = Path(task.path) if task.path else bundled_path()
    roots = {str(src.resolve().parent)}
    roots.update(str(Path(p).resolve()) for p in robot.package_roots.values())
    roots.update(str(Path(p).resolve()) for p in task.build.get("allow_paths", ()))
    # a folder inside another is covered by the outer walk
    return sorted(r for r in roots if not any(r != o and r.startswith(o.rstrip(os.sep) + os.sep) for o in roots))


def _mac(key: bytes, entry: dict) -> str:
    import hmac
    import json
    body = json.dumps({k: v for k, v in entry.items() if k != "mac"}, sort_keys=True, ensure_ascii=True)
    return hmac.new(key, body.encode("ascii"), "sha256").hexdigest()


# ------------------------------------------------------------------ lookup and store
def lookup(task):
    """The cached FileResult of ``task``, or None (no entry, foreign, corrupt or stale)."""
    import hmac
    import json
    key = secret()
    name = task_key(task)
    if key is None or name is None or not task.cache_dir:
        return None
    folder = _entries_folder(task.cache_dir, create=False)
    if folder is None:
        return None
    try:
        data = read_checked(folder / f"{name}.json", [folder], MAX_ENTRY_BYTES)
        entry = json.loads(data.decode("utf-8"))
        if not isinstance(entry, dict) or entry.get("format") != ENTRY_FORMAT or entry.get("key") != name:
            return None
        if not isinstance(entry.get("mac"), str) or not hmac.compare_digest(entry["mac"], _mac(key, entry)):
            return None                      # foreign or edited: never believed
        if entry["env"] != _env_digest(entry["env"], key):
            return None
        for root, sig in entry["trees"].items():
            if _tree_signature(root) != sig:
                return None
        for path, digest in entry["deps"].items():
            if file_hash(path) != digest:
                return None
        return _result(entry["result"], task)
    except (InputError, OSError, ValueError, KeyError, TypeError, AttributeError, RecursionError):
        return None


def store(task, robot, res, read: set) -> None:
    """Write the entry for ``res`` (best effort: no secret, a folder that is a symlink or read-only,
    a dependency too big: no entry)."""
    import json
    key = secret()
    name = task_key(task)
    if key is None or name is None or not task.cache_dir:
        return
    trees = {}
    for root in _roots(task, robot):
        sig = _tree_signature(root)
        if sig is None:
            return
        trees[root] = sig
    paths = set(read) | _model_files(robot)
    if getattr(task, "config", None):
        paths.add(os.path.abspath(task.config))
    if len(paths) > MAX_DEPS:
        return
    try:
        deps = {p: file_hash(p) for p in sorted(paths)}
    except OSError:
        return
    env = set()
    for d in robot.build_warnings:
        if d.code == "X007":
            env = set(d.data.get("environment", {}))
    entry = {"format": ENTRY_FORMAT, "key": name, "trees": trees, "deps": deps, "env": _env_digest(env, key),
             "result": _plain_result(res)}
    entry["mac"] = _mac(key, entry)
    _write_entry(task.cache_dir, f"{name}.json", json.dumps(entry, ensure_ascii=True).encode("ascii"))


def _entries_folder(cache_dir, create: bool) -> Path | None:
    """``<cache_dir>/check`` when it and ``cache_dir`` are real folders (not symlinks)."""
    top = _open_folder(Path(cache_dir), create)
    if top is None:
        return None
    try:
        sub = _open_folder(Path("check"), create, parent_fd=top)
        if sub is None:
            return None
        os.close(sub)
        if create:
            _gitignore(top)
    finally:
        os.close(top)
    return Path(cache_dir) / "check"


def _gitignore(top_fd: int) -> None:
    """A ``.gitignore`` saying ``*`` in the cache folder, created only when no such name exists (a
    file, or a symlink, dangling or not, is left alone)."""
    try:
        fd = os.open(".gitignore", os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o644, dir_fd=top_fd)
    except OSError:
        return
    try:
        os.write(fd, b"# created by myrabot-desc check\n*\n")
    finally:
        os.close(fd)


def _write_entry(cache_dir, name: str, data: bytes) -> None:
    if _entries_folder(cache_dir, create=True) is None:
        return
    top = _open_folder(Path(cache_dir), False)
    if top is None:
        return
    sub = _open_folder(Path("check"), False, parent_fd=top)
    os.close(top)
    if sub is None:
        return
    tmp = f".{name}.{os.getpid()}.{os.urandom(6).hex()}.tmp"
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | getattr(os, "O_CLOEXEC", 0),
                     0o600, dir_fd=sub)
        try:
            os.write(fd, data)
        finally:
            os.close(fd)
        os.replace(tmp, name, src_dir_fd=sub, dst_dir_fd=sub)    # replaces a link itself, never its target
    except OSError:
        try:
            os.unlink(tmp, dir_fd=sub)
        except OSError:
            pass
    finally:
        os.close(sub)


# ------------------------------------------------------------------ results as JSON
def _plain_result(res) -> dict:
    return {"robot": res.robot, "links": res.links, "joints": res.joints,
            "suggestions": [list(s) for s in res.suggestions],
            "seen": [list(k) for k in res.suppressions_seen], "used": [list(k) for k in res.suppressions_used],
            "suppressed": [[d.code, d.severity, d.message, d.loc.file if d.loc else None,
                            d.loc.line if d.loc else None, _plain(d.data), list(k)] for d, k in res.suppressed],
            "diagnostics": [[d.code, d.severity, d.message, d.loc.file if d.loc else None,
                             d.loc.line if d.loc else None, _plain(d.data)] for d in res.diagnostics]}


def _str(x, none: bool = False) -> str | None:
    if (none and x is None) or isinstance(x, str):
        return x
    raise TypeError("not a string")


def _int(x, none: bool = False) -> int | None:
    if (none and x is None) or (isinstance(x, int) and not isinstance(x, bool) and x >= 0):
        return x
    raise TypeError("not a count")


def _key3(k) -> tuple:
    if not isinstance(k, list) or len(k) != 3:
        raise TypeError("not a suppression key")
    return (_str(k[0]), _int(k[1]), _str(k[2]))


def _diagnostic(c, s, m, f, ln, data) -> Diagnostic:
    if not isinstance(c, str) or not _CODE.match(c) or s not in SEVERITIES or not isinstance(data, dict):
        raise ValueError("not a finding")
    return Diagnostic(c, s, _str(m), Loc(_str(f), _int(ln, True)) if f is not None else None, dict(data))


def _result(e: dict, task):
    """A FileResult from a verified entry, every field checked for its type (ValueError/TypeError
    otherwise: the entry is then ignored)."""
    res = FileResult(file=task.path or "", strict=task.strict, robot=_str(e["robot"], True),
                     links=_int(e["links"]), joints=_int(e["joints"]),
                     suggestions=[(_str(a), _str(b)) for a, b in e["suggestions"]])
    res.suppressions_seen = [_key3(k) for k in e["seen"]]
    res.suppressions_used = [_key3(k) for k in e["used"]]
    res.diagnostics = [_diagnostic(*d) for d in e["diagnostics"]]
    res.suppressed = [(_diagnostic(*d[:6]), _key3(d[6])) for d in e.get("suppressed", ())]
    return res
