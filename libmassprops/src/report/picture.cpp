// The picture of a mass-properties result (picture.h): the layout, the views and the SVG.

#include "massprops/report/picture.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Eigenvalues>

#include "massprops/mesh.h"
#include "massprops/monte_carlo.h"
#include "massprops/principal_axes.h"
#include "massprops/report/atomic_file.h"

namespace massprops::report {
namespace {

// More triangles than this are clustered onto a grid before they are drawn (a picture of 10^6
// sub-pixel triangles would be a 100 MB SVG that looks the same).
constexpr std::size_t kMaxDrawnTriangles = 12000;

struct View {
  const char* id;
  const char* label;
  Vector3 right, up;
  Vector3 toward() const { return right.cross(up); }  // towards the viewer
};

std::array<View, 4> Views() {
  return {View{"isometric", "isometric", Vector3(1, 1, 0).normalized(), Vector3(-1, 1, 2).normalized()},
          View{"front", "front (from -y)", Vector3::UnitX(), Vector3::UnitZ()},
          View{"top", "top (from +z)", Vector3::UnitX(), Vector3::UnitY()},
          View{"right", "right (from +x)", Vector3::UnitY(), Vector3::UnitZ()}};
}

std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '\'': out += "&apos;"; break;
      case '"': out += "&quot;"; break;
      default: out += (static_cast<unsigned char>(c) < 0x20) ? ' ' : c;
    }
  }
  return out;
}

std::string Number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

// The surface to draw, in metres: triangles with the part each came from.
struct Surface {
  std::vector<Vector3> v;
  std::vector<std::array<std::int32_t, 3>> tri;
  std::vector<std::int32_t> part;
};

Surface SurfaceOf(const SolidResult& r) {
  Surface s;
  const PolygonMesh& mesh = r.loaded.mesh;
  const double k = MetresPerUnit(r.unit);
  s.v.resize(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) s.v[static_cast<std::size_t>(i)] = k * mesh.V.row(i).transpose();
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    SplitPolygon(mesh.indices.data() + mesh.offsets[f], mesh.face_size(f), s.tri);
    const std::int32_t part =
        static_cast<std::size_t>(f) < r.loaded.face_part.size() ? r.loaded.face_part[static_cast<std::size_t>(f)] : 0;
    s.part.resize(s.tri.size(), part);
  }
  return s;
}

// Vertex clustering (Rossignac and Borrel): corners snapped to a grid's cells, each cell one
// vertex at the mean of its corners, triangles that collapse dropped. The grid is coarsened until
// at most kMaxDrawnTriangles remain.
Surface Simplified(Surface s, const Eigen::AlignedBox3d& box) {
  for (int cells = 200; s.tri.size() > kMaxDrawnTriangles && cells >= 8; cells = cells * 2 / 3) {
    const double cell = box.sizes().maxCoeff() / cells;
    if (!(cell > 0)) break;
    std::unordered_map<std::int64_t, std::int32_t> index;
    std::vector<std::int32_t> of(s.v.size());
    std::vector<Vector3> sum;
    std::vector<int> count;
    for (std::size_t i = 0; i < s.v.size(); ++i) {
      const Eigen::Vector3d c = ((s.v[i] - box.min()) / cell).array().floor();
      const std::int64_t key = (static_cast<std::int64_t>(c.x()) * 4096 + static_cast<std::int64_t>(c.y())) * 4096 +
                               static_cast<std::int64_t>(c.z());
      const auto [it, added] = index.emplace(key, static_cast<std::int32_t>(sum.size()));
      if (added) {
        sum.push_back(Vector3::Zero());
        count.push_back(0);
      }
      of[i] = it->second;
      sum[static_cast<std::size_t>(it->second)] += s.v[i];
      ++count[static_cast<std::size_t>(it->second)];
    }
    Surface out;
    for (std::size_t i = 0; i < sum.size(); ++i) out.v.push_back(sum[i] / count[i]);
    for (std::size_t t = 0; t < s.tri.size(); ++t) {
      const std::array<std::int32_t, 3> c = {of[static_cast<std::size_t>(s.tri[t][0])],
                                             of[static_cast<std::size_t>(s.tri[t][1])],
                                             of[static_cast<std::size_t>(s.tri[t][2])]};
      if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
      out.tri.push_back(c);
      out.part.push_back(s.part[t]);
    }
    s = std::move(out);
  }
  return s;
}

// The equivalent-inertia ellipsoid's semi-axes, along the principal axes.
Vector3 EllipsoidSemiAxes(const SolidResult& r) {
  const Vector3& I = r.principal.moments;
  Vector3 a;
  for (int i = 0; i < 3; ++i) {
    const double s = 5 * (I[(i + 1) % 3] + I[(i + 2) % 3] - I[i]) / (2 * r.mp.mass);
    a[i] = std::isfinite(s) && s > 0 ? std::sqrt(s) : 0;
  }
  return a;
}

// The radii of gyration √(I_i / m).
Vector3 Gyration(const SolidResult& r) {
  Vector3 k;
  for (int i = 0; i < 3; ++i) {
    const double s = r.principal.moments[i] / r.mp.mass;
    k[i] = std::isfinite(s) && s > 0 ? std::sqrt(s) : 0;
  }
  return k;
}

const char* const kPartColours[] = {"#8fb4d9", "#e3b27a", "#9ccf8f", "#d49ac4",
                                    "#b3a6e0", "#e0d47a", "#7fcfc8", "#d9a0a0"};
const char* const kAxisEnd[] = {"#ff0000", "#00c800", "#0000ff"};
const char* const kAxisLine[] = {"#a01010", "#107010", "#1010a0"};

Vector3 Rgb(const char* hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex + 1, "%2x%2x%2x", &r, &g, &b);
  return Vector3(r, g, b);
}

struct Panel {
  View view;
  double x0, y0, width, height;  // where it sits, px
  Vector3 origin;                // the world point at its center
  double scale = 1;              // px per metre (shared)
  Eigen::Vector2d Px(const Vector3& x) const {
    const Vector3 d = x - origin;
    return {x0 + width / 2 + scale * view.right.dot(d), y0 + height / 2 + 12 - scale * view.up.dot(d)};
  }
};

class Drawing {
 public:
  Drawing(const SolidResult& r, const PictureOptions& o)
      : r_(r),
        o_(o),
        tolerance_(o.surface_tolerance > 0 ? o.surface_tolerance
                   : r.brep                ? r.brep->deflection * MetresPerUnit(r.unit)
                                           : 0.0) {}
  std::string Svg();

 private:
  void DrawSurface(const Panel& p);
  void DrawBoxEdges(const Panel& p, bool behind);
  void DrawDimensions(const Panel& p);
  void DrawEllipsoid(const Panel& p);
  void DrawAxesAndCenter(const Panel& p);
  std::vector<std::string> LegendLines() const;
  void DrawLegend(double y, const std::vector<std::string>& lines);
  void Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const char* style) {
    Print("<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' %s/>\n", a.x(), a.y(), b.x(), b.y(), style);
  }
  void Text(double x, double y, const std::string& text, const char* style = "") {
    Print("<text x='%.1f' y='%.1f' font-family='DejaVu Sans, sans-serif' font-size='13' %s>", x, y, style);
    svg_ += Escape(text) + "</text>\n";
  }
  // About how wide a text is in the pictures' 13 px DejaVu Sans.
  static double TextWidth(const std::string& text) {
    double n = 0;
    for (const char ch : text) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;  // UTF-8 code points
    return 7.8 * n;
  }
  static Eigen::AlignedBox2d TextBox(double x, double baseline, double width, const std::string& anchor) {
    const double left = anchor == "end" ? x - width : anchor == "middle" ? x - width / 2 : x;
    return {Eigen::Vector2d(left, baseline - 10), Eigen::Vector2d(left + width, baseline + 3)};
  }
  bool Free(const Eigen::AlignedBox2d& box) const {
    return std::none_of(taken_.begin(), taken_.end(), [&](const Eigen::AlignedBox2d& t) { return t.intersects(box); });
  }
  // A text whose place no later label may take.
  void PlaceText(double x, double baseline, const std::string& text, const std::string& anchor, const char* style) {
    Text(x, baseline, text, ("text-anchor='" + anchor + "' " + style).c_str());
    taken_.push_back(TextBox(x, baseline, TextWidth(text), anchor));
  }
  // printf into the SVG.
  __attribute__((format(printf, 2, 3))) void Print(const char* format, ...) {
    char buffer[512];
    va_list args;
    va_start(args, format);
    const int n = std::vsnprintf(buffer, sizeof buffer, format, args);
    va_end(args);
    svg_.append(buffer, static_cast<std::size_t>(std::clamp(n, 0, static_cast<int>(sizeof buffer) - 1)));
  }
  std::string Length(double metres) const {
    return Number(metres / o_.units.Length()) + " " + UnitName(o_.units.length);
  }
  // A dimension of the box: approximate ("≈") when the surface drawn is.
  std::string Dimension(double metres) const { return (tolerance_ > 0 ? "≈ " : "") + Length(metres); }

  const SolidResult& r_;
  const PictureOptions& o_;
  Surface surface_;
  Eigen::AlignedBox3d box_;  // the surface's bounds, m (empty without a surface)
  const double tolerance_;   // m: how far the surface drawn may be from the solid's (0: it is the solid's)
  std::string svg_;
  std::vector<Eigen::AlignedBox2d> taken_;  // where labels and marks are, px
};

void Drawing::DrawSurface(const Panel& p) {
  const Vector3 toward = p.view.toward();
  const bool cull = r_.model == ModelKind::kSolid && r_.mp.volume > 0;  // closed and outward: the back is hidden
  const Vector3 light = (0.35 * p.view.right + 0.55 * p.view.up + toward).normalized();
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(surface_.tri.size());
  for (std::size_t t = 0; t < surface_.tri.size(); ++t) {
    const Vector3 &a = surface_.v[static_cast<std::size_t>(surface_.tri[t][0])],
                  &b = surface_.v[static_cast<std::size_t>(surface_.tri[t][1])],
                  &c = surface_.v[static_cast<std::size_t>(surface_.tri[t][2])];
    if (cull && !((b - a).cross(c - a).dot(toward) > 0)) continue;
    order.emplace_back(toward.dot(a + b + c), t);
  }
  std::sort(order.begin(), order.end());  // far first
  const bool parts = r_.parts.size() > 1;
  for (const auto& [depth, t] : order) {
    (void)depth;
    const Vector3 &a = surface_.v[static_cast<std::size_t>(surface_.tri[t][0])],
                  &b = surface_.v[static_cast<std::size_t>(surface_.tri[t][1])],
                  &c = surface_.v[static_cast<std::size_t>(surface_.tri[t][2])];
    const Vector3 n = (b - a).cross(c - a).normalized();
    const double lit = std::abs(n.dot(light));
    const Vector3 base = Rgb(parts ? kPartColours[static_cast<std::size_t>(surface_.part[t]) % 8] : "#b8c4d2");
    const Vector3 rgb = ((0.5 + 0.5 * (std::isfinite(lit) ? lit : 0)) * base).cwiseMin(255);
    const Eigen::Vector2d pa = p.Px(a), pb = p.Px(b), pc = p.Px(c);
    const int R = static_cast<int>(rgb.x()), G = static_cast<int>(rgb.y()), B = static_cast<int>(rgb.z());
    Print(
        "<polygon points='%.1f,%.1f %.1f,%.1f %.1f,%.1f' fill='#%02x%02x%02x' stroke='#%02x%02x%02x' "
        "stroke-width='0.5' stroke-linejoin='round'/>\n",
        pa.x(), pa.y(), pb.x(), pb.y(), pc.x(), pc.y(), R, G, B, R, G, B);
  }
}

// The box's corners by index (bit 0 x, bit 1 y, bit 2 z at the maximum) and its twelve edges as
// pairs of corners that differ in one bit.
std::array<Vector3, 8> Corners(const Eigen::AlignedBox3d& box) {
  std::array<Vector3, 8> corner;
  for (int i = 0; i < 8; ++i)
    corner[static_cast<std::size_t>(i)] = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
  return corner;
}

void Drawing::DrawBoxEdges(const Panel& p, bool behind) {
  if (box_.isEmpty()) return;
  const char* dashed = "stroke='#555' stroke-width='1' stroke-dasharray='5,4' fill='none'";
  const std::array<Vector3, 8> corner = Corners(box_);
  // The edges that meet at the corner farthest from the viewer lie behind the part: they are drawn
  // before it, so that the part covers them, and the others after.
  const Vector3 toward = p.view.toward();
  double far = std::numeric_limits<double>::infinity();
  for (const Vector3& c : corner) far = std::min(far, toward.dot(c));
  const double tolerance = 1e-9 * box_.sizes().norm();
  auto is_far = [&](int i) { return toward.dot(corner[static_cast<std::size_t>(i)]) <= far + tolerance; };
  for (int i = 0; i < 8; ++i) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((i & bit) != 0) continue;
      if ((is_far(i) || is_far(i | bit)) == behind)
        Line(p.Px(corner[static_cast<std::size_t>(i)]), p.Px(corner[static_cast<std::size_t>(i | bit)]), dashed);
    }
  }
}

void Drawing::DrawDimensions(const Panel& p) {
  if (box_.isEmpty()) return;
  const std::array<Vector3, 8> corner = Corners(box_);
  const Vector3 size = box_.sizes();
  auto axis_of = [](const Vector3& d) {
    int k = 0;
    d.cwiseAbs().maxCoeff(&k);
    return std::abs(d[k]) > 0.999 ? k : -1;
  };
  const int horizontal = axis_of(p.view.right), vertical = axis_of(p.view.up);
  if (horizontal < 0 || vertical < 0) {
    // The isometric view: each length beside one of the box's outline edges along that axis, the
    // lower one (the left one for an edge that stands upright), as a drawing dimensions a part.
    const char* names = "xyz";
    const Eigen::Vector2d center = p.Px(box_.center());
    for (int k = 0; k < 3; ++k) {
      const int bit = 1 << k;
      const Eigen::Vector2d along = p.Px(corner[static_cast<std::size_t>(bit)]) - p.Px(corner[0]);
      if (!(along.norm() > 0)) continue;
      Eigen::Vector2d normal(-along.y(), along.x());
      normal.normalize();
      const bool upright = std::abs(along.x()) < 0.3 * along.norm();
      if (upright ? normal.x() > 0 : normal.y() < 0) normal = -normal;  // left, or down (SVG's y is down)
      Eigen::Vector2d best = center;
      double best_reach = -std::numeric_limits<double>::infinity();
      for (int i = 0; i < 8; ++i) {
        if ((i & bit) != 0) continue;
        const Eigen::Vector2d m =
            (p.Px(corner[static_cast<std::size_t>(i)]) + p.Px(corner[static_cast<std::size_t>(i | bit)])) / 2;
        const double reach = (m - center).dot(normal);
        if (reach > best_reach + 1e-6) {
          best_reach = reach;
          best = m;
        }
      }
      const std::string text = std::string(1, names[k]) + " " + Dimension(size[k]);
      const Eigen::Vector2d at = best + 12 * normal;
      const char* anchor = normal.x() < -0.3 ? "end" : normal.x() > 0.3 ? "start" : "middle";
      const double baseline = at.y() + 5 + 6 * std::max(0.0, normal.y());
      PlaceText(at.x(), baseline, text, anchor, "fill='#333'");
    }
    return;
  }
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (const Vector3& c : corner) {
    const Eigen::Vector2d q = p.Px(c);
    x_lo = std::min(x_lo, q.x());
    x_hi = std::max(x_hi, q.x());
    y_lo = std::min(y_lo, q.y());
    y_hi = std::max(y_hi, q.y());
  }
  const char* dim = "stroke='#333' stroke-width='1'";
  Line({x_lo, y_hi + 14}, {x_hi, y_hi + 14}, dim);
  Line({x_lo, y_hi + 9}, {x_lo, y_hi + 19}, dim);
  Line({x_hi, y_hi + 9}, {x_hi, y_hi + 19}, dim);
  PlaceText((x_lo + x_hi) / 2, y_hi + 30, Dimension(size[horizontal]), "middle", "fill='#333'");
  Line({x_lo - 14, y_lo}, {x_lo - 14, y_hi}, dim);
  Line({x_lo - 19, y_lo}, {x_lo - 9, y_lo}, dim);
  Line({x_lo - 19, y_hi}, {x_lo - 9, y_hi}, dim);
  const double ym = (y_lo + y_hi) / 2;
  const std::string text = Dimension(size[vertical]);
  const double width = TextWidth(text);
  if (y_hi - y_lo < width + 8) {  // too short to write along: across, left of it
    PlaceText(x_lo - 24, ym + 5, text, "end", "fill='#333'");
    return;
  }
  Print(
      "<text x='%.1f' y='%.1f' font-family='DejaVu Sans, sans-serif' font-size='13' text-anchor='middle' "
      "fill='#333' transform='rotate(-90 %.1f %.1f)'>",
      x_lo - 20, ym, x_lo - 20, ym);
  svg_ += Escape(text) + "</text>\n";
  taken_.emplace_back(Eigen::Vector2d(x_lo - 31, ym - width / 2), Eigen::Vector2d(x_lo - 17, ym + width / 2));
}

void Drawing::DrawEllipsoid(const Panel& p) {
  // The outline of an ellipsoid seen along `toward` is the ellipse whose 2×2 matrix is P M Pᵀ,
  // M = R diag(a²) Rᵀ, P the view's right and up rows: its points c + L (cos t, sin t), L Lᵀ = P M Pᵀ.
  const Vector3 a = EllipsoidSemiAxes(r_);
  const Matrix3& R = r_.principal.axes;
  const Matrix3 M = R * a.cwiseProduct(a).asDiagonal() * R.transpose();
  Eigen::Matrix<double, 2, 3> P;
  P.row(0) = p.view.right.transpose();
  P.row(1) = p.view.up.transpose();
  const Eigen::Matrix2d S = P * M * P.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S);
  const Eigen::Matrix2d L = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).cwiseSqrt().asDiagonal();
  const Eigen::Vector2d c = p.Px(r_.mp.center_of_mass);
  svg_ += "<polygon fill='none' stroke='#ff8c00' stroke-width='1.5' stroke-dasharray='7,4' points='";
  for (int i = 0; i < 96; ++i) {
    const double t = 2 * kPi * i / 96;
    const Eigen::Vector2d q = L * Eigen::Vector2d(std::cos(t), std::sin(t));
    Print("%.2f,%.2f ", c.x() + p.scale * q.x(), c.y() - p.scale * q.y());
  }
  svg_ += "'/>\n";
}

void Drawing::DrawAxesAndCenter(const Panel& p) {
  const Vector3 k = Gyration(r_);
  const Vector3& com = r_.mp.center_of_mass;
  const Eigen::Vector2d c = p.Px(com);
  std::array<Eigen::Vector2d, 3> ends;
  for (int i = 2; i >= 0; --i) {
    const Vector3 e = r_.principal.axes.col(i);
    const Eigen::Vector2d plus = p.Px(com + k[i] * e), minus = p.Px(com - k[i] * e);
    ends[static_cast<std::size_t>(i)] = plus;
    char style[96];
    std::snprintf(style, sizeof style, "stroke='%s' stroke-width='2.5' stroke-linecap='round'", kAxisLine[i]);
    Line(minus, plus, style);
    Print("<circle cx='%.2f' cy='%.2f' r='5' fill='%s' stroke='white' stroke-width='1.5'/>\n", plus.x(), plus.y(),
          kAxisEnd[i]);
  }
  Print("<circle cx='%.2f' cy='%.2f' r='6' fill='#ff00ff' stroke='white' stroke-width='2'/>\n", c.x(), c.y());
  // The marks first, so that no number covers one; then each axis's number beside its end, away
  // from the center of mass where that spot is free, else turned round the end until one is.
  const Eigen::Vector2d mark(7, 7);
  taken_.emplace_back(c - mark, c + mark);
  for (const Eigen::Vector2d& end : ends) taken_.emplace_back(end - Eigen::Vector2d(6, 6), end + Eigen::Vector2d(6, 6));
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& plus = ends[static_cast<std::size_t>(i)];
    const Eigen::Vector2d away =
        (plus - c).norm() > 1 ? Eigen::Vector2d((plus - c).normalized()) : Eigen::Vector2d(1, 0);
    const std::string number = std::to_string(i + 1);
    const std::string style = "fill='" + std::string(kAxisLine[i]) + "' font-weight='bold'";
    Eigen::Vector2d at = plus + 12 * away;
    bool placed = false;
    for (const double distance : {12.0, 20.0}) {
      for (const int turn : {0, 1, -1, 2, -2, 3, -3, 4}) {
        const double angle = turn * kPi / 4;
        const Eigen::Vector2d d(std::cos(angle) * away.x() - std::sin(angle) * away.y(),
                                std::sin(angle) * away.x() + std::cos(angle) * away.y());
        const Eigen::Vector2d q = plus + distance * d;
        if (Free(TextBox(q.x(), q.y() + 5, TextWidth(number), "middle"))) {
          at = q;
          placed = true;
          break;
        }
      }
      if (placed) break;
    }
    PlaceText(at.x(), at.y() + 5, number, "middle", style.c_str());
  }
}

// The legend's lines of numbers. A Monte-Carlo estimate's come with ± one standard error, and the
// center of mass and the principal moments then have lines of their own.
std::vector<std::string> Drawing::LegendLines() const {
  const ReportUnits& u = o_.units;
  const MassPropertiesEstimate* e = r_.estimate ? &*r_.estimate : nullptr;
  auto pm = [&](double se, double unit) { return e ? " ± " + Number(se / unit) : std::string(); };
  const bool shell = r_.model == ModelKind::kShell;
  std::vector<std::string> lines(1);
  lines[0] =
      "mass " + Number(r_.mp.mass / u.Mass()) + pm(e ? e->standard_error.mass : 0, u.Mass()) + " " + UnitName(u.mass);
  if (!shell) {
    lines[0] += "  ·  volume " + Number(r_.mp.volume / u.Volume()) + pm(e ? e->standard_error.volume : 0, u.Volume()) +
                " " + u.VolumeName() + "  ·  density " + Number(r_.mp.density / u.Density()) + " " + u.DensityName();
  }
  auto triple = [](const Vector3& v) {
    return "(" + Number(v.x()) + ", " + Number(v.y()) + ", " + Number(v.z()) + ")";
  };
  std::string com = "center of mass " + triple(r_.mp.center_of_mass / u.Length());
  if (e) com += " ± " + triple(e->standard_error.center_of_mass / u.Length());
  com += std::string(" ") + UnitName(u.length);
  if (e) {
    lines.push_back(com);
  } else {
    lines[0] += "  ·  " + com;
  }
  const Vector3 I = r_.principal.moments / u.Inertia(), k = Gyration(r_) / u.Length();
  std::string moments = "principal moments";
  for (int i = 0; i < 3; ++i) moments += std::string(i ? "," : "") + " I" + std::to_string(i + 1) + " " + Number(I[i]);
  if (e) moments += " ± " + triple(e->principal_moments_se / u.Inertia());
  moments += std::string(" ") + UnitName(u.inertia) + "  ·  radii of gyration " + Number(k.x()) + ", " + Number(k.y()) +
             ", " + Number(k.z()) + " " + UnitName(u.length);
  lines.push_back(moments);
  // Repeated moments have no unique axes (principal_axes.h): say that the pair drawn is a choice.
  bool equal[2];
  for (int i = 0; i < 2; ++i) equal[i] = RepeatedMoments(r_.principal.moments, i) || (e && e->MomentsIndistinct(i));
  const char* within = e ? " within their error bars" : "";
  if (equal[0] && equal[1]) {
    lines.push_back(std::string("the three principal moments are equal") + within +
                    ": every axis through the center of mass is principal (the axes drawn are one choice)");
  } else if (equal[0] || equal[1]) {
    const int i = equal[0] ? 1 : 2;
    lines.push_back("principal moments " + std::to_string(i) + " and " + std::to_string(i + 1) + " are equal" + within +
                    ": any two perpendicular axes in their plane are principal (the pair drawn is one choice)");
  }
  if (e) {
    lines.push_back("± one standard error of the " +
                    std::string(e->method == SamplingMethod::kQuasiMonteCarlo ? "quasi-Monte-Carlo" : "Monte-Carlo") +
                    " estimate (" + std::to_string(e->samples) + " points); the marks are drawn at the estimate");
  }
  return lines;
}

void Drawing::DrawLegend(double y, const std::vector<std::string>& lines) {
  for (std::size_t i = 0; i < lines.size(); ++i) Text(16, y + 20 * static_cast<double>(i), lines[i]);
  // The key.
  double x = 16;
  const double ky = y + 20 * static_cast<double>(lines.size() - 1) + 24;
  Print("<circle cx='%.1f' cy='%.1f' r='6' fill='#ff00ff' stroke='white' stroke-width='2'/>\n", x + 6, ky - 4);
  Text(x + 16, ky, "center of mass");
  x += 140;
  for (int i = 0; i < 3; ++i) {
    Print("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-width='2.5'/>\n", x, ky - 4, x + 22, ky - 4,
          kAxisLine[i]);
    Print("<circle cx='%.1f' cy='%.1f' r='4' fill='%s'/>\n", x + 22, ky - 4, kAxisEnd[i]);
    x += 34;
  }
  Text(x, ky, "principal axes 1, 2, 3 (moments ascending), each as long as its radius of gyration");
  Print("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#ff8c00' stroke-width='1.5' stroke-dasharray='7,4'/>\n",
        16.0, ky + 18, 50.0, ky + 18);
  Text(58, ky + 22, "equivalent-inertia ellipsoid (uniform, same mass and principal moments)");
  Print("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#555' stroke-width='1' stroke-dasharray='5,4'/>\n",
        560.0, ky + 18, 594.0, ky + 18);
  Text(602, ky + 22,
       tolerance_ > 0 ? "bounding box (≈: of the surface drawn, within about " + Length(tolerance_) + " of the solid's)"
                      : std::string("bounding box"));
}

std::string Drawing::Svg() {
  const bool drawn = r_.loaded.mesh.V.rows() > 0 && r_.loaded.mesh.num_faces() > 0;
  if (drawn) {
    surface_ = SurfaceOf(r_);
    for (const Vector3& v : surface_.v) box_.extend(v);
    surface_ = Simplified(std::move(surface_), box_);
  }
  const double W = std::max(o_.width, 400), header = 64;
  const std::vector<std::string> legend_lines = LegendLines();
  const double legend = 90 + 20 * static_cast<double>(legend_lines.size() - 1);
  const double pw = W / 2, ph = pw * 0.72;
  const double H = header + 2 * ph + legend;
  const std::array<View, 4> views = Views();
  // What each view must hold: the box's corners, the ellipsoid and the axes' ends.
  std::vector<Vector3> points;
  if (!box_.isEmpty()) {
    for (int i = 0; i < 8; ++i) points.push_back(box_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  }
  const Vector3 com = r_.mp.center_of_mass, a = EllipsoidSemiAxes(r_), k = Gyration(r_);
  for (int i = 0; i < 3; ++i) {
    const Vector3 e = r_.principal.axes.col(i);
    const double reach = std::max(a[i], k[i]);
    points.push_back(com + reach * e);
    points.push_back(com - reach * e);
  }
  double scale = std::numeric_limits<double>::infinity();
  std::array<Vector3, 4> origin;
  for (std::size_t v = 0; v < 4; ++v) {
    Eigen::AlignedBox2d extent;
    for (const Vector3& x : points) extent.extend(Eigen::Vector2d(views[v].right.dot(x), views[v].up.dot(x)));
    const Eigen::Vector2d mid = extent.center();
    // The world point at the panel's center: mid along right and up, the center of mass in depth.
    origin[v] = mid.x() * views[v].right + mid.y() * views[v].up + views[v].toward().dot(com) * views[v].toward();
    const Eigen::Vector2d size = extent.sizes().cwiseMax(1e-12);
    scale = std::min({scale, (pw - 110) / size.x(), (ph - 90) / size.y()});
  }
  if (!std::isfinite(scale) || !(scale > 0)) scale = 1;
  Print("<svg xmlns='http://www.w3.org/2000/svg' width='%.0f' height='%.0f' viewBox='0 0 %.0f %.0f'>\n", W, H, W, H);
  svg_ += "<rect width='100%' height='100%' fill='white'/>\n";
  std::string title = o_.title;
  if (title.empty()) {
    title = std::filesystem::path(r_.source).filename().string();
    if (!r_.part.empty()) title += " (part '" + r_.part + "')";
    if (r_.parts.size() > 1) title += " (" + std::to_string(r_.parts.size()) + " parts)";
  }
  Print("<text x='16' y='28' font-family='DejaVu Sans, sans-serif' font-size='20' font-weight='bold'>");
  svg_ += Escape(title) + "</text>\n";
  Text(16, 50, "read in " + std::string(UnitName(r_.unit)) + "; shown in " + o_.units.Describe(), "fill='#444'");
  for (std::size_t v = 0; v < 4; ++v) {
    const double column = static_cast<double>(v % 2), row = static_cast<double>(v / 2);
    Panel p{views[v], column * pw, header + row * ph, pw, ph, origin[v], scale};
    Print(
        "<g id='view-%s' data-view='%s' data-right='%.17g %.17g %.17g' data-up='%.17g %.17g %.17g' "
        "data-scale='%.17g' data-center='%.17g %.17g' data-origin='%.17g %.17g %.17g'>\n",
        p.view.id, p.view.id, p.view.right.x(), p.view.right.y(), p.view.right.z(), p.view.up.x(), p.view.up.y(),
        p.view.up.z(), scale, p.x0 + pw / 2, p.y0 + ph / 2 + 12, origin[v].x(), origin[v].y(), origin[v].z());
    Print("<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='none' stroke='#ddd'/>\n", p.x0 + 4, p.y0 + 2,
          pw - 8, ph - 4);
    Text(p.x0 + 12, p.y0 + 20, p.view.label, "fill='#666'");
    DrawBoxEdges(p, true);
    DrawSurface(p);
    DrawBoxEdges(p, false);
    DrawDimensions(p);
    DrawEllipsoid(p);
    DrawAxesAndCenter(p);
    svg_ += "</g>\n";
  }
  if (!drawn) Text(16, header + ph - 8, "(no surface to draw: " + r_.path_used + ")", "fill='#a00'");
  if (r_.parts.size() > 1) {
    double x = W - 16;
    for (std::size_t i = std::min<std::size_t>(r_.parts.size(), 8); i-- > 0;) {
      const std::string name = r_.parts[i].part;
      x -= 20 + 7.5 * static_cast<double>(name.size());
      Print("<rect x='%.1f' y='38' width='12' height='12' fill='%s'/>\n", x, kPartColours[i % 8]);
      Text(x + 16, 49, name);
    }
  }
  DrawLegend(header + 2 * ph + 26, legend_lines);
  svg_ += "</svg>\n";
  return std::move(svg_);
}

}  // namespace

PictureFormat PictureFormatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".svg") return PictureFormat::kSvg;
  if (ext == ".png") return PictureFormat::kPng;
  throw std::invalid_argument("'" + path + "': a picture is .svg or .png");
}

std::string PictureSvg(const SolidResult& r, const PictureOptions& options) { return Drawing(r, options).Svg(); }

void WritePicture(const std::string& path, const SolidResult& r, const PictureOptions& options) {
  const PictureFormat format = PictureFormatOf(path);
  std::string svg = PictureSvg(r, options);
  WriteFileAtomically(path, format == PictureFormat::kSvg ? svg : SvgToPng(svg));
}

}  // namespace massprops::report
