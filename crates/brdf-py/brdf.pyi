"""Type stubs of the ``brdf`` module (PyO3): fit analytic BRDF models to
measured reflectance data with NumPy arrays in and out."""

import os
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

StrPath = Union[str, "os.PathLike[str]"]
ArrayLike = npt.ArrayLike
Samples = dict[str, Any]

class BrdfError(ValueError):
    """An error of the brdf library; the message names the file, line or
    parameter at fault."""

class Model:
    """A fitted or saved model."""

    @staticmethod
    def load(path: StrPath) -> "Model":
        """Read a model saved by ``Model.save`` or ``brdf fit --save``."""
    @property
    def name(self) -> str:
        """Catalogue name of the model."""
    @property
    def channels(self) -> int:
        """Colour channels the model returns."""
    @property
    def params(self) -> dict[str, float]:
        """Parameter values by name."""
    def eval(self, wi: ArrayLike, wo: ArrayLike) -> npt.NDArray[np.float64]:
        """Values at ``(n, 3)`` direction pairs: ``(n, channels)`` in 1/sr."""
    def export(
        self,
        *,
        to: str,
        name: str = "fitted",
        scene: bool = False,
        light: str = "studio",
        surface: str = "gltf_pbr",
        convert: bool = False,
        force: bool = False,
        mesh: bool = True,
    ) -> str:
        """The model as a mitsuba, pbrt, gltf, materialx, usd or blender material."""
    def tabulate(self, grid: StrPath) -> bytes:
        """The model tabulated on the grid of an RGL ``.bsdf`` measurement:
        a file Mitsuba 3's ``measured`` plugin renders."""
    def save(self, path: StrPath) -> None:
        """Write the model (JSON)."""
    def render(self, *, light: str = "studio", size: int = 128) -> npt.NDArray[np.float64]:
        """The judge's sphere under ``light`` ("studio", "sky" or
        "directional"): ``(size, size, 3)`` linear radiance."""

class Fit:
    """The outcome of ``fit``."""

    @property
    def model(self) -> Model:
        """The fitted model (the first of ``models``)."""
    @property
    def models(self) -> list[Model]:
        """One model per fit (three for ``channels="per-channel"``)."""
    @property
    def report(self) -> dict[str, Any]:
        """The report ``brdf fit --json`` prints."""
    @property
    def image_error(self) -> Optional[dict[str, Any]]:
        """Image errors against dense data (RGL, MERL), else None: per light set
        (``lights``) HDR-FLIP, PSNR and CIEDE2000, and ``colour_plane``."""

def load(path: StrPath) -> Samples:
    """Read a data set into NumPy arrays (``wi``, ``wo``, ``values``, ...)."""

def save_samples(data: Samples, path: StrPath) -> None:
    """Write a data set as a CSV sample file ``load`` reads back exactly."""

def fit(
    data: Union[StrPath, Samples],
    model: Optional[str] = None,
    *,
    channels: str = "rgb",
    metric: str = "auto",
    limit_deg: float = 80.0,
    starts: int = 12,
    irls_max_iterations: int = 500,
    solver: str = "auto",
    lobes: int = 1,
    order: int = 8,
    degree: int = 7,
    save: Optional[StrPath] = None,
    polish: bool = False,
    for_renderer: Optional[str] = None,
) -> Fit:
    """Fit a model to measured data, as ``brdf fit``; with ``for_renderer``
    instead of ``model``, the renderer's exact model closest to the data,
    as ``brdf fit --for``."""

def select(
    data: Union[StrPath, Samples],
    *,
    tolerance: Optional[float] = None,
    limit_deg: float = 80.0,
    grey: bool = False,
    models: Optional[list[str]] = None,
    max_parameters: Optional[int] = None,
    exhaustive: bool = False,
    by_image: Optional[bool] = None,
    polish: bool = False,
) -> dict[str, Any]:
    """Choose a model, as ``brdf select --json``: on data that can be
    rendered (or with ``by_image=True``) the renderer model of least image
    error; on scattered data (or with ``by_image=False``) the smallest
    adequate model by Ngan L2."""

def eval(
    model: Union[str, "os.PathLike[str]", dict[str, Any]],
    wi: ArrayLike,
    wo: ArrayLike,
    *,
    params: Optional[dict[str, float]] = None,
    channels: int = 1,
    lobes: int = 1,
    order: int = 8,
    degree: int = 7,
) -> npt.NDArray[np.float64]:
    """Evaluate a catalogue or saved model at direction pairs."""

def export(
    model: Union[str, "os.PathLike[str]", dict[str, Any]],
    to: str,
    *,
    params: Optional[dict[str, float]] = None,
    channels: int = 1,
    lobes: int = 1,
    order: int = 8,
    degree: int = 7,
    name: str = "fitted",
    scene: bool = False,
    light: str = "studio",
    surface: str = "gltf_pbr",
    convert: bool = False,
    force: bool = False,
    mesh: bool = True,
) -> str:
    """A model as a renderer's material, as ``brdf export`` writes it."""

def models(
    *, channels: int = 1, lobes: int = 1, order: int = 8, degree: int = 7
) -> list[dict[str, Any]]:
    """The catalogue, as ``brdf models --json`` prints it."""

def materials(path: StrPath) -> list[str]:
    """The data sets a path stands for, as ``brdf batch --data`` reads it."""

def canonical_name(name: str) -> str:
    """The catalogue name a forgiving model name stands for."""

def data_name(spec: str) -> str:
    """A data set's name in outputs (relative to ``BRDF_DATA``)."""

def format_number(x: float, digits: int) -> str:
    """``x`` with ``digits`` significant digits, as ``brdf batch``'s tables."""

def format_full(x: float) -> str:
    """``x`` in full, as ``brdf batch``'s CSV files hold it."""
