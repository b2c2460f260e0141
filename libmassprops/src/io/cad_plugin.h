#pragma once
// The CAD plugin's C interface (libmassprops_cad.so): what the loader (cad_loader.cpp) and the
// plugin (cad_plugin.cpp, the only translation unit that includes OpenCASCADE) agree on.

#include <cstddef>

extern "C" {

/// Bumped whenever the options or the result's layout change: a plugin of another build is refused.
#define MASSPROPS_CAD_ABI 2

enum MasspropsCadFormat { kMasspropsCadStep = 0, kMasspropsCadIges = 1, kMasspropsCadBrep = 2 };

struct MasspropsCadOptions {
  int abi;            ///< MASSPROPS_CAD_ABI
  int format;         ///< MasspropsCadFormat
  double deflection;  ///< chordal, in the file's unit; 0: relative_deflection × the part's diagonal
  double relative_deflection;
  double angular_deflection;  ///< rad
  double brep_tolerance;      ///< relative error target of the B-rep integration
};

/// Reads `path`; returns 0 with the result in `*out` (wire.h layout, described in cad_plugin.cpp),
/// or 1 with a message as its only string. `*out` is malloc'ed: free it with massprops_cad_free.
typedef int (*MasspropsCadReadFn)(const char* path, const MasspropsCadOptions* options, char** out,
                                  std::size_t* out_size);
typedef void (*MasspropsCadFreeFn)(void* p);
}
