"""read_log(), odometry(), evaluate() and simulate(): known answers and the command-line tool's answers."""
import subprocess

import numpy as np
import pytest

import contour_reg as cr
from conftest import BUNDLED_GT, BUNDLED_LOG


def test_read_log_gives_scans_and_odometry(bundled_log):
    assert len(bundled_log) == 99
    assert len(bundled_log[0]) == 1081
    assert np.all(np.diff(bundled_log.stamps) > 0)
    assert bundled_log.odometry.shape == (99, 3) and np.isfinite(bundled_log.odometry).all()
    assert bundled_log[-1].stamp == bundled_log.stamps[-1]
    with pytest.raises(IndexError):
        bundled_log[99]


def test_read_log_without_wheel_odometry_gives_the_scans_alone(bundled_log):
    scans_alone = cr.read_log(str(BUNDLED_LOG), wheel_odometry=False)
    assert len(scans_alone) == len(bundled_log)
    np.testing.assert_array_equal(scans_alone.stamps, bundled_log.stamps)
    np.testing.assert_array_equal(scans_alone[10].ranges, bundled_log[10].ranges)
    assert np.isnan(scans_alone.odometry).all() and scans_alone.wheel_odometry.shape[0] == 0
    # Without odometry the guess of each step is the motion before, not the wheels'.
    assert cr.odometry(scans_alone).registrations == len(bundled_log) - 1


def test_a_beam_step_keeps_every_nth_beam(bundled_log):
    # 1081 beams of 0.25 deg become 361 of 0.75 deg: beam k is the original's beam 3k.
    coarse = cr.read_log(str(BUNDLED_LOG), beam_step=3)
    assert len(coarse[0]) == 361
    assert coarse[0].angle_increment == pytest.approx(3 * bundled_log[0].angle_increment)
    np.testing.assert_array_equal(coarse[5].ranges, bundled_log[5].ranges[::3])
    with pytest.raises(ValueError, match="beam_step"):
        cr.read_log(str(BUNDLED_LOG), beam_step=0)


def test_a_missing_file_raises_with_its_name(tmp_path):
    missing = tmp_path / "no-such-log.clf"
    with pytest.raises(cr.ReadError, match="no-such-log.clf"):
        cr.read_log(str(missing))
    with pytest.raises(OSError):
        cr.read_tum(str(missing))


def test_a_bad_line_is_named_by_file_and_line(tmp_path):
    lines = BUNDLED_LOG.read_text().splitlines()
    first_scan = next(n for n, line in enumerate(lines) if line.startswith("ROBOTLASER1"))
    lines[first_scan + 2] = "ROBOTLASER1 0 -2.35 4.71 0.0043 30.0 0.1 0 1081 1.0 oops"
    corrupt = tmp_path / "corrupt.clf"
    corrupt.write_text("\n".join(lines) + "\n")
    log = cr.read_log(str(corrupt))
    assert log.skipped == 1
    assert log.problems[0].startswith(f"{corrupt}:{first_scan + 3}:")
    bad_tum = tmp_path / "bad.tum"
    bad_tum.write_text("0 0 0 0 0 0 0 1\n1 zero 0 0 0 0 0 1\n")
    with pytest.raises(cr.ReadError, match="bad.tum:2"):
        cr.read_tum(str(bad_tum))


def test_odometry_on_the_bundled_log_matches_the_tool(tool, tmp_path, bundled_log):
    run = cr.odometry(bundled_log, method="contour")
    assert run.trajectory.shape == (99, 4) and run.registrations == 98 and run.failures == 0
    assert len(run.steps) == 98 and all(step.converged for step in run.steps)
    tum = tmp_path / "contour.tum"
    subprocess.run([tool, "odometry", bundled_log.source, "-m", "contour", "-o", str(tum)], check=True,
                   capture_output=True)
    np.testing.assert_allclose(run.trajectory, cr.read_tum(str(tum)), atol=1e-5)
    metrics = cr.evaluate(run.trajectory, cr.read_tum(str(BUNDLED_GT)))
    assert metrics["end_point_percent"] < 0.5 and metrics["ate_m"] < 0.05
    assert metrics["path_length_m"] == pytest.approx(24.4, abs=0.5)


def test_steps_chain_to_the_trajectory(bundled_log):
    run = cr.odometry(bundled_log, method="contour")
    pose = np.zeros(3)
    for step in run.steps:
        pose = cr.matrix_pose(cr.pose_matrix(pose) @ cr.pose_matrix(step.motion))
    np.testing.assert_allclose(pose[:2], run.trajectory[-1, 1:3], atol=1e-6)


def test_simulate_and_evaluate_know_the_truth(s_run):
    assert len(s_run.log) == s_run.ground_truth.shape[0]
    np.testing.assert_allclose(s_run.log.stamps, np.arange(len(s_run.log)) / 5.0)
    assert s_run.path_length > 10
    perfect = cr.evaluate(s_run.ground_truth, s_run.ground_truth)
    assert perfect["end_point_percent"] == pytest.approx(0.0, abs=1e-9) and perfect["ate_m"] == pytest.approx(0.0, abs=1e-9)
    shifted = s_run.ground_truth.copy()
    shifted[-1, 1] += 0.5  # the last pose 0.5 m off: end-point error 0.5 m over the path
    end = cr.evaluate(shifted, s_run.ground_truth)
    assert end["end_point_m"] == pytest.approx(0.5, abs=1e-6)
    assert "relations_all" not in end
    # Stamps that do not tell the poses apart (a log that kept none) pair nothing: no metric,
    # and the count says why.
    unstamped = shifted.copy()
    unstamped[:, 0] = 0.0
    none = cr.evaluate(unstamped, unstamped)
    assert "end_point_percent" not in none and "ate_m" not in none
    assert none["estimate_stamps_not_increasing"] == len(unstamped) - 1
    assert end["estimate_stamps_not_increasing"] == 0 and end["ground_truth_stamps_not_increasing"] == 0


def test_the_wheel_odometry_is_logged_between_the_scans(s_run):
    samples = s_run.log.wheel_odometry
    assert samples.shape[1] == 4
    # 50 Hz over the run, the scans' stamps among them; at each scan the scan's own odometry.
    assert samples.shape[0] == round(s_run.log.stamps[-1] * 50) + 1
    np.testing.assert_allclose(np.diff(samples[:, 0]), 0.02, atol=1e-9)
    at_scans = samples[np.isin(np.round(samples[:, 0], 9), np.round(s_run.log.stamps, 9))]
    np.testing.assert_allclose(at_scans[:, 1:], s_run.log.odometry, atol=1e-12)


def test_relation_errors_of_the_truth_are_zero(s_run):
    gt = s_run.ground_truth
    relations = np.array([[gt[k, 0], gt[k + 5, 0], *cr.relative_pose(gt[k, 1:], gt[k + 5, 1:])]
                          for k in range(0, len(gt) - 5, 5)])
    errors = cr.relation_errors(gt, relations)
    assert errors["count"] == len(relations) and errors["translation_mean_m"] == pytest.approx(0.0, abs=1e-9)
    odometry = cr.Log([s_run.log[k] for k in range(len(s_run.log))], odometry=s_run.log.odometry)
    wheel = cr.odometry(odometry, method="contour", guess="odom")
    assert cr.relation_errors(wheel.trajectory, relations)["translation_mean_m"] < 0.02


def test_normalised_error_squared_weighs_the_error_by_the_covariance_and_the_reference_floor(s_run):
    covariance = np.diag([0.03 ** 2, 1e-4, 1e-4])
    assert cr.normalised_error_squared((1.03, 2, 0.1), (1, 2, 0.1), covariance, (0, 0)) == pytest.approx(1.0)
    # 3 cm and the reference's 4 cm in quadrature: 5 cm; 10 cm off gives 4.
    assert cr.normalised_error_squared((1.1, 2, 0.1), (1, 2, 0.1), covariance, (0.04, 0)) == pytest.approx(4.0)
    with pytest.raises(ValueError):
        cr.normalised_error_squared((1, 2, 0.1), (1, 2, 0.1), covariance, (-1, 0))
    # NaN in a pose or a covariance is refused, where it gave a NEES of NaN or inf.
    with pytest.raises(ValueError, match="finite"):
        cr.normalised_error_squared((np.nan, 2, 0.1), (1, 2, 0.1), covariance)
    with pytest.raises(ValueError, match="covariance must be finite"):
        cr.normalised_error_squared((1, 2, 0.1), (1, 2, 0.1), np.full((3, 3), np.nan))
    # The covariance of a registration covers its error against the truth.
    gt = s_run.ground_truth
    result = cr.register(s_run.log[10], s_run.log[5])
    truth = cr.relative_pose(gt[5, 1:], gt[10, 1:])
    assert result.converged
    assert 0 < cr.normalised_error_squared(result.pose, truth, result.covariance) < 11.34


def test_triangle_closure_weighs_how_far_three_registrations_fail_to_compose(s_run):
    small = np.diag([0.01 ** 2, 0.01 ** 2, 1e-8])
    # ab and bc no motion, ac 3 cm ahead: 3 cm back, the three variances summed.
    closure = cr.triangle_closure((0, 0, 0), small, (0, 0, 0), small, (0.03, 0, 0), small)
    assert closure["error"] == pytest.approx((-0.03, 0, 0), abs=1e-12)
    assert closure["covariance"][0, 0] == pytest.approx(3e-4)
    assert closure["nees"] == pytest.approx(3.0, rel=1e-3)
    # Registrations of scans 5 -> 10, 10 -> 15 and 5 -> 15 of a run close within their covariances.
    ab, bc, ac = (cr.register(s_run.log[b], s_run.log[a]) for a, b in ((5, 10), (10, 15), (5, 15)))
    assert ab.converged and bc.converged and ac.converged
    closure = cr.triangle_closure(ab.pose, ab.covariance, bc.pose, bc.covariance, ac.pose, ac.covariance)
    assert np.hypot(*closure["error"][:2]) < 0.05
    assert 0 <= closure["nees"] < 11.34
    with pytest.raises(ValueError):
        cr.triangle_closure((0, 0), small, (0, 0, 0), small, (0, 0, 0), small)
    with pytest.raises(ValueError, match="ab_covariance must be finite"):
        cr.triangle_closure((0, 0, 0), np.full((3, 3), np.nan), (0, 0, 0), small, (0, 0, 0), small)


def test_write_and_read_back(tmp_path, s_run):
    path = tmp_path / "s.clf"
    cr.write_carmen(str(path), s_run.log)
    again = cr.read_log(str(path))
    assert len(again) == len(s_run.log)
    np.testing.assert_allclose(again[4].ranges, s_run.log[4].ranges, atol=1e-3, equal_nan=True)
    cr.write_tum(str(tmp_path / "gt.tum"), s_run.ground_truth)
    np.testing.assert_allclose(cr.read_tum(str(tmp_path / "gt.tum")), s_run.ground_truth, atol=1e-5)


@pytest.mark.parametrize("name", ["s.bag", "s.db3", "s.mcap", "s.clf"])
def test_write_log_writes_the_format_its_name_asks_for(tmp_path, s_run, name):
    path = tmp_path / name
    try:
        cr.write_log(str(path), s_run.log)
    except cr.ReadError as error:
        if "cannot write ROS bags" in str(error):
            pytest.skip("built without ROS bag support")
        raise
    again = cr.read_log(str(path))
    assert len(again) == len(s_run.log)
    np.testing.assert_allclose(again.stamps, s_run.log.stamps, atol=1e-6)
    np.testing.assert_allclose(again[4].ranges, s_run.log[4].ranges, atol=1e-3, equal_nan=True)
    np.testing.assert_allclose(again.odometry, s_run.log.odometry, atol=1e-5)
    magic = {".bag": b"#ROSBAG V2.0", ".db3": b"SQLite format 3", ".mcap": b"\x89MCAP0\r\n", ".clf": b""}
    assert path.read_bytes().startswith(magic[path.suffix])
    with pytest.raises(cr.ReadError, match="nowhere"):
        cr.write_log(str(tmp_path / "nowhere" / name), s_run.log)


def test_the_door_row_has_its_line():
    run = cr.simulate(path="line", map="doors", lidar="ydlidar", rate=0.5, speed=1.0)
    assert run.path_length == pytest.approx(54.0)
    assert len(run.log) == 28  # a scan every 2 m and at the end
    np.testing.assert_allclose(run.ground_truth[:, 2], 1.2)  # along the corridor's axis
    with pytest.raises(ValueError, match="in the door row"):
        cr.simulate(path="L", map="doors")


def test_a_sick_lms200_run_is_followed_within_a_percent():
    run = cr.simulate(path="S", lidar="sick", rate=2)
    scan = run.log[0]
    assert len(scan.ranges) == 181
    assert scan.angle_increment == pytest.approx(np.pi / 180)
    finite = np.asarray(scan.ranges)[np.isfinite(scan.ranges)]
    np.testing.assert_allclose(finite * 100, np.round(finite * 100), atol=1e-3)  # whole centimetres
    odometry = cr.odometry(run.log)
    assert odometry.failures == 0
    assert cr.evaluate(odometry.trajectory, run.ground_truth)["end_point_percent"] < 1.0


def test_bad_simulation_and_odometry_arguments_raise(bundled_log):
    with pytest.raises(ValueError, match="unknown path"):
        cr.simulate(path="Z")
    with pytest.raises(ValueError, match="unknown lidar"):
        cr.simulate(lidar="velodyne")
    with pytest.raises(ValueError, match="rate"):
        cr.simulate(rate=0)
    with pytest.raises(ValueError, match="unknown guess"):
        cr.odometry(bundled_log, guess="gps")
    with pytest.raises(ValueError, match="N x 4"):
        cr.evaluate(np.zeros((3, 3)))


def test_numbers_out_of_range_raise_as_the_command_line_refuses_them(bundled_log):
    # As the command line's options and TUM and relations files: NaN or infinite rows, a
    # mounting no robot carries, a reading range or LIDAR turn out of range.
    truth = np.array([[0, 0, 0, 0], [1, 1, 0, 0], [2, 2, 0, 0.1]], float)
    unknown = truth.copy()
    unknown[1, 1] = np.nan
    with pytest.raises(ValueError, match="estimate must be finite"):
        cr.evaluate(unknown, ground_truth=truth)
    with pytest.raises(ValueError, match="ground_truth must be finite"):
        cr.evaluate(truth, ground_truth=unknown)
    relations = np.array([[0, 1, 1, 0, 0], [1, 2, 1, 0, 0.1]], float)
    with pytest.raises(ValueError, match="relations must be finite"):
        cr.relation_errors(truth, np.where(relations == 0.1, np.inf, relations))
    with pytest.raises(ValueError, match="max_dt"):
        cr.relation_errors(truth, relations, max_dt=np.nan)
    with pytest.raises(ValueError, match="local_dt"):
        cr.evaluate(truth, relations=relations, local_dt=-5)
    with pytest.raises(ValueError, match="max_range"):
        cr.read_log(str(BUNDLED_LOG), max_range=-1)
    with pytest.raises(ValueError, match="scan_period"):
        cr.read_log(str(BUNDLED_LOG), scan_period=1e300)
    with pytest.raises(ValueError, match="laser_pose"):
        cr.read_log(str(BUNDLED_LOG), laser_pose=(1e300, 0, 0))
    with pytest.raises(ValueError, match="laser_pose"):
        bundled_log.laser_pose = (0, 200, 0)
    with pytest.raises(ValueError, match="laser_pose"):
        cr.simulate(path="L", laser_pose=(0, 0, 7))


def test_a_mounted_laser_gives_the_robots_trajectory(tmp_path):
    mounted = cr.simulate(path="L", laser_pose=(0.3, 0.1, 0.5))
    assert mounted.log.laser_pose == pytest.approx((0.3, 0.1, 0.5))
    robot = cr.odometry(mounted.log, guess="odom")
    laser = cr.odometry(mounted.log, guess="odom", frame="laser")
    assert robot.frame == "robot" and laser.frame == "laser"
    assert cr.evaluate(robot.trajectory, mounted.ground_truth)["end_point_percent"] < 1.0
    assert cr.evaluate(laser.trajectory, mounted.ground_truth)["end_point_percent"] > 5.0
    path = tmp_path / "mounted.clf"
    cr.write_carmen(str(path), mounted.log)
    assert cr.read_log(str(path)).laser_pose == pytest.approx((0.3, 0.1, 0.5), abs=1e-6)
    assert cr.read_log(str(path), laser_pose=(0, 0, 0)).laser_pose == (0, 0, 0)
    with pytest.raises(ValueError, match="laser_pose"):
        cr.read_log(str(path), laser_pose=(0, 0))
    with pytest.raises(ValueError, match="unknown frame"):
        cr.odometry(mounted.log, frame="map")


def test_a_local_map_odometry_follows_the_truth(s_run):
    run = cr.odometry(s_run.log, local_map=3)
    assert run.failures == 0
    assert any(step.reference + 1 < step.scan for step in run.steps)
    assert cr.evaluate(run.trajectory, s_run.ground_truth)["end_point_percent"] < 1.0


def test_wheel_odometry_is_fused_with_the_guess_odom(s_run):
    fused = cr.odometry(s_run.log, guess="odom")
    guessed = cr.odometry(s_run.log, guess="odom", wheel_fusion=False)
    assert fused.fused == fused.registrations and fused.pinned_by_wheels == 0  # an office pins every direction
    assert guessed.fused == 0 and cr.odometry(s_run.log).fused == 0
    for step in fused.steps:
        assert np.linalg.eigvalsh(step.covariance).min() > 0
    assert cr.evaluate(fused.trajectory, s_run.ground_truth)["end_point_percent"] < 1.0


def test_without_wheels_a_scan_bent_by_an_ended_turn_converges_on_a_retry(tool, tmp_path):
    # The scans of a moving robot, read without the wheel odometry, are first deskewed by the
    # last motion; where a turn ends that bends a scan taken straight, and the retry with the
    # scan as taken converges.
    bag = tmp_path / "turning.bag"
    made = subprocess.run([tool, "simulate", "--path", "L", "--rate", "5", "--motion", "continuous", "--out",
                           str(bag)], capture_output=True, text=True)
    if made.returncode != 0:
        pytest.skip("the tool writes no ROS bags: " + made.stderr.strip())
    run = cr.odometry(cr.read_log(str(bag), wheel_odometry=False))
    assert run.failures == 0 and run.recovered_by_retry >= 1


def test_the_predicted_motion_decides_between_motions_a_period_apart():
    # Along the door row the scans fit a motion a period (3 m) along as well as the truth; the
    # motion predicted over the interval allows one of them alone.
    run = cr.simulate(path="line", map="doors", lidar="ydlidar", rate=1.0, speed=1.0)
    odometry = cr.odometry(run.log)
    assert odometry.decided_by_prediction >= odometry.registrations // 2
    assert "ambiguous" not in odometry.failure_reasons
    truth = run.ground_truth
    for step in odometry.steps:
        if step.converged:
            expected = cr.relative_pose(truth[step.reference, 1:], truth[step.scan, 1:])
            assert abs(step.motion[0] - expected[0]) < 0.05, step.scan
