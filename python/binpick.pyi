"""Type stubs of the binpick module (python/binpick_module.cpp; docs/python.md)."""
from typing import Any, Optional

import numpy as np
import numpy.typing as npt

RESULTS_CSV_HEADER: str

class InputError(ValueError): ...

class Model:
    """A trained point pair feature model (.ppfm)."""
    diameter: float
    voxel_size: float
    lookalikes: int
    @staticmethod
    def load(path: str) -> "Model": ...
    @staticmethod
    def train(part: str, *, unit_scale: float = 1.0, diameter: Optional[float] = None,
              voxel_ratio: float = 0.05, distance_steps: int = 20, angle_steps: int = 30) -> "Model": ...
    def save(self, path: str) -> None: ...

class Detection:
    """A pose found around one highest point (model to camera, mm)."""
    R: npt.NDArray[np.float64]
    t: npt.NDArray[np.float64]
    score: float
    fit: float
    factors: dict[str, float]
    votes: int
    hypothesis: int
    reason: str

class Detector:
    """Detection with one model; keyword arguments are detect's parameters ('_' for '-')."""
    params: dict[str, Any]
    def __init__(self, model: Model, **params: Any) -> None: ...
    def detect(self, depth: npt.NDArray[Any], K: npt.NDArray[np.float64],
               depth_scale: float = 1.0) -> list[Detection]: ...
    def detect_cloud(self, points: npt.NDArray[np.float32],
                     normals: Optional[npt.NDArray[np.float32]] = None) -> list[Detection]: ...

def results_csv_row(scene_id: int, im_id: int, obj_id: int, detection: Detection,
                    seconds: float) -> str: ...
def read_depth_png(path: str) -> npt.NDArray[np.uint16]: ...
