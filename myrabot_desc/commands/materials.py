"""``myrabot-desc materials FILE.material``: OGRE script -> SDF <material> blocks or JSON."""

from __future__ import annotations

import click

from myrabot_desc.commands.console import guarded
from myrabot_desc.materials.export import export
from myrabot_desc.output import write_output
from myrabot_desc.sanitize import clean


@click.command("materials", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("file", metavar="FILE.material", required=False)
@click.option("--to", "fmt", type=click.Choice(["sdf", "json"]), default="sdf", show_default=True,
              help="Output format.")
@click.option("-o", "--output", default="-", metavar="OUT", help="Write here instead of standard output.")
@click.option("--name", "names", multiple=True, metavar="NAME",
              help="Only this material (repeatable). Default: every material in the file.")
@click.option("--texture-prefix", default=None, metavar="URI",
              help="Write textures as URI+name (e.g. model://cans/materials/textures/) instead of the "
                   "image's absolute path.")
@click.option("--stock", is_flag=True,
              help="Print Gazebo classic's stock materials (Gazebo/Grey...) instead of a FILE; JSON also "
                   "shows what gz-sim's substring lookup would give.")
def materials_cmd(file, fmt, output, names, texture_prefix, stock):
    """Read an OGRE .material script (Gazebo classic) and print explicit colours.

    gz-sim cannot read material scripts, so each material becomes an SDF
    <material> with ambient, diffuse, specular and emissive (a texture as
    <pbr><metal><albedo_map>), or JSON. Parents (`material A : B`) are looked
    up in the file, its imports, the other scripts in its folder and Gazebo's
    stock materials (Gazebo/Grey...). Textures are looked for in ../textures.

    \b
    Examples:
      myrabot-desc materials Media/materials/scripts/myrabot_fer.material
      myrabot-desc materials brazo_fer.material --to json -o out/brazo.json
      myrabot-desc materials brazo_fer.material --name brazo_fer/White
      myrabot-desc materials --stock --name Gazebo/Grey
    """
    with guarded():
        if stock == (file is not None):
            raise click.UsageError("give a FILE.material, or --stock (not both)")
        text, warnings = export(file, fmt, names, texture_prefix, stock)
        write_output(output, text)
        if output != "-":                  # on stdout the warnings are already in the text
            for w in warnings:
                click.echo(f"warning: {clean(w)}", err=True)
