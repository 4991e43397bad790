# The Tanks and Temples toolbox's registration.py (written for Open3D 0.9) on Debian 12's Open3D
# 0.16, its algorithm untouched; record_tnt.sh imports this before the toolbox. What changed:
# - o3d.registration is o3d.pipelines.registration since 0.10;
# - RANSACConvergenceCriteria lost max_validation (the toolbox sets it; nothing reads it);
# - registration_ransac_based_on_correspondence took the criteria after ransac_n; 0.16 puts a
#   list of checkers there, so the toolbox's positional call is passed on with its criteria named.
import open3d as o3d
_r = o3d.pipelines.registration
class _Criteria(_r.RANSACConvergenceCriteria):
    pass
def _ransac(source, target, corres, distance, estimation, ransac_n, criteria):
    return _r.registration_ransac_based_on_correspondence(source, target, corres, distance, estimation, ransac_n,
                                                          criteria=criteria)
class _Registration:
    def __getattr__(self, name):
        return {"RANSACConvergenceCriteria": _Criteria,
                "registration_ransac_based_on_correspondence": _ransac}.get(name) or getattr(_r, name)
o3d.registration = _Registration()
