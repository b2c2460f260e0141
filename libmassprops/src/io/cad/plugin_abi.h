#pragma once
// The CAD plugin's C interface (libmassprops_cad.so): what the loader (cad_loader.cpp) and the
// plugin (io/cad/, the only translation units that include OpenCASCADE) agree on.

#include <cstddef>

extern "C" {

/// Bumped whenever the options or the messages' layout change: a plugin of another build is refused.
#define MASSPROPS_CAD_ABI 4

enum MasspropsCadFormat { kMasspropsCadStep = 0, kMasspropsCadIges = 1, kMasspropsCadBrep = 2 };

struct MasspropsCadOptions {
  int abi;            ///< MASSPROPS_CAD_ABI
  int format;         ///< MasspropsCadFormat
  double deflection;  ///< chordal, in the file's unit; 0: relative_deflection × the part's diagonal
  double relative_deflection;
  double angular_deflection;  ///< rad
  double brep_tolerance;      ///< relative error target of the B-rep integration
  /// How many pairs of solids whose boxes overlap get their exact common volume computed (a count,
  /// not a time, so that the output does not depend on the machine); 0: none.
  int interference_pairs;
  /// Threads for meshing and integrating the parts (0: every core, 1: one); the same triangles
  /// and the same bits for any count.
  int threads;
};

/// Hands one message (wire.h layout, described in cad/plugin.cpp) to the loader.
typedef void (*MasspropsCadSendFn)(void* context, const char* bytes, std::size_t size);

/// Reads `path` and sends its messages through `send`: 0 after the result and then the
/// interference report (two messages, the result first so that it survives a slow boolean); 1
/// after one message holding only the reason it refuses the file.
typedef int (*MasspropsCadReadFn)(const char* path, const MasspropsCadOptions* options, MasspropsCadSendFn send,
                                  void* context);
}
