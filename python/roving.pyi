# Type stubs for the `roving` extension module (roving_module.cpp), for editors and type checkers.
# Each keyword is an option of `roving measure` / `roving merge` / `roving batch` (the option with _ for -); None
# leaves it at the command's default. tests/python/test_roving.py checks that these keywords are
# exactly the commands' options.
from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Model = Union[str, "PathLike[str]", npt.ArrayLike, Tuple[npt.ArrayLike, npt.ArrayLike], Any]
Progress = Callable[[str, str, int, int], None]

class Error(ValueError): ...
class Warning(UserWarning): ...  # each of a report's warnings, through Python's warnings (not with quiet=True)

__version__: str  # the version the module was built from, as the reports' tool.version
commit: str  # the commit it was built from, as the reports' tool.commit
methods: List[str]
resolved_by: Dict[str, int]

def measure(
    reference: Model,
    test: Model,
    *,
    method: Optional[str] = ...,
    semantics: Optional[str] = ...,
    symmetric: bool = ...,
    samples: Optional[str] = ...,
    precision: Optional[str] = ...,
    seed: Optional[int] = ...,
    max_error: Optional[str] = ...,
    ref_type: Optional[str] = ...,
    test_type: Optional[str] = ...,
    views: Optional[str] = ...,
    resolution: Optional[int] = ...,
    backend: Optional[str] = ...,
    camera_geometry: Optional[str] = ...,
    view_culling: Optional[str] = ...,
    hausdorff_bound: Optional[str] = ...,
    ibsm: bool = ...,
    ibsm_views: Optional[int] = ...,
    ibsm_resolution: Optional[int] = ...,
    histogram_bins: Optional[int] = ...,
    threshold: Optional[Union[str, Sequence[str]]] = ...,
    certify_thresholds: bool = ...,
    pcc: bool = ...,
    pcc_resolution: Optional[float] = ...,
    pcc_normals: Optional[str] = ...,
    pcc_dropdups: Optional[int] = ...,
    pcc_neighbors_proc: Optional[int] = ...,
    pcc_average_normals: Optional[int] = ...,
    pcc_mse_space: Optional[int] = ...,
    pcc_normal_calc_modification: Optional[bool] = ...,
    protocol: Optional[str] = ...,
    dtu_obs_mask: Optional[str] = ...,
    dtu_plane: Optional[str] = ...,
    dtu_density: Optional[float] = ...,
    dtu_patch: Optional[float] = ...,
    dtu_max_dist: Optional[float] = ...,
    tnt_crop: Optional[str] = ...,
    tnt_alignment: Optional[str] = ...,
    tnt_trajectory: Optional[str] = ...,
    tnt_reference_trajectory: Optional[str] = ...,
    tnt_mapping: Optional[str] = ...,
    tnt_scene: Optional[str] = ...,
    tnt_tau: Optional[float] = ...,
    tnt_curves: Optional[str] = ...,
    tnt_plys: Optional[str] = ...,
    protocol_seed: Optional[Union[int, str]] = ...,
    protocol_runs: Optional[int] = ...,
    quiet: bool = ...,
    trust_references: bool = ...,
    strict_materials: bool = ...,
    fail_above: Optional[Union[str, Sequence[str]]] = ...,
    fail_below: Optional[Union[str, Sequence[str]]] = ...,
    gate_on: Optional[str] = ...,
    json: Optional[str] = ...,
    shard: Optional[str] = ...,
    shard_out: Optional[str] = ...,
    chunk: Optional[int] = ...,  # REF read a block of faces at a time where per_sample=False
    samples_out: Optional[str] = ...,
    heatmap: Optional[str] = ...,
    heatmap_png: Optional[str] = ...,
    html: Optional[str] = ...,
    heatmap_of: Optional[str] = ...,
    heatmap_range: Optional[str] = ...,
    progress: Optional[Progress] = ...,
    per_sample: bool = ...,  # False: no per-sample arrays (and REF may stream, as --chunk says)
) -> Dict[str, Any]: ...

def merge(
    *parts: Union[str, "PathLike[str]"],
    json: Optional[str] = ...,
    quiet: bool = ...,
) -> Dict[str, Any]: ...

def batch(
    *pairs: Union[str, "PathLike[str]"],
    out: Optional[str] = ...,
    shard: Optional[str] = ...,
    merge: bool = ...,
    html: bool = ...,
    skip_unpaired: bool = ...,
    trust_references: bool = ...,
    strict_materials: bool = ...,
    method: Optional[str] = ...,
    semantics: Optional[str] = ...,
    symmetric: bool = ...,
    samples: Optional[str] = ...,
    precision: Optional[str] = ...,
    seed: Optional[int] = ...,
    max_error: Optional[str] = ...,
    ref_type: Optional[str] = ...,
    test_type: Optional[str] = ...,
    views: Optional[str] = ...,
    resolution: Optional[int] = ...,
    backend: Optional[str] = ...,
    camera_geometry: Optional[str] = ...,
    view_culling: Optional[str] = ...,
    hausdorff_bound: Optional[str] = ...,
    ibsm: bool = ...,
    ibsm_views: Optional[int] = ...,
    ibsm_resolution: Optional[int] = ...,
    histogram_bins: Optional[int] = ...,
    threshold: Optional[Union[str, Sequence[str]]] = ...,
    certify_thresholds: bool = ...,
    pcc: bool = ...,
    pcc_resolution: Optional[float] = ...,
    pcc_normals: Optional[str] = ...,
    pcc_dropdups: Optional[int] = ...,
    pcc_neighbors_proc: Optional[int] = ...,
    pcc_average_normals: Optional[int] = ...,
    pcc_mse_space: Optional[int] = ...,
    pcc_normal_calc_modification: Optional[bool] = ...,
    protocol: Optional[str] = ...,
    dtu_obs_mask: Optional[str] = ...,
    dtu_plane: Optional[str] = ...,
    dtu_density: Optional[float] = ...,
    dtu_patch: Optional[float] = ...,
    dtu_max_dist: Optional[float] = ...,
    tnt_crop: Optional[str] = ...,
    tnt_alignment: Optional[str] = ...,
    tnt_trajectory: Optional[str] = ...,
    tnt_reference_trajectory: Optional[str] = ...,
    tnt_mapping: Optional[str] = ...,
    tnt_scene: Optional[str] = ...,
    tnt_tau: Optional[float] = ...,
    tnt_curves: Optional[str] = ...,
    tnt_plys: Optional[str] = ...,
    protocol_seed: Optional[Union[int, str]] = ...,
    protocol_runs: Optional[int] = ...,
    quiet: bool = ...,
    progress: Optional[Progress] = ...,
) -> int: ...
