"""Which optional extra a command needs, and the one line that says so when it is missing.

``pip install myrabot-desc`` is the core (build, check with Pinocchio, info, convert to SDF and
worlds, sim's kinematic programs); the rest comes with an extra (pyproject.toml
``[project.optional-dependencies]``). A command that needs an extra calls :func:`require` before it
does anything, so the user reads which extra to install (exit 2) instead of a missing module.
"""

from __future__ import annotations

import importlib.util

from myrabot_desc.errors import InputError

# extra -> (the modules it brings, what it is for)
EXTRAS = {
    "mjcf": (("mujoco",), "MJCF for MuJoCo"),
    "render": (("mujoco", "PIL"), "offscreen pictures"),
    "view": (("viser",), "the browser viewer"),
    "plot": (("matplotlib",), "plots"),
    "examples": (("example_robot_data",), "example-robot-data's robots"),
    "yourdfpy": (("yourdfpy",), "Robot.to_yourdfpy()"),
}


def missing(extra: str) -> list[str]:
    """The modules of ``extra`` that cannot be imported here (found, not imported: cheap)."""
    mods, _ = EXTRAS[extra]
    out = []
    for mod in mods:
        try:
            if importlib.util.find_spec(mod) is None:
                out.append(mod)
        except (ImportError, ValueError):
            out.append(mod)
    return out


def hint(extra: str, what: str) -> str:
    """The one line for a missing extra."""
    gone = ", ".join(missing(extra)) or EXTRAS[extra][0][0]
    return (f"{what} needs the [{extra}] extra ({EXTRAS[extra][1]}; missing: {gone}): "
            f"pip install 'myrabot-desc[{extra}]'")


def require(extra: str, what: str) -> None:
    """Raise the one-line InputError (exit 2 under ``guarded``) when ``extra`` is not installed."""
    if missing(extra):
        raise InputError(hint(extra, what))
