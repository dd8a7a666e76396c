"""Type stubs of the binpick module (python/module/; docs/python.md)."""
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

RESULTS_CSV_HEADER: str

class InputError(ValueError): ...

_Matrix4 = npt.NDArray[np.float64]

class Model:
    """A trained point pair feature model (.ppfm)."""
    diameter: float
    voxel_size: float
    points: npt.NDArray[np.float32]
    symmetries: dict[str, list[Any]]
    lookalikes: list[_Matrix4]
    @staticmethod
    def load(path: str) -> "Model": ...
    @staticmethod
    def train(part: Optional[str] = None, *, vertices: Optional[npt.ArrayLike] = None,
              faces: Optional[npt.ArrayLike] = None, unit_scale: float = 1.0,
              diameter: Optional[float] = None, voxel_ratio: float = 0.05,
              distance_steps: int = 20, angle_steps: int = 30,
              cup_diameter: float = 0.0) -> "Model": ...
    def save(self, path: str) -> None: ...

class Detection:
    """A pose found around one highest point (model to camera, mm)."""
    R: npt.NDArray[np.float64]
    t: npt.NDArray[np.float64]
    obj_id: int
    score: float
    fit: float
    factors: dict[str, float]
    votes: int
    hypothesis: int
    reason: str
    pick: Optional[dict[str, Any]]
    pick_reason: str

class Detector:
    """Detection with one model or several; keyword arguments are detect's parameters."""
    params: dict[str, Any]
    obj_ids: list[int]
    def __init__(self, models: Union[Model, Sequence[Model], Mapping[int, Model]],
                 **params: Any) -> None: ...
    def detect(self, depth: npt.NDArray[Any], K: npt.NDArray[np.float64],
               depth_scale: float = 1.0) -> list[Detection]: ...
    def detect_cloud(self, points: npt.NDArray[np.float32],
                     normals: Optional[npt.NDArray[np.float32]] = None) -> list[Detection]: ...

def results_csv_row(scene_id: int, im_id: int, detection: Detection, seconds: float) -> str: ...
def read_depth_png(path: str) -> npt.NDArray[np.uint16]: ...

# The batch verbs: keyword arguments are the verb's options ('_' for '-'); progress(label, done,
# total, status) takes the progress bar's updates.
_Progress = Callable[[str, int, int, str], Any]

def command(verb: str, *, progress: Optional[_Progress] = None, **options: Any) -> None: ...
def command_line(args: Sequence[str], *, progress: Optional[_Progress] = None) -> None: ...
def synth(*, progress: Optional[_Progress] = None, **options: Any) -> None: ...
def detect(*, progress: Optional[_Progress] = None, **options: Any) -> None: ...
def eval(*, progress: Optional[_Progress] = None, **options: Any) -> None: ...
def run(*, progress: Optional[_Progress] = None, **options: Any) -> None: ...
def tune(*, progress: Optional[_Progress] = None, **options: Any) -> None: ...
