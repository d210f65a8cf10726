// The evaluation metrics (end point, drift, ATE, relation errors) and planar pose helpers.
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "bindings.h"
#include "contour_reg/evaluation/closure.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"

namespace contour_reg::python {

namespace {

std::vector<io::Relation> relationsOf(const py::handle &array) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != 5)
    throw py::value_error("relations must be an N x 5 array (t1 s, t2 s, x m, y m, yaw rad), as read_relations()");
  const auto v = a.unchecked<2>();
  std::vector<io::Relation> relations(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t n = 0; n < v.shape(0); ++n) {
    if (!std::isfinite(v(n, 0) + v(n, 1) + v(n, 2) + v(n, 3) + v(n, 4)))
      throw py::value_error("relations must be finite: row " + std::to_string(n) + " is not");
    relations[n] = {v(n, 0), v(n, 1), {v(n, 2), v(n, 3), v(n, 4)}};
  }
  return relations;
}

py::dict relationDict(const evaluation::RelationErrors &r) {
  py::dict d;
  d["count"] = r.count;
  d["missing"] = r.missing;
  d["translation_mean_m"] = r.translation_mean;
  d["translation_std_m"] = r.translation_std;
  d["rotation_mean_deg"] = r.rotation_mean;
  d["rotation_std_deg"] = r.rotation_std;
  return d;
}

py::dict evaluateTrajectory(const py::handle &estimate, const py::object &ground_truth, const py::object &relations,
                            double local_dt) {
  if (!(local_dt > 0.0)) throw py::value_error("local_dt must be > 0 s");
  const io::Trajectory est = trajectoryOf(estimate, "estimate");
  io::Trajectory gt;
  std::vector<io::Relation> rel;
  if (!ground_truth.is_none()) gt = trajectoryOf(ground_truth, "ground_truth");
  if (!relations.is_none()) rel = relationsOf(relations);
  const evaluation::Evaluation e =
      evaluation::evaluate(est, ground_truth.is_none() ? nullptr : &gt, relations.is_none() ? nullptr : &rel, local_dt);
  py::dict d;
  d["estimate_poses"] = e.estimate_poses;
  d["matched_poses"] = e.matched_poses;
  d["estimate_stamps_not_increasing"] = e.estimate_stamps_not_increasing;
  d["ground_truth_stamps_not_increasing"] = e.ground_truth_stamps_not_increasing;
  if (e.end_point) {
    d["end_point_percent"] = e.end_point->percent;
    d["end_point_m"] = e.end_point->error;
    d["path_length_m"] = e.end_point->path_length;
  }
  if (e.drift) d["drift_percent"] = e.drift->mean_percent;
  if (e.ate) d["ate_m"] = *e.ate;
  if (e.relations_all) d["relations_all"] = relationDict(*e.relations_all);
  if (e.relations_local) d["relations_local"] = relationDict(*e.relations_local);
  return d;
}

io::Pose2D poseOf(const py::handle &pose) {
  const auto p = pose.cast<std::vector<double>>();
  if (p.size() != 3 || !std::isfinite(p[0] + p[1] + p[2]))
    throw py::value_error("a pose is (x m, y m, yaw rad), finite");
  return {p[0], p[1], p[2]};
}

py::tuple poseTuple(const io::Pose2D &p) { return py::make_tuple(p.x, p.y, p.yaw); }

}  // namespace

void bindEvaluation(py::module_ &m) {
  m.def("evaluate", &evaluateTrajectory, py::arg("estimate"), py::arg("ground_truth") = py::none(),
        py::arg("relations") = py::none(), py::arg("local_dt") = 5.0,
        "Every metric the references allow, as a dict. With ground_truth (N x 4): end_point_percent (the paper's "
        "end-point error over path length), end_point_m, path_length_m, drift_percent (over 10 m windows), ate_m. "
        "With relations (N x 5): relations_all and relations_local (|t2 - t1| <= local_dt s), each with count, "
        "missing, translation_mean_m, translation_std_m, rotation_mean_deg, rotation_std_deg. A metric the "
        "references do not cover is absent, and so is every metric where the estimate's stamps do not increase, "
        "and every ground-truth metric where the ground truth's do not (estimate_stamps_not_increasing, "
        "ground_truth_stamps_not_increasing count those stamps).");
  m.def(
      "relation_errors",
      [](const py::handle &estimate, const py::handle &relations, double max_dt) {
        if (!(max_dt > 0.0)) throw py::value_error("max_dt must be > 0 s (inf: every relation)");
        return relationDict(
            evaluation::relationErrors(trajectoryOf(estimate, "estimate"), relationsOf(relations), max_dt));
      },
      py::arg("estimate"), py::arg("relations"), py::arg("max_dt") = std::numeric_limits<double>::infinity(),
      "Relation errors (Kümmerle et al. 2009) of the relations at most max_dt s apart, as a dict.");
  m.def(
      "normalised_error_squared",
      [](const py::handle &estimate, const py::handle &reference, const py::handle &covariance,
         std::pair<double, double> reference_sigma) {
        if (!(reference_sigma.first >= 0.0 && reference_sigma.second >= 0.0))
          throw py::value_error("reference_sigma must be (m, deg), both >= 0");
        return evaluation::normalisedErrorSquared(poseOf(estimate), poseOf(reference),
                                                  matrixOf(covariance, "covariance"), reference_sigma.first,
                                                  reference_sigma.second * M_PI / 180.0);
      },
      py::arg("estimate"), py::arg("reference"), py::arg("covariance"),
      py::arg("reference_sigma") = std::make_pair(0.02, 0.5),
      "NEES of an estimated motion (x, y, yaw) against a reference one under its 3 x 3 covariance, with the "
      "reference's own error (m, deg) added: 3 on average for an honest covariance, above 11.34 for 1 % of them.");
  m.def(
      "triangle_closure",
      [](const py::handle &ab, const py::handle &ab_covariance, const py::handle &bc, const py::handle &bc_covariance,
         const py::handle &ac, const py::handle &ac_covariance) {
        const evaluation::TriangleClosure closure = evaluation::triangleClosure(
            poseOf(ab), matrixOf(ab_covariance, "ab_covariance"), poseOf(bc), matrixOf(bc_covariance, "bc_covariance"),
            poseOf(ac), matrixOf(ac_covariance, "ac_covariance"));
        py::dict out;
        out["error"] = py::make_tuple(closure.error(0), closure.error(1), closure.error(2));
        out["covariance"] = matrixArray(closure.covariance);
        out["nees"] = closure.nees;
        return out;
      },
      py::arg("ab"), py::arg("ab_covariance"), py::arg("bc"), py::arg("bc_covariance"), py::arg("ac"),
      py::arg("ac_covariance"),
      "A covariance check without a reference: motions ab (scan b in a's frame), bc and ac with their 3 x 3 "
      "covariances compose to the identity, ac^-1 ab bc; its departure (error: x, y, yaw), the covariance carried "
      "through the composition and the NEES, chi-square with 3 degrees of freedom for honest covariances "
      "(docs/reliability.md), as a dict.");
  m.def(
      "relative_pose",
      [](const py::handle &a, const py::handle &b) { return poseTuple(io::between(poseOf(a), poseOf(b))); },
      py::arg("a"), py::arg("b"), "Pose b in the frame of pose a, (x, y, yaw).");
  m.def(
      "pose_matrix", [](const py::handle &pose) { return matrixArray(io::toMatrix(poseOf(pose))); }, py::arg("pose"),
      "The 3 x 3 homogeneous transform of a pose (x, y, yaw).");
  m.def(
      "matrix_pose", [](const py::handle &matrix) { return poseTuple(io::toPose(rigidMatrixOf(matrix, "matrix"))); },
      py::arg("matrix"), "The pose (x, y, yaw) of a 3 x 3 homogeneous transform.");
}

}  // namespace contour_reg::python
