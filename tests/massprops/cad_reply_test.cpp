// The parent's decoder of the CAD reader's reply (cad_reply.h): a real reply decodes into the
// solid it describes, and every truncation and mutation of it is a clear MeshFileError or a
// result, never a crash, an overrun or a huge allocation (run under the sanitizers in CI).

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "io/cad_reply.h"
#include "io/wire.h"
#include "massprops/mass_properties.h"

namespace massprops {
namespace {

// One message of the plugin, framed as the child frames it.
void Frame(wire::Writer& out, const std::string& message) {
  out.U64(0);
  out.Str(message);
}

// A reply for a file in inches holding one part: the tetrahedron (0,0,0), (a,0,0), (0,a,0),
// (0,0,a) with a = 25.4 mm, its exact integrals, and one overlap in the interference report.
std::string TetrahedronReply(std::uint64_t status = 0) {
  const double a = 25.4, v = a * a * a / 6;
  wire::Writer result;
  result.Str("STEP");
  result.Str("INCH");
  result.F64(25.4);
  result.U64(1);
  result.Str("a product left out");
  result.U64(1);  // parts
  result.Str("tet");
  result.Str("tet:1");
  result.Str("steel");
  result.Str("INCH");  // the part's own declared unit
  result.F64(7850);
  result.U64(1);  // solids
  result.F64(v);
  for (double c : {a / 4, a / 4, a / 4}) result.F64(c);
  for (int k = 0; k < 9; ++k) result.F64(k % 4 == 0 ? v * a * a / 10 : 0.0);  // not a real tensor: only carried
  result.F64(1e-15);                                                          // error
  result.F64(a * a * (1.5 + std::sqrt(3.0) / 2));                             // area
  result.F64(0.01);                                                           // deflection
  result.U64(0);
  result.U64(0);
  result.U64(1);
  result.Str("1 solid was inside out: turned outward");
  result.U64(1);  // the file's volume
  result.F64(v);
  for (double c : {0.0, 0.0, 0.0}) result.F64(c);
  result.F64(0);
  const std::vector<double> xyz = {0, 0, 0, a, 0, 0, 0, a, 0, 0, 0, a};
  const std::vector<std::int32_t> tris = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  result.U64(4);
  result.F64s(xyz.data(), xyz.size());
  result.U64(4);
  result.I32s(tris.data(), tris.size());
  wire::Writer interference;
  interference.U64(1);
  interference.U64(1);
  interference.U64(1);
  interference.U64(0);
  interference.U64(0);
  interference.F64(25.4 * 25.4 * 25.4);
  wire::Writer reply;
  if (status == 0) {
    Frame(reply, result.bytes());
    Frame(reply, interference.bytes());
  } else {
    wire::Writer refusal;
    refusal.Str("OpenCASCADE could not parse it");
    Frame(reply, refusal.bytes());
  }
  reply.U64(1);
  reply.U64(status);
  return reply.bytes();
}

TEST(CadReply, ARealReplyDecodesIntoItsSolidInTheFilesUnit) {
  const auto mesh = internal::DecodeCadReply("part.step", false, TetrahedronReply(), "");
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->declared_unit, LengthUnit::kInch);
  ASSERT_EQ(mesh->cad_parts.size(), 1u);
  const CadPart& p = mesh->cad_parts[0];
  EXPECT_EQ(p.instance, "tet:1");
  EXPECT_EQ(p.unit, "INCH");
  EXPECT_EQ(p.density, 7850);
  EXPECT_NEAR(p.brep.volume, 1.0 / 6, 1e-15);  // one cubic inch over six
  EXPECT_NEAR(p.brep.first[0], 1.0 / 24, 1e-15);
  ASSERT_TRUE(p.file.volume);
  EXPECT_NEAR(*p.file.volume, 1.0 / 6, 1e-15);
  EXPECT_EQ(p.fixes.size(), 1u);
  EXPECT_EQ(mesh->cad_notes.size(), 1u);
  // The check mesh: the same tetrahedron, outward, in inches.
  const VolumeIntegrals mi = IntegratePolygons(mesh->mesh);
  EXPECT_NEAR(mi.volume, 1.0 / 6, 1e-15);
  ASSERT_TRUE(mesh->cad_interference.done);
  ASSERT_EQ(mesh->cad_interference.overlaps.size(), 1u);
  EXPECT_NEAR(mesh->cad_interference.overlaps[0].volume, 1.0, 1e-12);  // one cubic inch
}

TEST(CadReply, ARefusalIsTheFilesMessage) {
  try {
    internal::DecodeCadReply("part.step", false, TetrahedronReply(1), "");
    FAIL() << "a refusal decoded";
  } catch (const MeshFileError& e) {
    EXPECT_EQ(std::string(e.what()), "part.step: OpenCASCADE could not parse it");
  }
}

TEST(CadReply, AResultWithoutItsInterferenceReportSaysWhy) {
  std::string reply = TetrahedronReply();
  // The child stopped during the interference test: only the result's frame came.
  wire::Reader r(reply);
  r.U64();
  const std::string first = r.Str();
  wire::Writer cut;
  Frame(cut, first);
  const auto mesh = internal::DecodeCadReply("part.step", false, cut.bytes(), "stopped after 2 s");
  ASSERT_TRUE(mesh);
  EXPECT_FALSE(mesh->cad_interference.done);
  EXPECT_EQ(mesh->cad_interference.not_done, "stopped after 2 s");
}

// Decodes, or refuses with a MeshFileError; anything else fails the test (and a crash the run).
void Survives(const std::string& bytes, const std::string& what) {
  try {
    internal::DecodeCadReply("part.step", false, bytes, "");
  } catch (const MeshFileError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": " << e.what();
  }
}

TEST(CadReply, EveryTruncationAndMutationIsAnAnswerOrAClearError) {
  const std::string reply = TetrahedronReply();
  for (std::size_t n = 0; n < reply.size(); ++n) Survives(reply.substr(0, n), "cut at " + std::to_string(n));
  std::mt19937_64 rng(46);
  for (int trial = 0; trial < 20000; ++trial) {
    std::string m = reply;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) {
      const std::size_t at = rng() % m.size();
      switch (rng() % 4) {
        case 0: m[at] = static_cast<char>(rng()); break;
        case 1: m[at] ^= static_cast<char>(1 << (rng() % 8)); break;
        case 2: m[at] = static_cast<char>(0xff); break;  // huge counts and NaNs
        default: m.erase(at, 1 + rng() % 16); break;
      }
      if (m.empty()) m = "x";
    }
    Survives(m, "mutation " + std::to_string(trial));
  }
}

}  // namespace
}  // namespace massprops
