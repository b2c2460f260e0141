// The definitions of massprops/solids.h: tessellations of simple solids and their closed-form mass
// properties, shared by tests, benchmarks and apps.

#include "massprops/solids.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace massprops::solids {
namespace {

void Require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

// Closed surface of revolution about z. `profile` runs from the bottom to the top as (ρ, z)
// pairs; a point with ρ = 0 becomes a single pole vertex. `m` segments around the axis.
TriangleMesh Revolve(const std::vector<std::pair<double, double>>& profile, int m) {
  std::vector<Vector3> verts;
  std::vector<std::array<std::int32_t, 3>> tris;
  std::vector<std::vector<std::int32_t>> rings;
  for (const auto& [rho, z] : profile) {
    std::vector<std::int32_t> ring(static_cast<std::size_t>(m));
    if (rho == 0.0) {
      std::fill(ring.begin(), ring.end(), static_cast<std::int32_t>(verts.size()));
      verts.emplace_back(0.0, 0.0, z);
    } else {
      for (int j = 0; j < m; ++j) {
        const double phi = 2.0 * kPi * j / m;
        ring[static_cast<std::size_t>(j)] = static_cast<std::int32_t>(verts.size());
        verts.emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);
      }
    }
    rings.push_back(std::move(ring));
  }
  for (std::size_t i = 0; i + 1 < rings.size(); ++i) {
    const auto& lo = rings[i];
    const auto& hi = rings[i + 1];
    for (int j = 0; j < m; ++j) {
      const auto j0 = static_cast<std::size_t>(j), j1 = static_cast<std::size_t>((j + 1) % m);
      // Quad (lo j, lo j+1, hi j+1, hi j): e_φ × e_z points outward. Skip collapsed halves.
      if (lo[j0] != lo[j1]) tris.push_back({lo[j0], lo[j1], hi[j1]});
      if (hi[j0] != hi[j1]) tris.push_back({lo[j0], hi[j1], hi[j0]});
    }
  }
  TriangleMesh out;
  out.V.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (std::size_t i = 0; i < verts.size(); ++i) out.V.row(static_cast<Eigen::Index>(i)) = verts[i];
  out.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) {
    out.F.row(static_cast<Eigen::Index>(i)) << tris[i][0], tris[i][1], tris[i][2];
  }
  return out;
}

// Profile of a half circle of radius r centred at z = zc, from angle t0 to t1 (0 = bottom pole,
// π = top pole), in `bands` steps; the endpoint is included.
void AppendArc(std::vector<std::pair<double, double>>& profile, double r, double zc, double t0, double t1, int bands,
               bool include_first) {
  for (int k = include_first ? 0 : 1; k <= bands; ++k) {
    const double t = t0 + (t1 - t0) * k / bands;
    // Exact poles and equator avoid stray round-off in ρ.
    const bool pole = (k == 0 && t0 == 0.0) || (k == bands && t1 == kPi);
    const double rho = pole ? 0.0 : r * std::sin(t);
    profile.emplace_back(rho, zc - r * std::cos(t));
  }
}

MassProperties Make(double volume, double density, const Vector3& diag, double area) {
  MassProperties mp;
  mp.volume = volume;
  mp.density = density;
  mp.mass = density * volume;
  mp.inertia_com = (mp.mass * diag).asDiagonal();
  mp.surface_area = area;
  return mp;
}

}  // namespace

PolygonMesh Box(const Vector3& size) {
  Require(size.allFinite() && (size.array() > 0).all(), "Box: edge lengths must be positive");
  PolygonMesh out;
  out.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    out.V.row(i) << ((i & 1) ? 0.5 : -0.5) * size[0], ((i & 2) ? 0.5 : -0.5) * size[1],
        ((i & 4) ? 0.5 : -0.5) * size[2];
  }
  const int faces[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  for (const auto& f : faces) out.AddFace(f);
  return out;
}

TriangleMesh Tetrahedron(const Vector3& p0, const Vector3& p1, const Vector3& p2, const Vector3& p3) {
  TriangleMesh out;
  out.V.resize(4, 3);
  out.V << p0.transpose(), p1.transpose(), p2.transpose(), p3.transpose();
  out.F.resize(4, 3);
  out.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  if ((p1 - p0).dot((p2 - p0).cross(p3 - p0)) < 0) out.F.col(1).swap(out.F.col(2));
  return out;
}

TriangleMesh RegularTetrahedron(Scalar edge) {
  Require(edge > 0 && std::isfinite(edge), "RegularTetrahedron: edge must be positive");
  const double s = edge / (2.0 * std::sqrt(2.0));
  return Tetrahedron(Vector3(s, s, s), Vector3(s, -s, -s), Vector3(-s, s, -s), Vector3(-s, -s, s));
}

TriangleMesh Octahedron(Scalar a) {
  Require(a > 0 && std::isfinite(a), "Octahedron: size must be positive");
  TriangleMesh out;
  out.V.resize(6, 3);
  out.V << a, 0, 0, -a, 0, 0, 0, a, 0, 0, -a, 0, 0, 0, a, 0, 0, -a;
  out.F.resize(8, 3);
  int t = 0;
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz, ++t) {
        const int x = sx, y = 2 + sy, z = 4 + sz;  // index 0/2/4 = positive, +1 = negative
        if ((sx + sy + sz) % 2 == 0) {
          out.F.row(t) << x, y, z;
        } else {
          out.F.row(t) << x, z, y;
        }
      }
    }
  }
  return out;
}

PolygonMesh RegularPrism(int n, Scalar r, Scalar h) {
  Require(n >= 3 && r > 0 && h > 0, "RegularPrism: needs n >= 3, r > 0, h > 0");
  PolygonMesh out;
  out.V.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const double phi = 2.0 * kPi * k / n;
    out.V.row(k) << r * std::cos(phi), r * std::sin(phi), -0.5 * h;
    out.V.row(n + k) << r * std::cos(phi), r * std::sin(phi), 0.5 * h;
  }
  std::vector<int> bottom, top;
  for (int k = 0; k < n; ++k) {
    bottom.push_back(n - 1 - k);
    top.push_back(n + k);
  }
  out.AddFace(bottom);
  out.AddFace(top);
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    out.AddFace(std::array<int, 4>{k, k1, n + k1, n + k});
  }
  return out;
}

TriangleMesh Sphere(Scalar r, int n) {
  Require(r > 0 && n >= 2, "Sphere: needs r > 0 and n >= 2");
  std::vector<std::pair<double, double>> profile;
  AppendArc(profile, r, 0.0, 0.0, kPi, n, true);
  return Revolve(profile, 2 * n);
}

TriangleMesh Ellipsoid(const Vector3& semi_axes, int n) {
  Require((semi_axes.array() > 0).all(), "Ellipsoid: semi-axes must be positive");
  TriangleMesh mesh = Sphere(1.0, n);
  mesh.V = mesh.V * semi_axes.asDiagonal();
  return mesh;
}

TriangleMesh Cylinder(Scalar r, Scalar h, int n) {
  Require(r > 0 && h > 0 && n >= 2, "Cylinder: needs r > 0, h > 0, n >= 2");
  return Revolve({{0.0, -0.5 * h}, {r, -0.5 * h}, {r, 0.5 * h}, {0.0, 0.5 * h}}, 2 * n);
}

TriangleMesh Cone(Scalar r, Scalar h, int n) {
  Require(r > 0 && h > 0 && n >= 2, "Cone: needs r > 0, h > 0, n >= 2");
  return Revolve({{0.0, -0.25 * h}, {r, -0.25 * h}, {0.0, 0.75 * h}}, 2 * n);
}

TriangleMesh Torus(Scalar R, Scalar a, int n) {
  Require(a > 0 && R > a && n >= 3, "Torus: needs R > a > 0 and n >= 3");
  const int nu = 2 * n, nv = n;
  TriangleMesh out;
  out.V.resize(nu * nv, 3);
  out.F.resize(2 * nu * nv, 3);
  for (int i = 0; i < nu; ++i) {
    const double u = 2.0 * kPi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2.0 * kPi * j / nv;
      const double rho = R + a * std::cos(v);
      out.V.row(i * nv + j) << rho * std::cos(u), rho * std::sin(u), a * std::sin(v);
    }
  }
  int t = 0;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const int p00 = i * nv + j, p10 = ((i + 1) % nu) * nv + j;
      const int p01 = i * nv + (j + 1) % nv, p11 = ((i + 1) % nu) * nv + (j + 1) % nv;
      out.F.row(t++) << p00, p10, p11;
      out.F.row(t++) << p00, p11, p01;
    }
  }
  return out;
}

TriangleMesh Capsule(Scalar r, Scalar h, int n) {
  Require(r > 0 && h > 0 && n >= 2, "Capsule: needs r > 0, h > 0, n >= 2");
  const int bands = std::max(1, n / 2);
  std::vector<std::pair<double, double>> profile;
  AppendArc(profile, r, -0.5 * h, 0.0, 0.5 * kPi, bands, true);
  AppendArc(profile, r, 0.5 * h, 0.5 * kPi, kPi, bands, true);
  return Revolve(profile, 2 * n);
}

TriangleMesh HollowSphere(Scalar R, Scalar r, int n) {
  Require(R > r && r > 0, "HollowSphere: needs R > r > 0");
  TriangleMesh outer = Sphere(R, n), inner = Sphere(r, n);
  TriangleMesh out;
  out.V.resize(outer.V.rows() + inner.V.rows(), 3);
  out.V << outer.V, inner.V;
  out.F.resize(outer.F.rows() + inner.F.rows(), 3);
  FaceMatrix flipped = inner.F.array() + static_cast<std::int32_t>(outer.V.rows());
  flipped.col(1).swap(flipped.col(2));
  out.F << outer.F, flipped;
  return out;
}

// ---- closed forms ----

MassProperties BoxProperties(const Vector3& s, Scalar rho) {
  const Vector3 sq = s.cwiseProduct(s);
  return Make(s.prod(), rho, Vector3(sq[1] + sq[2], sq[0] + sq[2], sq[0] + sq[1]) / 12.0,
              2.0 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]));
}

MassProperties RegularTetrahedronProperties(Scalar a, Scalar rho) {
  return Make(a * a * a / (6.0 * std::sqrt(2.0)), rho, Vector3::Constant(a * a / 20.0), std::sqrt(3.0) * a * a);
}

MassProperties OctahedronProperties(Scalar a, Scalar rho) {
  return Make(4.0 / 3.0 * a * a * a, rho, Vector3::Constant(a * a / 5.0), 4.0 * std::sqrt(3.0) * a * a);
}

MassProperties RegularPrismProperties(int n, Scalar r, Scalar h, Scalar rho) {
  const double theta = 2.0 * kPi / n;
  const double area = 0.5 * n * r * r * std::sin(theta);
  const double polar = r * r * (2.0 + std::cos(theta)) / 6.0;  // per unit mass, about the axis
  return Make(area * h, rho, Vector3(0.5 * polar + h * h / 12.0, 0.5 * polar + h * h / 12.0, polar),
              2.0 * area + n * 2.0 * r * std::sin(kPi / n) * h);
}

MassProperties SphereProperties(Scalar r, Scalar rho) {
  return Make(4.0 / 3.0 * kPi * r * r * r, rho, Vector3::Constant(0.4 * r * r), 4.0 * kPi * r * r);
}

MassProperties EllipsoidProperties(const Vector3& s, Scalar rho) {
  // Surface area through Legendre's form (a >= b >= c): S = 2πc² + 2πab/sinφ·(E(φ,k) sin²φ +
  // F(φ,k) cos²φ), cos φ = c/a, k² = a²(b²−c²)/(b²(a²−c²)).
  Vector3 d = s;
  std::sort(d.data(), d.data() + 3, std::greater<>());
  const double a = d[0], b = d[1], c = d[2];
  double area;
  if (a == c) {
    area = 4.0 * kPi * a * a;
  } else {
    const double phi = std::acos(c / a);
    const double k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
    const double sp = std::sin(phi), cp = std::cos(phi);
    area = 2.0 * kPi * c * c +
           2.0 * kPi * a * b / sp * (std::ellint_2(k, phi) * sp * sp + std::ellint_1(k, phi) * cp * cp);
  }
  const Vector3 q = s.cwiseProduct(s);
  return Make(4.0 / 3.0 * kPi * s.prod(), rho, Vector3(q[1] + q[2], q[0] + q[2], q[0] + q[1]) / 5.0, area);
}

MassProperties CylinderProperties(Scalar r, Scalar h, Scalar rho) {
  const double t = (3.0 * r * r + h * h) / 12.0;
  return Make(kPi * r * r * h, rho, Vector3(t, t, 0.5 * r * r), 2.0 * kPi * r * (r + h));
}

MassProperties ConeProperties(Scalar r, Scalar h, Scalar rho) {
  const double t = 3.0 / 20.0 * r * r + 3.0 / 80.0 * h * h;
  return Make(kPi * r * r * h / 3.0, rho, Vector3(t, t, 0.3 * r * r), kPi * r * r + kPi * r * std::sqrt(r * r + h * h));
}

MassProperties TorusProperties(Scalar R, Scalar a, Scalar rho) {
  const double t = 0.5 * R * R + 5.0 / 8.0 * a * a;
  return Make(2.0 * kPi * kPi * R * a * a, rho, Vector3(t, t, R * R + 0.75 * a * a), 4.0 * kPi * kPi * R * a);
}

MassProperties CapsuleProperties(Scalar r, Scalar h, Scalar rho) {
  // Cylinder plus two hemispheres; a hemisphere's center of mass is 3r/8 from its flat face and
  // its transverse inertia about that point is 83/320·m r².
  const double vc = kPi * r * r * h, vh = 2.0 / 3.0 * kPi * r * r * r;
  const double d = 0.5 * h + 3.0 / 8.0 * r;
  const double Ixx = vc * (3.0 * r * r + h * h) / 12.0 + 2.0 * vh * (83.0 / 320.0 * r * r + d * d);
  const double Izz = vc * r * r / 2.0 + 2.0 * vh * 0.4 * r * r;
  const double v = vc + 2.0 * vh;
  return Make(v, rho, Vector3(Ixx, Ixx, Izz) / v, 4.0 * kPi * r * r + 2.0 * kPi * r * h);
}

MassProperties HollowSphereProperties(Scalar R, Scalar r, Scalar rho) {
  const double R3 = R * R * R, r3 = r * r * r;
  const double k = 0.4 * (R3 * R * R - r3 * r * r) / (R3 - r3);
  return Make(4.0 / 3.0 * kPi * (R3 - r3), rho, Vector3::Constant(k), 4.0 * kPi * (R * R + r * r));
}

}  // namespace massprops::solids
