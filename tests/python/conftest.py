"""Shared fixtures of the Python module's tests: the bundled log, the command-line tool, a simulated run."""
import os
import pathlib

import pytest

import contour_reg as cr

SOURCE_DIR = pathlib.Path(os.environ.get("CONTOUR_REG_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
BUNDLED_LOG = SOURCE_DIR / "data" / "office" / "L-hokuyo-2hz.clf"
BUNDLED_GT = SOURCE_DIR / "data" / "office" / "L-hokuyo-2hz.gt.tum"


@pytest.fixture(scope="session")
def bundled_log():
    return cr.read_log(str(BUNDLED_LOG))


@pytest.fixture(scope="session")
def tool():
    """The contour_reg command-line tool of the same build (ctest sets CONTOUR_REG_TOOL)."""
    path = os.environ.get("CONTOUR_REG_TOOL")
    if not path:
        pytest.skip("CONTOUR_REG_TOOL is not set (ctest sets it)")
    return path


@pytest.fixture(scope="session")
def s_run():
    """The S path through the built-in office at 5 Hz, stop-and-go: scans 0.1 m apart with ground truth."""
    return cr.simulate(path="S", rate=5.0, seed=3)
