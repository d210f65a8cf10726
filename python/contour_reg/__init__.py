"""2-D LIDAR scan registration and laser odometry by contour analysis, with PCL's ICP and NDT beside it.

Scans are LaserScan objects or N x 2 NumPy arrays of points in beam order (NaN rows: invalid beams);
trajectories are N x 4 arrays (stamp s, x m, y m, yaw rad); transforms and covariances 3 x 3 arrays.

    import contour_reg as cr
    log = cr.read_log("data/office/L-hokuyo-2hz.clf")
    result = cr.register(log[1], log[0])              # scan 1 onto scan 0, from a zero guess
    run = cr.odometry(log, method="contour")          # the whole log, one pose per scan
    cr.evaluate(run.trajectory, cr.read_tum("data/office/L-hokuyo-2hz.gt.tum"))

See docs/python.md.
"""

from ._core import (
    Features,
    LaserScan,
    Log,
    OdometryRun,
    OdometryStep,
    ReadError,
    RegistrationResult,
    SimulatedRun,
    evaluate,
    features,
    matrix_pose,
    methods,
    normalised_error_squared,
    odometry,
    pose_matrix,
    read_log,
    read_relations,
    read_tum,
    register,
    relation_errors,
    relative_pose,
    simulate,
    triangle_closure,
    write_carmen,
    write_log,
    write_tum,
)

__all__ = [
    "Features", "LaserScan", "Log", "OdometryRun", "OdometryStep", "ReadError", "RegistrationResult",
    "SimulatedRun", "evaluate", "features", "matrix_pose", "methods", "normalised_error_squared", "odometry",
    "pose_matrix", "read_log", "read_relations", "read_tum", "register", "relation_errors", "relative_pose",
    "simulate", "triangle_closure", "write_carmen", "write_log", "write_tum",
]
