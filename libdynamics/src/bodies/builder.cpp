// The body builder (bodies.h): shapes to mass properties, display meshes and colliders.

#include <cstdint>
#include <string>

#include "bodies/bodies.h"
#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/repair/repair.h"
#include "massprops/text.h"

namespace dynamics {
namespace {

using massprops::MassProperties;

std::string Num(double v, const char* fmt) { return massprops::FormatDouble(v, fmt); }

// A solid from its closed form (exact mass properties) and a tessellation to look at.
BuiltShape LoadPrimitive(const massprops::Primitive& p, const massprops::MassSpec& mass) {
  BuiltShape out;
  try {
    const MassProperties unit = massprops::ClosedForm(p, 1.0);  // at density 1
    out.display = massprops::Tessellate(p, 24);
    out.mp = massprops::AtDensity(unit, massprops::ResolveDensity(mass, unit.volume));
    out.principal = massprops::ComputePrincipalInertia(out.mp.inertia_com);
  } catch (const std::exception& e) {
    throw BodyError("solid", e.what());
  }
  out.source = massprops::Describe(p);
  return out;
}

// A mesh file through massprops' pipeline, whole (the display mesh needs it). @throws BodyError.
massprops::SolidResult ReadMesh(const MeshSource& m, const BodyShape& s, const massprops::Vocabulary& words,
                                int threads, std::vector<BodyWarning>& warnings) {
  massprops::LoadOptions opt;
  opt.unit = s.unit;
  opt.unit_stated = s.unit_stated;
  opt.mass = s.mass;
  opt.repair = m.repair;
  opt.allow_open = m.allow_open;
  opt.parts = m.parts || m.part >= 0;
  opt.full_check = true;  // load the mesh whole: the display mesh needs it
  opt.num_threads = threads;
  massprops::SolidResult r;
  try {
    r = massprops::LoadSolid(m.path, opt);
  } catch (const std::exception& e) {
    throw BodyError("mesh", massprops::WordedError(e, words));
  }
  for (const auto& f : r.findings) warnings.push_back({"mesh", m.path + ": " + massprops::Worded(f.message, words)});
  return r;
}

// The body of a mesh file's result (the whole, or one of its parts).
BuiltShape FromResult(const massprops::SolidResult& r, const std::string& path) {
  if (!r.validity.valid) {
    throw BodyError("mesh", path + ": the inertia is not that of a real body (" + r.validity.reason + ")");
  }
  BuiltShape out;
  out.mp = r.mp;
  out.principal = r.principal;
  // The unit the file was read in: the stated one, else the file's own (a STEP in inches, a 3MF).
  const double scale = massprops::MetresPerUnit(r.unit);
  out.display = massprops::Triangulate(r.loaded.mesh);
  for (Eigen::Index i = 0; i < out.display.V.rows(); ++i) {
    out.display.V.row(i) = (scale * out.display.V.row(i).transpose() - r.mp.center_of_mass).transpose();
  }
  out.source = path + (r.part.empty() ? std::string() : " part '" + r.part + "'") + " (unit " +
               massprops::UnitName(r.unit) + ", " + std::to_string(out.display.F.rows()) + " triangles)";
  return out;
}

// Mass properties by quasi-Monte Carlo to a relative standard error of 1e-4, and a
// marching-tetrahedra surface to look at.
BuiltShape LoadImplicit(const ImplicitSource& i, const BodyShape& s, int threads, std::vector<BodyWarning>& warnings) {
  using namespace massprops;
  ImplicitOptions opt;
  opt.unit = s.unit;
  opt.unit_stated = s.unit_stated;
  opt.mass = s.mass;
  opt.sampling.tolerance = 1e-4;
  opt.sampling.max_samples = std::int64_t{1} << 27;
  opt.num_threads = threads;
  SolidResult r;
  try {
    r = EstimateImplicit(*i.shape, opt);
  } catch (const std::exception& ex) {
    throw BodyError("implicit", ex.what());
  }
  const MassPropertiesEstimate& e = *r.estimate;
  if (!e.tolerance_met) {
    warnings.push_back({"implicit", "mass properties known to a relative standard error of " +
                                        Num(e.MaxRelativeError(), "%.2g") + " only (" + std::to_string(e.samples) +
                                        " points)"});
  }
  BuiltShape out;
  out.mp = r.mp;
  out.principal = r.principal;
  out.display = implicit::Polygonize(*implicit::Scaled(i.shape, MetresPerUnit(s.unit)), 64);
  out.display.V.rowwise() -= out.mp.center_of_mass.transpose();
  out.source = i.text + " (unit " + UnitName(s.unit) + "; QMC, relative standard error " +
               Num(e.MaxRelativeError(), "%.1g") + ")";
  return out;
}

}  // namespace

bool CollidesAsItself(const massprops::Primitive& p) {
  namespace pr = massprops::primitive;
  return std::holds_alternative<pr::Box>(p) || std::holds_alternative<pr::Sphere>(p) ||
         std::holds_alternative<pr::Capsule>(p) || std::holds_alternative<pr::Cylinder>(p);
}

BodyBuilder::BodyBuilder(massprops::Vocabulary words, int threads) : words_(std::move(words)), threads_(threads) {}

BuiltShape BodyBuilder::LoadMeshFile(const MeshSource& m, const BodyShape& shape, std::vector<BodyWarning>& warnings) {
  const double mass = std::visit([](const auto& spec) { return spec.value; }, shape.mass);
  const std::string file_key = m.path + '\n' + massprops::UnitName(shape.unit) + (shape.unit_stated ? "!" : "") +
                               (std::holds_alternative<massprops::TotalMass>(shape.mass) ? " kg " : " kg/m3 ") +
                               massprops::FormatDouble(mass, "%.17g") + (m.repair ? " repair" : "") +
                               (m.allow_open ? " allow_open" : "") + (m.parts || m.part >= 0 ? " parts" : "");
  const std::string key = file_key + " part " + std::to_string(m.part);
  if (const auto it = files_.find(key); it != files_.end()) return it->second;
  if (m.part < 0) return files_[key] = FromResult(ReadMesh(m, shape, words_, threads_, warnings), m.path);
  std::shared_ptr<const massprops::SolidResult>& whole = assemblies_[file_key];
  if (!whole) whole = std::make_shared<const massprops::SolidResult>(ReadMesh(m, shape, words_, threads_, warnings));
  if (static_cast<std::size_t>(m.part) >= whole->parts.size()) {
    throw BodyError("mesh", m.path + ": has " + std::to_string(whole->parts.size()) + " parts; there is no part " +
                                std::to_string(m.part) + " (parts are counted from 0)");
  }
  return files_[key] = FromResult(whole->parts[static_cast<std::size_t>(m.part)], m.path);
}

BuiltShape BodyBuilder::Load(const BodyShape& shape, std::vector<BodyWarning>& warnings) {
  try {
    if (const auto* m = std::get_if<MeshSource>(&shape.source)) return LoadMeshFile(*m, shape, warnings);
    if (const auto* i = std::get_if<ImplicitSource>(&shape.source)) return LoadImplicit(*i, shape, threads_, warnings);
    return LoadPrimitive(std::get<massprops::Primitive>(shape.source), shape.mass);
  } catch (const BodyError&) {
    throw;
  } catch (const std::exception& e) {
    throw BodyError("", e.what());
  }
}

std::optional<Collider> BodyBuilder::ColliderOf(const CollisionSpec& c, const BodyShape& shape,
                                                const BuiltShape& built) {
  namespace pr = massprops::primitive;
  const massprops::Primitive* primitive = c.primitive ? &*c.primitive : nullptr;
  if (c.kind == CollisionKind::kNone) return std::nullopt;
  CollisionKind kind = c.kind;
  std::optional<massprops::PolygonMesh> hull;
  if (kind == CollisionKind::kAuto || kind == CollisionKind::kItself) {
    const bool simple = shape.solid() && CollidesAsItself(*shape.solid());
    if (simple) {
      primitive = shape.solid();
      kind = CollisionKind::kPrimitive;
    } else if (kind == CollisionKind::kAuto) {
      return std::nullopt;
    } else {  // convex: its hull is itself (the volumes agree to rounding); else its surface
      hull = massprops::ConvexHull(massprops::ToPolygonMesh(built.display));
      const double hull_volume = massprops::ComputeMassProperties(*hull, 1.0).volume;
      kind = hull_volume <= built.mp.volume * (1 + 1e-9) ? CollisionKind::kHull : CollisionKind::kMesh;
    }
  }
  Collider out;
  out.material = c.material;
  out.rotation = built.principal.axes.transpose();  // mesh axes → body axes
  if (kind == CollisionKind::kMesh) {
    // The display mesh (mesh axes, about the center of mass); equal meshes share one field.
    const massprops::TriangleMesh& m = built.display;
    const std::string key(reinterpret_cast<const char*>(m.V.data()),
                          sizeof(double) * static_cast<std::size_t>(m.V.size()));
    const std::string faces(reinterpret_cast<const char*>(m.F.data()),
                            sizeof(m.F(0, 0)) * static_cast<std::size_t>(m.F.size()));
    shape::Mesh& slot = meshes_[key + faces];
    if (slot.field == nullptr) {
      shape::Mesh mesh = MeshOf(m);
      slot = MakeMesh(std::move(mesh.vertices), std::move(mesh.triangles));
    }
    out.shape = slot;
    return out;
  }
  if (kind == CollisionKind::kHull) {
    out.shape = ConvexOf(hull ? *hull : massprops::ConvexHull(massprops::ToPolygonMesh(built.display)));
    return out;
  }
  const massprops::Primitive& p = *primitive;
  if (const auto* box = std::get_if<pr::Box>(&p)) out.shape = shape::Box{box->size / 2};
  if (const auto* sphere = std::get_if<pr::Sphere>(&p)) out.shape = shape::Sphere{sphere->radius};
  if (const auto* capsule = std::get_if<pr::Capsule>(&p))
    out.shape = shape::Capsule{capsule->radius, capsule->length / 2};
  if (const auto* cylinder = std::get_if<pr::Cylinder>(&p)) {
    out.shape = shape::Cylinder{cylinder->radius, cylinder->height / 2};
  }
  return out;
}

}  // namespace dynamics
