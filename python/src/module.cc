// The Python module contour_reg._core: the library's registration methods, readers, odometry,
// evaluation and simulator for NumPy users. contour_reg/__init__.py re-exports it.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "contour_reg/io/scan_log.h"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace contour_reg::python;
  m.doc() = "2-D LIDAR scan registration and laser odometry by contour analysis, with PCL's ICP and NDT beside it.";
  py::register_exception<contour_reg::io::ReadError>(m, "ReadError", PyExc_OSError);
  bindScans(m);
  bindRegistration(m);
  bindLogs(m);
  bindOdometry(m);
  bindEvaluation(m);
  bindSimulation(m);
}
