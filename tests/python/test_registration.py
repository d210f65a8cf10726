"""register() and features(): known answers, the same answers as the C++ tool, NaN beams, threads, errors."""
import csv
import subprocess
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import contour_reg as cr
from conftest import BUNDLED_GT


def pose_error(result_pose, reference):
    dx, dy = result_pose[0] - reference[0], result_pose[1] - reference[1]
    dyaw = np.remainder(result_pose[2] - reference[2] + np.pi, 2 * np.pi) - np.pi
    return np.hypot(dx, dy), abs(dyaw)


def true_motion(run, k, j):
    gt = run.ground_truth
    return cr.relative_pose(gt[k, 1:], gt[j, 1:])


def square_room_scan(half_width=2.0, beams=720):
    """A scan from the centre of a square room of side 2 * half_width, 360 deg."""
    angles = -np.pi + np.arange(beams) * (2 * np.pi / beams)
    ranges = half_width / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return cr.LaserScan(ranges, angle_min=angles[0], angle_increment=angles[1] - angles[0], range_max=30.0)


def test_contour_recovers_simulated_motion(s_run):
    log = s_run.log
    for k in range(0, len(log) - 2, 10):
        result = cr.register(log[k + 2], log[k])
        assert result.converged, result.reason
        assert result.status == "converged"
        error_m, error_rad = pose_error(result.pose, true_motion(s_run, k, k + 2))
        assert error_m < 0.03 and error_rad < np.radians(0.5), (k, result)
        assert result.transform.shape == (3, 3)
        assert np.all(np.linalg.eigvalsh(result.covariance) > 0)


def test_a_declined_registration_gives_the_motion_it_declined(s_run):
    # No special points (threshold 0.99), all of the contour demanded on the target, and no
    # free space to let the beams vouch for less: the contours' own best motion is found and
    # declined for low overlap.
    truth = true_motion(s_run, 0, 2)
    result = cr.register(s_run.log[2], s_run.log[0], threshold=0.99, local_fallback=1.0, free_space=False)
    assert not result.converged and result.status == "low_overlap", result
    d = result.declined
    error_m, error_rad = pose_error((d[0, 2], d[1, 2], np.arctan2(d[1, 0], d[0, 0])), truth)
    assert error_m < 0.03 and error_rad < np.radians(0.5), (result.declined, truth)
    np.testing.assert_array_equal(result.transform, np.eye(3))
    assert cr.register(s_run.log[2], s_run.log[0]).declined is None  # converged: nothing declined


def test_a_converged_registration_names_the_distinct_rival_it_weighed(bundled_log):
    # Scans 81 and 82 of the bundled log: the judge weighs a motion 0.2 m and more from its
    # answer and keeps the answer, which the ground truth confirms.
    gt = cr.read_tum(str(BUNDLED_GT))
    truth = cr.relative_pose(gt[81, 1:], gt[82, 1:])
    result = cr.register(bundled_log[82], bundled_log[81])
    assert result.converged, result
    assert all(e < 0.01 for e in pose_error(result.pose, truth)), (result, truth)
    r = result.rival
    rival_pose = (r[0, 2], r[1, 2], np.arctan2(r[1, 0], r[0, 0]))
    apart_m, apart_rad = pose_error(rival_pose, result.pose)
    assert apart_m + apart_rad > 0.2, (rival_pose, result)
    assert cr.register(bundled_log[82], bundled_log[81], threshold=0.99, local_fallback=1.0).rival is None


def test_icp_from_the_true_motion_stays_there(s_run):
    guess = cr.pose_matrix(true_motion(s_run, 0, 1))
    result = cr.register(s_run.log[1], s_run.log[0], method="icp", guess=guess)
    assert result.converged
    error_m, _ = pose_error(result.pose, true_motion(s_run, 0, 1))
    assert error_m < 0.03


def test_points_give_the_same_answer_as_the_scan(bundled_log):
    for method in ("contour", "icp"):
        from_scans = cr.register(bundled_log[5], bundled_log[4], method=method)
        from_points = cr.register(bundled_log[5].points(), bundled_log[4].points(), method=method)
        assert from_scans.converged == from_points.converged and from_scans.inliers == from_points.inliers
        np.testing.assert_allclose(from_scans.transform, from_points.transform, atol=1e-9)


def test_nan_beams_are_accepted(s_run):
    source, target = s_run.log[3], s_run.log[0]
    ranges = source.ranges
    ranges[::7] = np.nan
    ranges[3::11] = np.inf
    source.ranges = ranges
    points = target.points()
    points[::5] = np.nan
    result = cr.register(source, points)
    assert result.converged, result.reason
    error_m, error_rad = pose_error(result.pose, true_motion(s_run, 0, 3))
    assert error_m < 0.03 and error_rad < np.radians(0.5)
    assert np.isnan(source.points()[0]).all()


def test_an_empty_scan_is_not_converged_and_says_why(bundled_log):
    empty = cr.LaserScan(np.full(100, np.nan), angle_min=-1.0, angle_increment=0.02)
    result = cr.register(empty, bundled_log[0])
    assert not result.converged
    assert result.status != "converged" and result.reason
    np.testing.assert_array_equal(result.transform, np.eye(3))


def test_same_answers_as_the_command_line_tool(tool, tmp_path, bundled_log):
    csv_path = tmp_path / "pairs.csv"
    subprocess.run([tool, "relations", bundled_log.source, "--log-poses", "3", "--limit", "30", "--methods",
                    "contour", "icp", "--pairs-csv", str(csv_path)], check=True, capture_output=True)
    rows = list(csv.DictReader(open(csv_path)))
    assert len(rows) == 60
    for row in rows:
        first, second = int(row["first"]), int(row["second"])
        result = cr.register(bundled_log[second], bundled_log[first], method=row["method"])
        assert result.converged == (row["converged"] == "1"), row
        x, y, yaw = result.pose
        assert abs(x - float(row["est_x_m"])) < 1e-4 and abs(y - float(row["est_y_m"])) < 1e-4, row
        assert abs(yaw - float(row["est_yaw_rad"])) < 1e-5, row
        if result.score is None:
            assert row["est_score"] == "" and row["est_overlap"] == "", row
        else:
            assert abs(result.score - float(row["est_score"])) < 1e-4, row
            assert abs(result.overlap - float(row["est_overlap"])) < 1e-4, row
            assert result.score <= result.overlap <= 1.0, row
    assert any(row["est_score"] for row in rows if row["method"] == "contour" and row["converged"] == "1")
    assert not any(row["est_score"] for row in rows if row["method"] == "icp")


def test_threads_give_the_same_answers_as_one_thread(bundled_log):
    pairs = [(k + 2, k) for k in range(0, 60, 3)]
    serial = [cr.register(bundled_log[s], bundled_log[t]).transform for s, t in pairs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda p: cr.register(bundled_log[p[0]], bundled_log[p[1]]).transform, pairs))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)


def test_features_of_a_square_room_are_its_four_corners():
    features = cr.features(square_room_scan())
    assert len(features) == 4
    np.testing.assert_allclose(np.sort(np.abs(features.points), axis=0), np.full((4, 2), 2.0), atol=0.02)
    np.testing.assert_allclose(features.corner_angles, np.pi / 2, atol=np.radians(5))
    assert len(features.contours) >= 1 and features.contours[0].shape[1] == 2
    assert np.all(features.responses > 0.08)


def test_bad_arguments_raise():
    scan = square_room_scan()
    with pytest.raises(ValueError, match="unknown method 'foo'"):
        cr.register(scan, scan, method="foo")
    with pytest.raises(TypeError, match="unknown setting 'treshold'"):
        cr.register(scan, scan, treshold=0.1)
    with pytest.raises(ValueError, match="invalid setting"):
        cr.register(scan, scan, contour_step=-1.0)
    with pytest.raises(ValueError, match="3 x 3"):
        cr.register(scan, scan, guess=np.eye(2))
    # A guess or a matrix that is no rigid motion (no rotation block, a last row that is not
    # 0 0 1, a mirror) has no pose: it raises instead of reading as some yaw.
    for not_rigid in (np.zeros((3, 3)), np.diag([2.0, 2.0, 1.0]), np.diag([1.0, -1.0, 1.0]),
                      np.array([[1.0, 0, 0], [0, 1, 0], [0.5, 0, 1]])):
        with pytest.raises(ValueError, match="rigid"):
            cr.register(scan, scan, guess=not_rigid)
        with pytest.raises(ValueError, match="rigid"):
            cr.matrix_pose(not_rigid)
    # A rotation in single precision, as from a PCL transform, is one.
    turned = cr.pose_matrix((1.0, 2.0, 0.3)).astype(np.float32)
    assert cr.matrix_pose(turned) == pytest.approx((1.0, 2.0, 0.3), abs=1e-6)
    with pytest.raises(ValueError, match="N x 2"):
        cr.register(np.zeros((10, 3)), scan)
    with pytest.raises(TypeError):
        cr.register("scan", scan)
    with pytest.raises(ValueError, match="evenly spaced"):
        cr.LaserScan.from_angles(np.ones(4), np.array([0.0, 0.1, 0.25, 0.3]))


def test_from_angles_builds_the_scan_geometry():
    scan = cr.LaserScan.from_angles(np.array([1.0, 2.0, 3.0]), np.array([-0.1, 0.0, 0.1]), stamp=4.0)
    assert scan.angle_min == pytest.approx(-0.1) and scan.angle_increment == pytest.approx(0.1)
    np.testing.assert_allclose(scan.points()[1], [2.0, 0.0])
    assert len(scan) == 3 and scan.stamp == 4.0


def test_the_scan_geometry_set_afterwards_is_checked_as_the_constructor_checks_it():
    scan = square_room_scan()
    for name, value in (("angle_min", float("nan")), ("angle_min", float("inf")), ("angle_increment", 0.0),
                        ("angle_increment", float("nan")), ("time_increment", -1.0),
                        ("time_increment", float("nan"))):
        with pytest.raises(ValueError, match=name):
            setattr(scan, name, value)
    scan.angle_increment = -scan.angle_increment  # beams taken clockwise: a geometry
    scan.time_increment = 1e-5
    assert scan.time_increment == 1e-5


def test_methods_lists_every_method_and_each_registers():
    names = cr.methods()
    assert names == ["contour", "icp", "icp-pl", "ndt2d", "ndt", "gicp", "contour+icp"]
    scan = square_room_scan()
    for name in names:
        assert isinstance(cr.register(scan, scan, method=name), cr.RegistrationResult)


def test_twists_deskew_scans_taken_while_moving():
    """The S path at 2 Hz without stopping, each scan deskewed by the true motion to the next one:
    on pairs that turn, the raw scans are bent and turn the answer by degrees."""
    run = cr.simulate(path="S", rate=2.0, motion="continuous")
    log, gt = run.log, run.ground_truth
    assert log[0].time_increment > 0

    def twist(k):
        x, y, yaw = true_motion(run, k, k + 1)
        dt = gt[k + 1, 0] - gt[k, 0]
        return (x / dt, y / dt, yaw / dt)

    raw, deskewed = [], []
    for k in range(len(log) - 2):
        truth = true_motion(run, k, k + 1)
        if abs(truth[2]) < np.radians(5):
            continue
        plain = cr.register(log[k + 1], log[k])
        swept = cr.register(log[k + 1], log[k], source_twist=twist(k + 1), target_twist=twist(k))
        assert swept.converged, (k, swept.reason)
        deskewed.append(np.degrees(pose_error(swept.pose, truth)[1]))
        raw.append(np.degrees(pose_error(plain.pose, truth)[1]) if plain.converged else np.inf)
    assert len(deskewed) >= 6
    assert np.median(deskewed) < 0.5 * np.median(raw), (deskewed, raw)
    assert max(deskewed) < 6.0, deskewed
    with pytest.raises(ValueError):
        cr.register(np.zeros((4, 2)), log[0], source_twist=(1.0, 0.0, 0.0))
    with pytest.raises(ValueError):
        cr.register(log[1], log[0], source_twist=(1.0, 0.0))


def test_an_ambiguous_registration_gives_the_motions_that_fit_as_well(s_run):
    # A square room seen from its centre, and again turned 45 deg: turns of 45 deg plus any
    # multiple of 90 deg fit alike.
    target = square_room_scan()
    beams = 720
    angles = -np.pi + np.arange(beams) * (2 * np.pi / beams) + np.radians(45.0)
    ranges = 2.0 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    source = cr.LaserScan(ranges, angle_min=-np.pi, angle_increment=2 * np.pi / beams, range_max=30.0)
    result = cr.register(source, target)
    assert result.status == "ambiguous", result
    assert len(result.alternatives) == 2
    yaws = [np.arctan2(t[1, 0], t[0, 0]) for t, _ in result.alternatives]
    for yaw in yaws:
        assert abs(np.remainder(yaw - np.pi / 4 + np.pi / 4, np.pi / 2) - np.pi / 4) < 0.02, yaws
    assert abs(np.remainder(yaws[0] - yaws[1] + np.pi, 2 * np.pi) - np.pi) > 1.0, yaws  # distinct turns
    assert cr.register(s_run.log[2], s_run.log[0]).alternatives == []  # converged: none


def test_people_walking_about_never_make_a_converged_answer_wrong():
    # Ten people about an S-bend, scans 1 m apart: some pairs are declined, none is answered wrong.
    run = cr.simulate(path="S", rate=1.0, speed=1.0, seed=3, people=10)
    answered = 0
    for k in range(len(run.log) - 1):
        result = cr.register(run.log[k + 1], run.log[k])
        if result.converged:
            answered += 1
            error_m, error_rad = pose_error(result.pose, true_motion(run, k, k + 1))
            assert error_m < 0.1 and error_rad < np.radians(2.0), (k, result)
    assert answered >= 0.8 * (len(run.log) - 1)
    with pytest.raises(ValueError, match="people"):
        cr.simulate(people=-1)
