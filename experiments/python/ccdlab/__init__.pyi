# Type stubs of the ccdlab package (its functions are compiled: experiments/python/ccdlab_module.cpp).
from typing import Any, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

class Error(ValueError): ...

Points = npt.ArrayLike  # N×3 positions (any numeric dtype, order or strides; lists and tuples too)
Triangles = npt.ArrayLike  # F×3 vertex indices
Strategy = Union[str, dict[str, Any]]  # a name, "name:key=value,…" or {"name": …, key: value}

class StepResult(TypedDict):
    vf: npt.NDArray[np.int64]          # M×4: v, f0, f1, f2
    vf_toi: npt.NDArray[np.float64]
    vf_coords: npt.NDArray[np.float64]  # M×2: barycentric weights of f1, f2
    vf_normal: npt.NDArray[np.float64]  # M×3
    ee: npt.NDArray[np.int64]          # K×4: a0, a1, b0, b1
    ee_toi: npt.NDArray[np.float64]
    ee_coords: npt.NDArray[np.float64]  # K×2: parameters along edge a, edge b
    ee_normal: npt.NDArray[np.float64]
    hash: str
    counters: dict[str, int]
    ms: dict[str, float]

class ProximityResult(TypedDict):
    vf: npt.NDArray[np.int64]           # M×4: v, f0, f1, f2
    vf_distance: npt.NDArray[np.float64]
    vf_type: npt.NDArray[np.str_]       # p_t, p_e0, p_e1, p_e2, p_t0, p_t1, p_t2
    vf_coords: npt.NDArray[np.float64]   # M×2: barycentric weights of f1, f2 of the closest point
    ee: npt.NDArray[np.int64]           # K×4: a0, a1, b0, b1
    ee_distance: npt.NDArray[np.float64]
    ee_type: npt.NDArray[np.str_]       # ea_eb, ea0_eb, ea1_eb, ea_eb0, ea_eb1, ea0_eb0, ea0_eb1, ea1_eb0, ea1_eb1
    ee_coords: npt.NDArray[np.float64]   # K×2: parameters along edge a, edge b
    hash: str
    counters: dict[str, int]
    ms: dict[str, float]

class ActiveSetAndStep(ProximityResult):
    step_size: float

def step(x0: Points, x1: Points, faces: Triangles, **options: Any) -> StepResult: ...
def earliest_toi(x0: Points, x1: Points, faces: Triangles, **options: Any) -> float: ...
def sequence(frames: Sequence[Points], faces: Triangles, **options: Any) -> list[StepResult]: ...
def proximity(x: Points, faces: Triangles, dhat: float, **options: Any) -> ProximityResult: ...
def active_set_and_step(x0: Points, x1: Points, faces: Triangles, dhat: float, separation: float,
                        **options: Any) -> ActiveSetAndStep: ...
class Detector:
    """A detector kept across calls: its hierarchies are built on the first call and refit on later ones."""
    def __init__(self, faces: Triangles | None = None, *, bodies: Sequence[dict[str, Any]] | None = None,
                 **options: Any) -> None: ...
    def step(self, x0: Points, x1: Points) -> dict[str, npt.NDArray[Any]]: ...
    def earliest_toi(self, x0: Points, x1: Points) -> float: ...
    def proximity(self, x: Points, dhat: float) -> dict[str, npt.NDArray[Any]]: ...
    def active_set_and_step(self, x0: Points, x1: Points, dhat: float, separation: float) -> dict[str, Any]: ...
    @property
    def options(self) -> str: ...

def validate(paths: Sequence[str], testers: Sequence[str] = ..., repeat: int = ...) -> list[dict[str, Any]]: ...
def schedulers() -> list[str]: ...
def testers() -> list[str]: ...
