#pragma once
// What the CAD reader's child process sends, decoded in the parent (cad_loader.cpp). The child is
// this build's own code, but it may die mid-message, and whatever it sent must never take the
// parent down: every count is checked against the bytes left, every number and index is checked
// before it is used (tests/massprops/cad_reply_test.cpp mutates real replies).
//
// The child frames the plugin's messages: tag 0 and the message (wire.h string) for each, then
// tag 1 and the plugin's status. The messages are those of io/cad/plugin.cpp.

#include <optional>
#include <string>
#include <string_view>

#include "massprops/io/mesh_io.h"

namespace massprops::internal {

/// The parts of a CAD reply, or nothing when no whole result came (the child crashed or was
/// stopped before it: the caller words that). `stopped` says why the child did not finish ("" when
/// it did): a result without its interference report says so there.
/// @throws MeshFileError naming `path` for a refusal sent by the plugin, or a malformed result.
std::optional<LoadedMesh> DecodeCadReply(const std::string& path, bool brep_format, std::string_view bytes,
                                         const std::string& stopped);

}  // namespace massprops::internal
