"""The inputs of the commands that read a model: click's FILE and package options (the one table
in options.py) passing :class:`ModelInputs`, which load the Robot."""

from __future__ import annotations

from myrabot_desc.commands import options
from myrabot_desc.commands.options import Inputs
from myrabot_desc.model.loader import load_robot


class ModelInputs(Inputs):
    """Inputs that load the model."""

    def load(self, path: str | None = None):
        """Load one model (the first FILE, or the bundled MYRAbot) into a Robot."""
        return load_robot(path if path is not None else self.file, **self.build_options())


def input_options(multiple: bool = False):
    """options.input_options passing ModelInputs (``inputs.load()`` gives the Robot)."""
    return options.input_options(multiple, ModelInputs)
