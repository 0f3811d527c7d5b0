"""What a pull request can plant for ``check``: cache entries and repository configuration.

Each test builds its repository at test time and runs the real command line (limited.run: CPU time
and peak memory from the kernel, a timeout for a run that would block). Before this round a
planted entry reporting a negative mass as clean turned CI green, a symlink to /dev/zero was read
for gigabytes, a FIFO blocked, a symlinked cache folder or a dangling .gitignore made check write
outside the project; a configuration could raise limits, open any folder, and take minutes with
tens of thousands of globs.
"""

from __future__ import annotations

import hashlib
import json
import os
import random
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from limited import run, within_budget, write  # noqa: E402

NEG = """<robot name="neg">
  <link name="base"><inertial><mass value="-1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""
CLEAN = {"robot": "neg", "links": 1, "joints": 0, "suggestions": [], "seen": [], "used": [], "diagnostics": []}


@pytest.fixture
def repo(tmp_path):
    """A repository with a configuration (the project opts into the cache) and a model whose mass is
    negative (check: I003, exit 1); the user's cache folder in tmp_path/xdg."""
    r = tmp_path / "repo"
    write(r / "pyproject.toml", "[tool.myrabot-desc]\n")
    (r / ".git").mkdir()
    write(r / "neg.urdf", NEG)
    return r


def env(tmp_path):
    return {"XDG_CACHE_HOME": str(tmp_path / "xdg"), "MYRABOT_DESC_CACHE_DIR": ""}


def check(tmp_path, repo, *extra):
    r = run(["check", "neg.urdf", *extra], cwd=repo, env=env(tmp_path), timeout=60)
    assert not within_budget(r), within_budget(r)
    return r


def entry_of(folder: Path) -> Path:
    entries = list((folder / "check").glob("*.json"))
    assert len(entries) == 1, entries
    return entries[0]


def sign(tmp_path, entry: dict) -> dict:
    """Sign an entry as the real user would (the test is the user: it can read the secret)."""
    import hmac

    key = (tmp_path / "xdg" / "myrabot-desc" / "secret").read_bytes()
    body = json.dumps({k: v for k, v in entry.items() if k != "mac"}, sort_keys=True, ensure_ascii=True)
    entry["mac"] = hmac.new(key, body.encode("ascii"), "sha256").hexdigest()
    return entry


# ------------------------------------------------------------------ the cache
def test_entries_live_in_the_user_cache_folder_signed_by_a_secret_outside_the_repository(tmp_path, repo):
    first = check(tmp_path, repo)
    assert first.code == 1 and "I003" in first.stdout
    user = tmp_path / "xdg" / "myrabot-desc"
    assert entry_of(user).stat().st_mode & 0o077 == 0
    secret = user / "secret"
    assert secret.stat().st_size == 32 and secret.stat().st_mode & 0o777 == 0o600
    assert not [p for p in repo.rglob("*") if "cache" in p.name]          # nothing in the repository
    second = check(tmp_path, repo)
    assert second.stdout == first.stdout and second.code == 1


def test_a_forged_entry_reporting_a_negative_mass_clean_is_not_believed(tmp_path, repo):
    """A pull request commits a repository-local cache (the runner uses --cache-dir) whose entry has
    the right name and says the model is clean: the HMAC fails, the model is checked."""
    local = repo / ".myrabot-desc-cache"
    check(tmp_path, repo, "--cache-dir", local)
    p = entry_of(local)
    entry = json.loads(p.read_text())
    entry["result"] = CLEAN
    p.write_text(json.dumps(entry))                                        # the old MAC no longer fits
    r = check(tmp_path, repo, "--cache-dir", local)
    assert r.code == 1 and "I003" in r.stdout
    entry["mac"] = hashlib.sha256(b"a guess").hexdigest()                  # any other MAC: still foreign
    p.write_text(json.dumps(entry))
    assert check(tmp_path, repo, "--cache-dir", local).code == 1
    # the same entry planted in another user's folder (another secret) is foreign too
    other = tmp_path / "other"
    r = run(["check", "neg.urdf", "--cache-dir", local], cwd=repo, env={"XDG_CACHE_HOME": str(other)})
    assert r.code == 1 and "I003" in r.stdout


@pytest.mark.parametrize("kind", ["dev-zero", "fifo", "outside", "folder"])
def test_an_entry_that_is_no_regular_file_inside_the_cache_is_ignored(tmp_path, repo, kind):
    local = repo / ".myrabot-desc-cache"
    check(tmp_path, repo, "--cache-dir", local)
    p = entry_of(local)
    secret_file = tmp_path / "elsewhere.json"
    secret_file.write_text(p.read_text())           # a valid entry, but outside the cache folder
    p.unlink()
    if kind == "dev-zero":
        p.symlink_to("/dev/zero")
    elif kind == "fifo":
        os.mkfifo(p)
    elif kind == "outside":
        p.symlink_to(secret_file)
    else:
        p.mkdir()
    r = check(tmp_path, repo, "--cache-dir", local)
    assert r.code == 1 and "I003" in r.stdout
    assert r.cpu < 5 and r.rss < 400 * 2**20, (r.cpu, r.rss)


def test_a_symlinked_cache_folder_or_gitignore_makes_nothing_written_outside(tmp_path, repo):
    outside = tmp_path / "outside"
    outside.mkdir()
    (repo / "linked").symlink_to(outside)
    r = check(tmp_path, repo, "--cache-dir", repo / "linked")
    assert r.code == 1 and list(outside.iterdir()) == []
    (outside / "check").mkdir()
    cache = repo / "cache"
    cache.mkdir()
    (cache / "check").symlink_to(outside / "check")                       # the entries folder linked out
    check(tmp_path, repo, "--cache-dir", cache)
    assert list((outside / "check").iterdir()) == []
    fresh = repo / "fresh"
    fresh.mkdir()
    (fresh / ".gitignore").symlink_to(outside / "planted")                # dangling
    check(tmp_path, repo, "--cache-dir", fresh)
    assert not (outside / "planted").exists() and (fresh / ".gitignore").is_symlink()
    assert len(list((fresh / "check").glob("*.json"))) == 1               # the entry itself is written


def test_an_unknown_severity_or_a_hostile_message_in_a_signed_entry(tmp_path, repo):
    """Even an entry signed with the user's key is data: an unknown severity is ignored and rebuilt
    (it broke --format github), and a cached message is printed through the sanitiser."""
    local = repo / ".myrabot-desc-cache"
    check(tmp_path, repo, "--cache-dir", local)
    p = entry_of(local)
    entry = json.loads(p.read_text())
    entry["result"]["diagnostics"][0][1] = "fatal"
    p.write_text(json.dumps(sign(tmp_path, entry)))
    r = check(tmp_path, repo, "--cache-dir", local, "--format", "github")
    assert r.code == 1 and "::error file=neg.urdf,line=2,title=I003" in r.stdout
    entry = json.loads(p.read_text())
    entry["result"]["diagnostics"][0][2] = "x\n::add-mask::secret \x1b]0;title\x07 \x9b31m"
    p.write_text(json.dumps(sign(tmp_path, entry)))
    for fmt in ("text", "github"):
        r = check(tmp_path, repo, "--cache-dir", local, "--format", fmt)
        lines = r.stdout.splitlines()
        assert any("add-mask" in ln for ln in lines)                      # the cached message is used...
        assert not any(ln.lstrip().startswith("::add-mask") for ln in lines)   # ...but cannot command the runner
        assert "\x1b]" not in r.stdout and "\x9b" not in r.stdout


def test_the_key_is_the_content_of_what_the_check_read(tmp_path, repo):
    """An included file edited in place keeping its size and time stamp (what a name-or-metadata key
    misses) and the tool's own code: either change gives a new result."""
    write(repo / "parts.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
          '<link name="a"><inertial><mass value="-1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
          '</inertial></link></robot>\n')
    write(repo / "top.urdf.xacro", '<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">'
          '<xacro:include filename="parts.xacro"/></robot>\n')
    e = env(tmp_path)
    assert run(["check", "top.urdf.xacro"], cwd=repo, env=e).code == 1
    part = repo / "parts.xacro"
    st = part.stat()
    part.write_text(part.read_text().replace('"-1"', '"+1"'))             # same size
    os.utime(part, ns=(st.st_atime_ns, st.st_mtime_ns))                   # same time stamp
    assert part.stat().st_size == st.st_size
    r = run(["check", "top.urdf.xacro"], cwd=repo, env=e)
    assert r.code == 0 and "I003" not in r.stdout


def test_the_code_fingerprint_follows_the_package_source(tmp_path):
    from myrabot_desc.checks import cache

    pkg = tmp_path / "pkg" / "myrabot_desc"
    write(pkg / "a.py", "x = 1\n")
    write(pkg / "checks" / "cache.py", "")
    before = cache.code_fingerprint(pkg)
    write(pkg / "a.py", "x = 2\n")                                          # an editable install edited
    assert cache.code_fingerprint(pkg) != before


# ------------------------------------------------------------------ configuration
BOMB = """<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="m0"><link name="l"/></xacro:macro>
""" + "".join(f'  <xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>\n' for i in range(1, 22)) + \
    """  <xacro:m21/>
</robot>
"""


@pytest.mark.parametrize("value", [str(2**63), "1" + "0" * 28])
def test_limits_from_the_repository_can_only_lower(tmp_path, value):
    """A 2^21-call macro bomb stays refused when the configuration asks for 2^63 calls (it ran for ever),
    and a 29-digit limit is no internal error; a lower limit applies."""
    r = tmp_path / "r"
    write(r / "myrabot-desc.toml", f"[limits]\nmax-macro-calls = {value}\n")
    write(r / "bomb.urdf.xacro", BOMB)
    res = run(["check", "bomb.urdf.xacro", "--no-cache"], cwd=r)
    assert res.code == 2 and "over 20000 macro calls" in res.stdout + res.stderr
    assert not within_budget(res), within_budget(res)
    write(r / "myrabot-desc.toml", "[limits]\nmax-macro-calls = 100\n")
    res = run(["check", "bomb.urdf.xacro", "--no-cache"], cwd=r)
    assert res.code == 2 and "over 100 macro calls" in res.stdout + res.stderr


@pytest.mark.parametrize("setting, line", [
    ('allow-paths = ["/"]', 2),
    ('package-paths = ["../.."]', 2),
    ('[packages]\nsecrets = "/etc"', 3),
    ('[packages]\nup = "../elsewhere"', 3),
])
def test_folders_from_the_configuration_stay_inside_the_repository(tmp_path, setting, line):
    r = tmp_path / "r"
    (r / ".git").mkdir(parents=True)
    write(r / "myrabot-desc.toml", "# planted\n" + setting + "\n")
    write(r / "m.urdf", NEG)
    res = run(["check", "m.urdf"], cwd=r, env=env(tmp_path))
    assert res.code == 2
    assert f"myrabot-desc.toml:{line}: error:" in res.stdout + res.stderr and "outside the repository" in res.stdout + res.stderr


def test_load_yaml_cannot_reach_the_runner_through_the_configuration(tmp_path):
    """allow-paths = ["/"] used to let load_yaml read any file, whose text then reached the report."""
    r = tmp_path / "r"
    (r / ".git").mkdir(parents=True)
    secret = write(tmp_path / "runner-secret.yaml", "token: s3cr3t-value\n")
    write(r / "myrabot-desc.toml", 'allow-paths = ["/"]\n')
    write(r / "y.urdf.xacro", f'<robot name="y" xmlns:xacro="http://www.ros.org/wiki/xacro">'
          f'<link name="${{xacro.load_yaml(\'{secret}\')[\'token\']}}"/></robot>\n')
    res = run(["check", "y.urdf.xacro"], cwd=r, env=env(tmp_path))
    assert res.code == 2 and "s3cr3t" not in res.stdout + res.stderr


def test_many_globs_are_bounded_and_matching_is_linear(tmp_path):
    r = tmp_path / "r"
    write(r / "myrabot-desc.toml", "exclude = [" + ", ".join(f'"d{i}/*.urdf"' for i in range(34_000)) + "]\n")
    write(r / "m.urdf", NEG)
    res = run(["check", "-r", ".", "--no-cache"], cwd=r)
    assert res.code == 2 and "myrabot-desc.toml:1: error: exclude: 34000 entries, at most 1000" in res.stdout + res.stderr
    assert res.cpu < 5
    ignores = "\n".join(f'"p{i}/**" = ["I003"]' for i in range(30_000))
    write(r / "myrabot-desc.toml", "[per-file-ignores]\n" + ignores + "\n")
    res = run(["check", "-r", ".", "--no-cache"], cwd=r)
    assert res.code == 2 and "per-file-ignores: 30000 entries" in res.stdout + res.stderr and res.cpu < 5


def test_globset_cost_is_linear_in_files_and_patterns():
    from myrabot_desc.checks.config import GlobSet

    pats = [f"dir{i}/*.urdf" for i in range(1000)]
    gs = GlobSet(pats)
    paths = [f"robots/sub{i}/model_{i}.urdf" for i in range(20_000)]
    t = time.process_time()
    assert not any(gs.matching(p) for p in paths)
    assert time.process_time() - t < 3.0          # 20,000 files x 1,000 patterns (fnmatch: minutes)


def test_globset_agrees_with_pathspec():
    """The index finds exactly the patterns pathspec's gitignore matching says match."""
    import warnings

    from pathspec.patterns.gitwildmatch import GitWildMatchPattern

    from myrabot_desc.checks.config import GlobSet

    rnd = random.Random(7)
    segs = ["a", "b", "robots", "*.urdf", "*", "**", "x*", "?y", "[ab]c", "build", "m.xacro"]
    names = ["a", "b", "robots", "r.urdf", "x1", "zy", "ac", "build", "m.xacro", "q"]
    for _ in range(300):
        pats = ["/".join(rnd.choice(segs) for _ in range(rnd.randint(1, 3))) + rnd.choice(["", "/"])
                for _ in range(rnd.randint(1, 6))]
        gs = GlobSet(pats)
        for _ in range(20):
            path = "/".join(rnd.choice(names) for _ in range(rnd.randint(1, 4)))
            want = []
            for i, p in enumerate(pats):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    if GitWildMatchPattern(p).match_file(path) is not None:
                        want.append(i)
            assert gs.matching(path) == want, (pats, path)


def test_deep_nesting_and_sizes_are_errors_at_file_line(tmp_path):
    r = tmp_path / "r"
    write(r / "myrabot-desc.toml", "# deep\nselect = " + "[" * 5000 + "]" * 5000 + "\n")
    write(r / "m.urdf", NEG)
    res = run(["check", "m.urdf", "--no-cache"], cwd=r)
    assert res.code == 2 and "myrabot-desc.toml:2: error: arrays or tables nest deeper than" in res.stdout + res.stderr
    write(r / "myrabot-desc.toml", "ignore = [" + ", ".join('"I003"' for _ in range(5000)) + "]\n")
    res = run(["check", "m.urdf", "--no-cache"], cwd=r)
    assert res.code == 2 and "myrabot-desc.toml:1: error: ignore: 5000 entries" in res.stdout + res.stderr
    write(r / "myrabot-desc.toml", "x" * 2_000_000)
    res = run(["check", "m.urdf", "--no-cache"], cwd=r)
    assert res.code == 2 and "myrabot-desc.toml: error: cannot read configuration" in res.stdout + res.stderr
