"""rtiow: a path tracer for the scenes of *Ray Tracing in One Weekend*, from Python.

    import rtiow
    scene = rtiow.builtin_scene("cover")
    render = rtiow.render(scene, width=400, spp=64)
    render.image          # numpy array, height x width x 3, float32, linear
    render.write("cover.exr")

render()'s keyword arguments are `rtiow render`'s long options with underscores
(--time-limit is time_limit); the same request gives the command line's pixels. See
docs/python.md.
"""

from ._rtiow import (  # noqa: F401
    InvalidInput,
    Render,
    Scene,
    __version__,
    builtin_scene,
    builtin_scenes,
    denoise,
    diff,
    load_scene,
    merge,
    read_channels,
    read_image,
    render,
    render_like,
    scene,
)

__all__ = [
    "InvalidInput",
    "Render",
    "Scene",
    "builtin_scene",
    "builtin_scenes",
    "denoise",
    "diff",
    "load_scene",
    "merge",
    "read_channels",
    "read_image",
    "render",
    "render_like",
    "scene",
]
