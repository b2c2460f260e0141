#pragma once
// What the compiled module's files share: the keyword arguments → LoadOptions mapping and the
// Python wording of messages (module.cpp), and the binding of each further part.

#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"

namespace massprops_python {

/// Every keyword checked (a misspelt one is a TypeError, a bad value a ValueError naming it).
massprops::LoadOptions LoadOptionsFrom(const pybind11::kwargs& kw);
const massprops::Vocabulary& PythonWords();
/// Classes with Python's own metaclass rather than pybind11's: what the type stubs declare.
pybind11::metaclass PlainType();
/// packages={'NAME': 'DIR'} (package://NAME/, model://NAME/ roots) as FillOptions::packages.
std::vector<std::pair<std::string, std::string>> PackagesOf(const pybind11::dict& packages);

/// Runs `work` without the GIL; a file that cannot be read becomes OSError, any other error
/// ValueError, both with the error's message worded in Python's vocabulary.
template <typename Work>
void RunWithoutGil(const Work& work) {
  std::string message;
  enum { kNone, kAccess, kValue } kind = kNone;
  {
    pybind11::gil_scoped_release release;
    try {
      work();
    } catch (const massprops::FileAccessError& e) {
      kind = kAccess;
      message = e.what();
    } catch (const std::exception& e) {  // LoadError, MeshFileError, invalid_argument, ...
      kind = kValue;
      message = massprops::WordedError(e, PythonWords());
    }
  }
  if (kind == kAccess) {
    PyErr_SetString(PyExc_OSError, message.c_str());
    throw pybind11::error_already_set();
  }
  if (kind == kValue) throw pybind11::value_error(message);
}

/// massprops._core.resting_poses (poses.cpp).
void BindPoses(pybind11::module_& m);
/// World's and ContactWorld's loops, couplings and tendons (constraints.cpp), after both are bound.
void BindConstraints(pybind11::module_& dyn);
/// massprops.dynamics.load_scene (scenes.cpp), on the dynamics submodule.
void BindScenes(pybind11::module_& dyn);
/// massprops.dynamics.drop (drop.cpp), on the dynamics submodule.
void BindDrop(pybind11::module_& dyn);

}  // namespace massprops_python
