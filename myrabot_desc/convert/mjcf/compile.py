"""MuJoCo itself: importing it, compiling a spec, and its messages turned into ours.

MuJoCo refuses a flat tensor and computes every mesh's volume even when the inertias are given;
both are repaired here, for the elements that need it, and said in a warning. Its own warnings
(through ``mju_user_warning``, or the Python ``UserWarning``s ``MjSpec.compile`` turns them into)
and whatever its C code prints on stdout/stderr become our warnings: its default handler would
also append them to MUJOCO_LOG.TXT in the working directory, a file the user never asked for.
"""

from __future__ import annotations

import contextlib
import re

from myrabot_desc.errors import InputError


def import_mujoco(what: str = "MJCF"):
    """mujoco, without the GLFW probe; ``what`` needs it (for the one-line error when it is missing)."""
    import os

    # We never render: without this, `import mujoco` loads pyGLFW, which spawns a Python
    # subprocess to probe libglfw (a process per conversion, seen by the hardening audit).
    # (only while importing: a process this one starts later, a render, chooses its own)
    saved = os.environ.get("MUJOCO_GL")
    os.environ.setdefault("MUJOCO_GL", "disable")
    try:
        import mujoco
    except ImportError:
        raise InputError(f"{what} needs the mujoco package: pip install 'myrabot-desc[mjcf]'") from None
    finally:
        if saved is None:
            os.environ.pop("MUJOCO_GL", None)
    return mujoco


@contextlib.contextmanager
def messages_to(mujoco, notes):
    """MuJoCo's warnings, and what its C code prints, as our warnings while the block runs."""
    with _c_stdout_to(notes), _warnings_to(mujoco, notes), _python_warnings_to(notes):
        yield


@contextlib.contextmanager
def _python_warnings_to(notes):
    """``MjSpec.compile`` reports MuJoCo's warnings as Python ``UserWarning``s."""
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            for w in caught:
                notes.warn("MuJoCo: " + str(w.message).strip())


@contextlib.contextmanager
def _c_stdout_to(notes):
    import os
    import sys
    import tempfile

    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), 1)
        os.dup2(tmp.fileno(), 2)
        try:
            yield
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
            tmp.seek(0)
            for line in tmp.read().decode("utf-8", "replace").splitlines():
                line = line.strip()
                if line:
                    notes.warn("MuJoCo: " + line.removeprefix("WARNING: "))


@contextlib.contextmanager
def _warnings_to(mujoco, notes):
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: notes.warn("MuJoCo: " + str(msg).strip()))
    try:
        yield
    finally:
        mujoco.set_mju_user_warning(previous)


def rejected(exc: Exception, loc) -> InputError:
    msg = str(exc).strip().splitlines()
    return InputError(f"MuJoCo rejected the model: {' '.join(m.strip() for m in msg if m.strip())}", loc)


MAX_SHELLED = 1000


def compile_spec(mujoco, spec, notes):
    """The compiled model. A mesh too thin to have a volume (a decal, a flat nub) gets shell
    inertia and a body whose fused links add up to a flat tensor MuJoCo's ``balanceinertia``;
    then it compiles again. Anything else MuJoCo refuses raises its ValueError."""
    shelled = []
    while True:
        try:
            model = spec.compile()
            break
        except ValueError as exc:
            text = str(exc)
            if "A + B >= C" in text and not spec.compiler.balanceinertia:
                # a body whose fused links add up to a flat tensor (point masses on an axis): MuJoCo's
                # own repair, which raises only the bodies that need it
                b = re.search(r"Element name '([^']*)'", text)
                notes.warn(f"body '{b.group(1) if b else '?'}' (with the links fixed to it) has an inertia that breaks "
                           "A + B >= C: MuJoCo's balanceinertia raises the bodies that do")
                spec.compiler.balanceinertia = True
                continue
            m = re.search(r"mesh volume is too small: (\S+?)\s*\.", text)
            mesh = spec.mesh(m.group(1)) if m else None
            if mesh is None or mesh.inertia == mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL \
                    or len(shelled) > MAX_SHELLED:
                raise
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
            shelled.append(mesh.name)
    if shelled:
        notes.warn(f"{len(shelled)} mesh(es) too thin for a volume use shell inertia in MuJoCo: {', '.join(shelled)}")
    return model
