"""Type stubs of rtiow's compiled part (python/rtiow_module.cpp), for editors and type checkers."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class InvalidInput(ValueError):
    """rtiow's one-line refusal of an input (a bad option, a scene file, an image)."""

class Scene:
    """A scene: spheres, their materials, a camera and a sky."""

    @property
    def name(self) -> str: ...
    @property
    def spheres(self) -> int: ...
    def to_dict(self) -> Dict[str, Any]:
        """The scene in the scene file's words; rtiow.scene(d) gives it back."""

class Render:
    """A finished render."""

    @property
    def image(self) -> npt.NDArray[np.float32]:
        """height x width x 3, linear, over the render's own memory."""
    @property
    def spp(self) -> npt.NDArray[np.uint32]:
        """Each pixel's sample count, height x width."""
    @property
    def variance(self) -> Optional[npt.NDArray[np.float32]]:
        """The variance of each pixel's mean where the render kept two replicates, else None."""
    @property
    def passes(self) -> Dict[str, npt.NDArray[np.float32]]:
        """The first-hit passes asked, by channel name."""
    @property
    def noisy(self) -> Optional[npt.NDArray[np.float32]]:
        """With denoise=True, the noisy image the denoiser started from; else None."""
    @property
    def denoise_mse(self) -> Optional[npt.NDArray[np.float32]]:
        """With denoise=True, each pixel's estimated squared error (bias included); else None."""
    @property
    def summary(self) -> Dict[str, Any]:
        """What --summary-json says of the render."""
    def write(self, path: str, reproducible: bool = False) -> None:
        """Writes the image with rtiow's metadata, as `rtiow render -o` does."""

_ImageLike = Union[str, Render]

def builtin_scene(name: str = "cover", scene_seed: int = ...) -> Scene: ...
def builtin_scenes() -> List[str]: ...
def load_scene(path: str) -> Scene: ...
def scene(description: Dict[str, Any]) -> Scene:
    """A scene from a dict in the scene file's words (docs/scene-format.md)."""
def render(
    scene: Scene,
    *,
    progress: Optional[Callable[[float], Any]] = None,
    width: int = ...,
    height: int = ...,
    spp: int = ...,
    seed: int = ...,
    sampler: str = ...,
    depth: int = ...,
    time_limit: float = ...,
    image_error: float = ...,
    target_error: float = ...,
    adaptive: bool = ...,
    min_spp: int = ...,
    passes: Union[str, Sequence[str]] = ...,
    crop: Union[str, Tuple[int, int, int, int]] = ...,
    stats_channels: bool = ...,
    roulette: Union[bool, str] = ...,
    threads: int = ...,
    accel: str = ...,
    lookfrom: Union[str, Sequence[float]] = ...,
    lookat: Union[str, Sequence[float]] = ...,
    vup: Union[str, Sequence[float]] = ...,
    vfov: float = ...,
    aperture: float = ...,
    focus_distance: float = ...,
    fresnel: str = ...,
    part: str = ...,
    sample_range: str = ...,
    output: str = ...,
    checkpoint: float = ...,
    resume: bool = ...,
    restart: bool = ...,
    keep_state: bool = ...,
    preview: float = ...,
    display: str = ...,
    reproducible: bool = ...,
    denoise: bool = ...,
) -> Render: ...

def render_like(
    image: str,
    *,
    scene: Optional[Scene] = None,
    progress: Optional[Callable[[float], Any]] = None,
    width: int = ...,
    height: int = ...,
    spp: int = ...,
    seed: int = ...,
    sampler: str = ...,
    depth: int = ...,
    time_limit: float = ...,
    image_error: float = ...,
    target_error: float = ...,
    adaptive: bool = ...,
    min_spp: int = ...,
    passes: Union[str, Sequence[str]] = ...,
    crop: Union[str, Tuple[int, int, int, int]] = ...,
    stats_channels: bool = ...,
    roulette: Union[bool, str] = ...,
    threads: int = ...,
    accel: str = ...,
    lookfrom: Union[str, Sequence[float]] = ...,
    lookat: Union[str, Sequence[float]] = ...,
    vup: Union[str, Sequence[float]] = ...,
    vfov: float = ...,
    aperture: float = ...,
    focus_distance: float = ...,
    fresnel: str = ...,
    part: str = ...,
    sample_range: str = ...,
    output: str = ...,
    checkpoint: float = ...,
    resume: bool = ...,
    restart: bool = ...,
    keep_state: bool = ...,
    preview: float = ...,
    display: str = ...,
    reproducible: bool = ...,
    denoise: bool = ...,
) -> Render:
    """Renders again what an image rtiow wrote records, as rtiow render --like does."""
def merge(
    parts: Sequence[str],
    output: str,
    *,
    stats_channels: bool = False,
    denoise: bool = False,
    threads: int = 0,
    progress: Optional[Callable[[float], Any]] = None,
) -> Optional[Dict[str, float]]:
    """Adds part files into the image one render of all their samples gives (rtiow merge)."""
def denoise(
    parts: Sequence[str],
    output: str,
    *,
    stats_channels: bool = False,
    threads: int = 0,
    progress: Optional[Callable[[float], Any]] = None,
) -> Dict[str, float]:
    """Denoises a render kept as part files (rendered with denoise=True), as rtiow denoise does."""
def diff(
    test: Union[_ImageLike, Sequence[_ImageLike]],
    reference: _ImageLike,
    *,
    alpha: float = 0.01,
    block: int = 16,
    fail: float = 1e-6,
    fail_percent: float = 0.0,
) -> Dict[str, Any]: ...
def read_image(path: str) -> npt.NDArray[np.float32]: ...
def read_channels(path: str) -> Dict[str, npt.NDArray[np.float32]]: ...
