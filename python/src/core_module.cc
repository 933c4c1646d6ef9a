// mrsim._core: the compiled half of the `mrsim` package.
#include <pybind11/pybind11.h>

#include "lcmtypes/runtime/version.h"
#include "python/src/bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "mrsim's C++ libraries for Python: scenarios, the MuJoCo simulation, "
      "gaits, episodes, logs and LCM messages. Use it through the `mrsim` "
      "package.";
  m.attr("__version__") = mrsim::ProjectVersion();
  mrsim::python::BindErrors(m);
  mrsim::python::BindScenario(m);
  mrsim::python::BindState(m);
  mrsim::python::BindGait(m);
  mrsim::python::BindSimulation(m);
  mrsim::python::BindLcm(m);
  mrsim::python::BindLogs(m);
  mrsim::python::BindEpisode(m);
  mrsim::python::BindOptimizer(m);
}
