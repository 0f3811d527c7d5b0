"""Texture images named by untrusted models and material scripts, read with limits.

An image is read through the path gate (a regular file, at most ``max_mesh_bytes``), and its
pixel count is checked from its header before any pixel is decoded: a small PNG can announce
176 megapixels (~900 MB decoded). MYRABOT_DESC_MAX_TEXTURE_PIXELS (safety.LIMITS) bounds it.
"""

from __future__ import annotations

from myrabot_desc.errors import InputError
from myrabot_desc.safety import limit, read_checked


class TextureError(ValueError):
    """A texture that cannot or may not be read (the message names the file and why)."""


def open_image(path, roots=None):
    """A PIL image of ``path`` whose size is within the pixel limit (header read, nothing decoded
    yet); TextureError otherwise."""
    import io

    from PIL import Image

    name = getattr(path, "name", str(path))
    try:
        data = read_checked(path, roots, limit("max_mesh_bytes"), what="texture")
    except InputError as exc:
        raise TextureError(f"{name}: {exc.message}") from None
    most = limit("max_texture_pixels")
    try:
        import warnings

        with warnings.catch_warnings():      # PIL's own bomb warning: the limit below is ours
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            im = Image.open(io.BytesIO(data))
        w, h = im.size
    except Exception as exc:  # PIL's own errors for a file that is no image
        raise TextureError(f"{name} is not a readable image ({type(exc).__name__})") from None
    if w * h > most:
        raise TextureError(f"{name} is {w}x{h} pixels, over the {most}-pixel texture limit "
                           "(MYRABOT_DESC_MAX_TEXTURE_PIXELS)")
    return im


def mean_rgb(path, roots=None) -> tuple[float, float, float] | None:
    """Average colour of a texture image (0..1 each), None when it cannot or may not be read."""
    try:
        im = open_image(path, roots)
    except TextureError:
        return None
    try:
        from PIL import Image

        with im:
            im.draft("RGB", (256, 256))           # JPEG: decode at a reduced scale (same mean)
            px = im.convert("RGB").resize((1, 1), Image.Resampling.BOX).getpixel((0, 0))
    except Exception:  # a truncated or corrupt image: keep the material's own colour
        return None
    return tuple(round(c / 255.0, 4) for c in px)
