"""The command line: every click command and the click-free plain ``build`` path, in one package.

entry.py (the console script) → fastbuild.py (a plain ``build``, no click) or main.py (the click
group, subcommands loaded lazily from build.py, check.py, convert.py, materials.py, sim.py,
info.py, view.py, render.py). options.py holds the option tables both parsers use, console.py
the one-line errors and exit codes, common.py the click side of the shared options. The layers
below (consumers, model, expand, base) import nothing from here (docs/architecture.md).
"""
