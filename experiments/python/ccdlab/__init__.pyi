# Type stubs of the ccdlab package (its functions are compiled: experiments/python/ccdlab_module.cpp).
from typing import Any, Sequence, TypedDict, Union, Unpack

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

class Options(TypedDict, total=False):
    """The keywords every function and Detector take: ccdlab.settings() lists them with their defaults."""
    k: int  # the k-DOP of every bounding volume: 6, 14, 18 or 26 directions
    width: int  # BVH width the traversal reads: 2 (binary BVTT) or 4 (wide, SIMD lane pairs)
    end_boxes: str  # also drop node pairs apart on x, y or z at both ends of the step: always, never, or where they pay
    hierarchy: Strategy  # the BVH builder, e.g. sah:bins=32
    restructure_threshold: float  # rebuild a sub-tree whose quality grew past this x its value at the last build; 0 = off
    normal_cones: bool  # continuous normal-cone culling of self tests (thickness 0 only)
    scheduler: Strategy  # the BVTT traversal scheduler, e.g. phc:c=8
    threads: int  # threads for every stage
    tester: Strategy  # the elementary CCD tester, e.g. conservative:delta=1e-4
    narrow: str  # narrow phase: batched (SIMD culling stages over whole batches) or scalar (pair by pair)
    representative: str  # who tests a feature pair: fixed (ICCD owners + orphan set) or first_free
    rule_triangles: str  # stage 0 (whole triangle pairs): where it pays, always or never
    rule_sixteenths: str  # stage 3's sixteenths of the step: where they pay, always or never
    rule_proximity: str  # stage 4 (distance at the step's ends): where it pays, always or never
    rule_orphan_carry: str  # the candidates carry the orphans: where it pays, always or never
    rule_certificates: str  # orphan blocks skipped by their certificates: where it pays, always or never
    memory_limit: str  # resident memory a step may use (8GiB, 60%, none); above the predicted need it streams its candidates
    candidate_limit: float  # refuse a step estimated to find more candidate triangle pairs per triangle than this; 0 = no limit
    time_limit: float  # seconds a step may run: past them it stops with an error; 0 = no limit

def step(x0: Points, x1: Points, faces: Triangles, **options: Unpack[Options]) -> StepResult: ...
def earliest_toi(x0: Points, x1: Points, faces: Triangles, **options: Unpack[Options]) -> float: ...
def sequence(frames: Sequence[Points], faces: Triangles, **options: Unpack[Options]) -> list[StepResult]: ...
def proximity(x: Points, faces: Triangles, dhat: float, **options: Unpack[Options]) -> ProximityResult: ...
def active_set_and_step(x0: Points, x1: Points, faces: Triangles, dhat: float, separation: float,
                        **options: Unpack[Options]) -> ActiveSetAndStep: ...
class Detector:
    """A detector kept across calls: its hierarchies are built on the first call and refit on later ones."""
    def __init__(self, faces: Triangles | None = None, *, bodies: Sequence[dict[str, Any]] | None = None,
                 **options: Unpack[Options]) -> None: ...
    def step(self, x0: Points, x1: Points) -> dict[str, npt.NDArray[Any]]: ...
    def earliest_toi(self, x0: Points, x1: Points) -> float: ...
    def proximity(self, x: Points, dhat: float) -> dict[str, npt.NDArray[Any]]: ...
    def active_set_and_step(self, x0: Points, x1: Points, dhat: float, separation: float) -> dict[str, Any]: ...
    @property
    def options(self) -> str: ...

def validate(paths: Sequence[str], testers: Sequence[str] = ..., repeat: int = ...) -> list[dict[str, Any]]: ...
def schedulers() -> list[str]: ...
def testers() -> list[str]: ...
def settings() -> list[dict[str, Any]]: ...
