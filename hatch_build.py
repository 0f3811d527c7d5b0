"""Wheel build hook: record which commit the wheel is built from (myrabot_desc/BUILD_COMMIT), so
that an installed ``myrabot-desc --version`` can say it (myrabot_desc/commands/version.py)."""

from __future__ import annotations

import importlib.util
import os
import tempfile
from pathlib import Path

from hatchling.builders.hooks.plugin.interface import BuildHookInterface


class CustomBuildHook(BuildHookInterface):
    def initialize(self, version, build_data):
        if version == "editable":           # runs from the checkout: git answers at run time
            return
        path = Path(self.root) / "myrabot_desc" / "commands" / "version.py"
        spec = importlib.util.spec_from_file_location("_myrabot_desc_version", path)
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        state = mod.git_state(Path(self.root), self.metadata.version)
        if state is None:                   # not built from a checkout: --version says unknown
            return
        fd, self._tmp = tempfile.mkstemp(prefix="myrabot-desc-build-", suffix=".txt")
        with os.fdopen(fd, "w", encoding="ascii") as f:
            f.write(f"{state['commit']} {'dirty' if state['dirty'] else 'clean'} "
                    f"{'release' if state['release'] else '-'}\n")
        build_data["force_include"][self._tmp] = "myrabot_desc/BUILD_COMMIT"

    def finalize(self, version, build_data, artifact_path):
        tmp = getattr(self, "_tmp", None)
        if tmp and os.path.exists(tmp):
            os.unlink(tmp)
