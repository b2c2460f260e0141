#pragma once
// `massprops validate`: the closed-form solids tessellated at a series of resolutions, integrated
// by both paths, against their closed forms, with the observed order of convergence
// (massprops/validation.h computes; this prints and plots).

namespace massprops::cli {

int ValidateMain(int argc, char** argv);

}  // namespace massprops::cli
