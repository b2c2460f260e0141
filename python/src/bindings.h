#pragma once
// What the compiled module's files share: the keyword arguments → LoadOptions mapping and the
// Python wording of messages (module.cpp), and the binding of each further part.

#include <pybind11/pybind11.h>

#include "massprops/load.h"

namespace massprops_python {

/// Every keyword checked (a misspelt one is a TypeError, a bad value a ValueError naming it).
massprops::LoadOptions LoadOptionsFrom(const pybind11::kwargs& kw);
const massprops::Vocabulary& PythonWords();

/// massprops._core.resting_poses (poses.cpp).
void BindPoses(pybind11::module_& m);

}  // namespace massprops_python
