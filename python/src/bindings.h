// The parts of the mrsim._core extension module, each binding one area of
// the C++ libraries; core_module.cc calls them in dependency order.
#pragma once

#include <pybind11/pybind11.h>

namespace mrsim::python {

void BindErrors(pybind11::module_& m);
void BindScenario(pybind11::module_& m);
void BindState(pybind11::module_& m);
void BindGait(pybind11::module_& m);
void BindSimulation(pybind11::module_& m);
void BindLcm(pybind11::module_& m);
void BindLogs(pybind11::module_& m);
void BindEpisode(pybind11::module_& m);
void BindOptimizer(pybind11::module_& m);

}  // namespace mrsim::python
