#include "massprops/implicit.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace massprops::implicit {
namespace {

std::string Num(Scalar v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

void RequirePositive(Scalar v, const char* what) {
  if (!(std::isfinite(v) && v > 0)) {
    throw std::invalid_argument(std::string(what) + " must be finite and positive (got " + Num(v) + ")");
  }
}

AlignedBox3 Centered(const Vector3& half) { return AlignedBox3(-half, half); }

class SphereSolid final : public ImplicitSolid {
 public:
  explicit SphereSolid(Scalar r) : r_(r) { RequirePositive(r, "sphere: r"); }
  Scalar Value(const Vector3& x) const override { return x.norm() - r_; }
  AlignedBox3 Bounds() const override { return Centered(Vector3::Constant(r_)); }
  std::string Describe() const override { return "sphere(r=" + Num(r_) + ")"; }

 private:
  Scalar r_;
};

class EllipsoidSolid final : public ImplicitSolid {
 public:
  explicit EllipsoidSolid(const Vector3& s) : s_(s) {
    for (int i = 0; i < 3; ++i) RequirePositive(s[i], "ellipsoid: semi-axis");
  }
  Scalar Value(const Vector3& x) const override { return x.cwiseQuotient(s_).squaredNorm() - 1.0; }
  AlignedBox3 Bounds() const override { return Centered(s_); }
  std::string Describe() const override { return "ellipsoid(a=" + Num(s_.x()) + ", b=" + Num(s_.y()) + ", c=" + Num(s_.z()) + ")"; }

 private:
  Vector3 s_;
};

class BoxSolid final : public ImplicitSolid {
 public:
  explicit BoxSolid(const Vector3& size) : half_(0.5 * size) {
    for (int i = 0; i < 3; ++i) RequirePositive(size[i], "box: edge");
  }
  Scalar Value(const Vector3& x) const override { return (x.cwiseAbs() - half_).maxCoeff(); }
  AlignedBox3 Bounds() const override { return Centered(half_); }
  std::string Describe() const override {
    return "box(x=" + Num(2 * half_.x()) + ", y=" + Num(2 * half_.y()) + ", z=" + Num(2 * half_.z()) + ")";
  }

 private:
  Vector3 half_;
};

class CylinderSolid final : public ImplicitSolid {
 public:
  CylinderSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "cylinder: r");
    RequirePositive(h, "cylinder: h");
  }
  Scalar Value(const Vector3& x) const override {
    return std::max(std::hypot(x.x(), x.y()) - r_, std::abs(x.z()) - 0.5 * h_);
  }
  AlignedBox3 Bounds() const override { return Centered(Vector3(r_, r_, 0.5 * h_)); }
  std::string Describe() const override { return "cylinder(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

class ConeSolid final : public ImplicitSolid {
 public:
  ConeSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "cone: r");
    RequirePositive(h, "cone: h");
  }
  Scalar Value(const Vector3& x) const override {
    const Scalar apex = 0.75 * h_;
    // Inside: below the apex, above the base, and within the radius r (apex − z)/h.
    return std::max({-0.25 * h_ - x.z(), x.z() - apex, std::hypot(x.x(), x.y()) - r_ * (apex - x.z()) / h_});
  }
  AlignedBox3 Bounds() const override { return AlignedBox3(Vector3(-r_, -r_, -0.25 * h_), Vector3(r_, r_, 0.75 * h_)); }
  std::string Describe() const override { return "cone(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

class TorusSolid final : public ImplicitSolid {
 public:
  TorusSolid(Scalar R, Scalar a) : R_(R), a_(a) {
    RequirePositive(R, "torus: R");
    RequirePositive(a, "torus: r");
    if (!(a < R)) throw std::invalid_argument("torus: r must be smaller than R (got r=" + Num(a) + ", R=" + Num(R) + ")");
  }
  Scalar Value(const Vector3& x) const override { return std::hypot(std::hypot(x.x(), x.y()) - R_, x.z()) - a_; }
  AlignedBox3 Bounds() const override { return Centered(Vector3(R_ + a_, R_ + a_, a_)); }
  std::string Describe() const override { return "torus(R=" + Num(R_) + ", r=" + Num(a_) + ")"; }

 private:
  Scalar R_, a_;
};

class CapsuleSolid final : public ImplicitSolid {
 public:
  CapsuleSolid(Scalar r, Scalar h) : r_(r), h_(h) {
    RequirePositive(r, "capsule: r");
    RequirePositive(h, "capsule: h");
  }
  Scalar Value(const Vector3& x) const override {
    const Scalar z = std::clamp(x.z(), -0.5 * h_, 0.5 * h_);
    return (x - Vector3(0, 0, z)).norm() - r_;
  }
  AlignedBox3 Bounds() const override { return Centered(Vector3(r_, r_, 0.5 * h_ + r_)); }
  std::string Describe() const override { return "capsule(r=" + Num(r_) + ", h=" + Num(h_) + ")"; }

 private:
  Scalar r_, h_;
};

class CsgSolid final : public ImplicitSolid {
 public:
  enum Op { kUnion, kIntersection, kDifference };
  CsgSolid(Op op, std::vector<ImplicitPtr> parts) : op_(op), parts_(std::move(parts)) {
    if (parts_.size() < (op_ == kDifference ? 2u : 1u)) throw std::invalid_argument("CSG needs at least two solids");
    for (const auto& p : parts_) {
      if (!p) throw std::invalid_argument("CSG: a part is missing");
    }
    bounds_ = parts_[0]->Bounds();
    for (std::size_t i = 1; i < parts_.size(); ++i) {
      if (op_ == kUnion) bounds_.extend(parts_[i]->Bounds());
      if (op_ == kIntersection) bounds_ = bounds_.intersection(parts_[i]->Bounds());
    }
    if (bounds_.isEmpty()) throw std::invalid_argument("intersection: the parts' bounding boxes do not overlap: the solid is empty");
  }
  Scalar Value(const Vector3& x) const override {
    Scalar v = parts_[0]->Value(x);
    for (std::size_t i = 1; i < parts_.size(); ++i) {
      const Scalar w = parts_[i]->Value(x);
      v = op_ == kUnion ? std::min(v, w) : op_ == kIntersection ? std::max(v, w) : std::max(v, -w);
    }
    return v;
  }
  AlignedBox3 Bounds() const override { return bounds_; }
  std::string Describe() const override {
    std::string s = op_ == kUnion ? "union(" : op_ == kIntersection ? "intersection(" : "difference(";
    for (std::size_t i = 0; i < parts_.size(); ++i) s += (i ? ", " : "") + parts_[i]->Describe();
    return s + ")";
  }

 private:
  Op op_;
  std::vector<ImplicitPtr> parts_;
  AlignedBox3 bounds_;
};

class TransformedSolid final : public ImplicitSolid {
 public:
  TransformedSolid(ImplicitPtr a, const Matrix3& R, const Vector3& t, Scalar s)
      : a_(std::move(a)), R_(R), t_(t), s_(s) {
    if (!a_) throw std::invalid_argument("transform: the solid is missing");
    if (!R.allFinite() || !t.allFinite() || (R.transpose() * R - Matrix3::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
        R.determinant() < 0) {
      throw std::invalid_argument("transform: not a rotation, or not finite");
    }
    RequirePositive(s, "scale: s");
    const AlignedBox3 b = a_->Bounds();
    for (int corner = 0; corner < 8; ++corner) {
      const Vector3 c = b.corner(static_cast<AlignedBox3::CornerType>(corner));
      bounds_.extend(Vector3(s_ * (R_ * c) + t_));
    }
  }
  Scalar Value(const Vector3& x) const override { return s_ * a_->Value(R_.transpose() * ((x - t_) / s_)); }
  AlignedBox3 Bounds() const override { return bounds_; }
  std::string Describe() const override {
    std::string s = a_->Describe();
    if (s_ != 1) s = "scale(" + s + ", s=" + Num(s_) + ")";
    if (!R_.isIdentity(0)) {
      const Eigen::AngleAxisd aa(R_);
      s = "rotate(" + s + ", axis=[" + Num(aa.axis().x()) + ", " + Num(aa.axis().y()) + ", " + Num(aa.axis().z()) +
          "], deg=" + Num(aa.angle() * 180 / M_PI) + ")";
    }
    if (!t_.isZero(0)) s = "move(" + s + ", x=" + Num(t_.x()) + ", y=" + Num(t_.y()) + ", z=" + Num(t_.z()) + ")";
    return s;
  }

 private:
  ImplicitPtr a_;
  Matrix3 R_;
  Vector3 t_;
  Scalar s_;
  AlignedBox3 bounds_;
};

class GridSolid final : public ImplicitSolid {
 public:
  GridSolid(const Eigen::Vector3i& n, const Vector3& origin, const Vector3& h, std::vector<Scalar> v, std::string name)
      : n_(n), origin_(origin), h_(h), v_(std::move(v)), name_(std::move(name)) {
    if ((n.array() < 2).any()) throw std::invalid_argument("grid: at least 2 samples along each axis");
    for (int i = 0; i < 3; ++i) RequirePositive(h[i], "grid: spacing");
    if (!origin.allFinite()) throw std::invalid_argument("grid: origin not finite");
    const auto count = static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y()) * static_cast<std::size_t>(n.z());
    if (v_.size() != count) {
      throw std::invalid_argument("grid: " + std::to_string(v_.size()) + " values for " + std::to_string(n.x()) + "×" +
                                  std::to_string(n.y()) + "×" + std::to_string(n.z()) + " samples");
    }
    for (std::size_t i = 0; i < v_.size(); ++i) {
      if (!std::isfinite(v_[i])) throw std::invalid_argument("grid: value " + std::to_string(i) + " is not finite");
    }
  }
  Scalar Value(const Vector3& x) const override {
    const Vector3 u = (x - origin_).cwiseQuotient(h_);
    Scalar f[3];
    int i[3];
    for (int k = 0; k < 3; ++k) {
      if (!(u[k] >= 0 && u[k] <= n_[k] - 1)) return 1.0;  // outside the grid: absent
      i[k] = std::min(static_cast<int>(u[k]), n_[k] - 2);
      f[k] = u[k] - i[k];
    }
    auto at = [&](int dx, int dy, int dz) {
      return v_[static_cast<std::size_t>(i[0] + dx) +
                static_cast<std::size_t>(n_.x()) * (static_cast<std::size_t>(i[1] + dy) + static_cast<std::size_t>(n_.y()) * static_cast<std::size_t>(i[2] + dz))];
    };
    Scalar c[2];
    for (int dz = 0; dz < 2; ++dz) {
      const Scalar c0 = at(0, 0, dz) * (1 - f[0]) + at(1, 0, dz) * f[0];
      const Scalar c1 = at(0, 1, dz) * (1 - f[0]) + at(1, 1, dz) * f[0];
      c[dz] = c0 * (1 - f[1]) + c1 * f[1];
    }
    return c[0] * (1 - f[2]) + c[1] * f[2];
  }
  AlignedBox3 Bounds() const override {
    return AlignedBox3(origin_, origin_ + h_.cwiseProduct((n_.array() - 1).cast<Scalar>().matrix()));
  }
  std::string Describe() const override { return name_; }

 private:
  Eigen::Vector3i n_;
  Vector3 origin_, h_;
  std::vector<Scalar> v_;
  std::string name_;
};

// ---- the shape syntax ----

struct Value {
  enum Kind { kNumber, kVector, kString, kShape } kind = kNumber;
  Scalar number = 0;
  Vector3 vector = Vector3::Zero();
  std::string text;
  ImplicitPtr shape;
};

class Parser {
 public:
  explicit Parser(const std::string& s) : s_(s) {}

  ImplicitPtr ParseAll() {
    ImplicitPtr shape = Shape();
    Skip();
    if (pos_ != s_.size()) Fail("unexpected '" + s_.substr(pos_, 10) + "' after the shape");
    return shape;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument("shape, at character " + std::to_string(pos_ + 1) + ": " + what);
  }
  void Skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool Accept(char c) {
    Skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void Expect(char c) {
    if (!Accept(c)) Fail(std::string("expected '") + c + "'");
  }
  std::string Name() {
    Skip();
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    if (pos_ == start) Fail("expected a name");
    return s_.substr(start, pos_ - start);
  }
  Scalar Number() {
    Skip();
    const char* begin = s_.c_str() + pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) Fail("expected a number");
    if (!std::isfinite(v)) Fail("the number is not finite");
    pos_ += static_cast<std::size_t>(end - begin);
    return v;
  }

  Value ParseValue() {
    Skip();
    Value v;
    if (pos_ < s_.size() && s_[pos_] == '[') {
      ++pos_;
      v.kind = Value::kVector;
      for (int i = 0; i < 3; ++i) {
        if (i) Expect(',');
        v.vector[i] = Number();
      }
      Expect(']');
    } else if (pos_ < s_.size() && s_[pos_] == '"') {
      ++pos_;
      const std::size_t end = s_.find('"', pos_);
      if (end == std::string::npos) Fail("unterminated string");
      v.kind = Value::kString;
      v.text = s_.substr(pos_, end - pos_);
      pos_ = end + 1;
    } else if (pos_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[pos_])))) {
      v.kind = Value::kShape;
      v.shape = Shape();
    } else {
      v.number = Number();
    }
    return v;
  }

  ImplicitPtr Shape() {
    const std::size_t at = pos_;
    struct Depth {  // nesting guard: the parser recurses once per level
      int& d;
      explicit Depth(int& depth) : d(depth) { ++d; }
      ~Depth() { --d; }
    } depth(depth_);
    if (depth_ > 200) Fail("shapes nested more than 200 deep");
    const std::string name = Name();
    Expect('(');
    std::vector<ImplicitPtr> shapes;
    std::map<std::string, Value> named;
    if (!Accept(')')) {
      do {
        Skip();
        // key=value, or a positional shape
        const std::size_t save = pos_;
        std::string key;
        if (pos_ < s_.size() && std::isalpha(static_cast<unsigned char>(s_[pos_]))) {
          key = Name();
          if (!Accept('=')) {
            pos_ = save;
            key.clear();
          }
        }
        Value v = ParseValue();
        if (key.empty()) {
          if (v.kind != Value::kShape) Fail("a positional argument must be a shape; give numbers as key=value");
          shapes.push_back(v.shape);
        } else {
          if (named.count(key)) Fail("'" + key + "' given twice");
          named[key] = v;
        }
      } while (Accept(','));
      Expect(')');
    }
    auto num = [&](const std::string& key) {
      auto it = named.find(key);
      if (it == named.end()) {
        pos_ = at;
        Fail(name + ": missing " + key + "=");
      }
      if (it->second.kind != Value::kNumber) Fail(name + ": " + key + " must be a number");
      const Scalar v = it->second.number;
      named.erase(it);
      return v;
    };
    auto opt_num = [&](const std::string& key, Scalar fallback) { return named.count(key) ? num(key) : fallback; };
    auto vec = [&](const std::string& key) {
      auto it = named.find(key);
      if (it == named.end()) Fail(name + ": missing " + key + "=[x, y, z]");
      if (it->second.kind != Value::kVector) Fail(name + ": " + key + " must be [x, y, z]");
      const Vector3 v = it->second.vector;
      named.erase(it);
      return v;
    };
    auto shapes_exactly = [&](std::size_t n) {
      if (shapes.size() != n) Fail(name + " takes " + std::to_string(n) + " shape" + (n == 1 ? "" : "s") + ", got " + std::to_string(shapes.size()));
    };
    ImplicitPtr out;
    try {
      if (name == "sphere") {
        shapes_exactly(0);
        out = Sphere(num("r"));
      } else if (name == "ellipsoid") {
        shapes_exactly(0);
        const Scalar a = num("a"), b = num("b"), c = num("c");
        out = Ellipsoid(Vector3(a, b, c));
      } else if (name == "box") {
        shapes_exactly(0);
        const Scalar x = num("x"), y = num("y"), z = num("z");
        out = Box(Vector3(x, y, z));
      } else if (name == "cylinder" || name == "cone" || name == "capsule") {
        shapes_exactly(0);
        const Scalar r = num("r"), h = num("h");
        out = name == "cylinder" ? Cylinder(r, h) : name == "cone" ? Cone(r, h) : Capsule(r, h);
      } else if (name == "torus") {
        shapes_exactly(0);
        const Scalar R = num("R"), r = num("r");
        out = Torus(R, r);
      } else if (name == "grid") {
        shapes_exactly(0);
        auto it = named.find("file");
        if (it == named.end() || it->second.kind != Value::kString) Fail("grid: needs file=\"path\"");
        const std::string file = it->second.text;
        named.erase(it);
        out = SdfGridFromFile(file);
      } else if (name == "union" || name == "intersection") {
        if (shapes.size() < 2) Fail(name + " takes two or more shapes");
        out = name == "union" ? Union(shapes) : Intersection(shapes);
      } else if (name == "difference") {
        shapes_exactly(2);
        out = Difference(shapes[0], shapes[1]);
      } else if (name == "move") {
        shapes_exactly(1);
        const Vector3 t(opt_num("x", 0), opt_num("y", 0), opt_num("z", 0));
        out = Transformed(shapes[0], Matrix3::Identity(), t);
      } else if (name == "rotate") {
        shapes_exactly(1);
        const Vector3 axis = vec("axis");
        const Scalar deg = num("deg");
        if (!(axis.norm() > 0)) Fail("rotate: the axis is zero");
        out = Transformed(shapes[0], Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()).toRotationMatrix(), Vector3::Zero());
      } else if (name == "scale") {
        shapes_exactly(1);
        out = Scaled(shapes[0], num("s"));
      } else {
        pos_ = at;
        Fail("unknown shape '" + name +
             "' (sphere, ellipsoid, box, cylinder, cone, torus, capsule, grid, union, intersection, difference, move, rotate, scale)");
      }
    } catch (const std::runtime_error& e) {  // a grid file that cannot be read
      Fail(e.what());
    } catch (const std::invalid_argument& e) {
      if (std::string(e.what()).rfind("shape, at", 0) == 0) throw;
      pos_ = at;
      Fail(e.what());
    }
    if (!named.empty()) Fail(name + ": unknown parameter '" + named.begin()->first + "'");
    return out;
  }

  const std::string& s_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

ImplicitPtr Sphere(Scalar r) { return std::make_shared<SphereSolid>(r); }
ImplicitPtr Ellipsoid(const Vector3& s) { return std::make_shared<EllipsoidSolid>(s); }
ImplicitPtr Box(const Vector3& size) { return std::make_shared<BoxSolid>(size); }
ImplicitPtr Cylinder(Scalar r, Scalar h) { return std::make_shared<CylinderSolid>(r, h); }
ImplicitPtr Cone(Scalar r, Scalar h) { return std::make_shared<ConeSolid>(r, h); }
ImplicitPtr Torus(Scalar major, Scalar minor) { return std::make_shared<TorusSolid>(major, minor); }
ImplicitPtr Capsule(Scalar r, Scalar h) { return std::make_shared<CapsuleSolid>(r, h); }
ImplicitPtr Union(std::vector<ImplicitPtr> parts) { return std::make_shared<CsgSolid>(CsgSolid::kUnion, std::move(parts)); }
ImplicitPtr Intersection(std::vector<ImplicitPtr> parts) {
  return std::make_shared<CsgSolid>(CsgSolid::kIntersection, std::move(parts));
}
ImplicitPtr Difference(ImplicitPtr a, ImplicitPtr b) {
  return std::make_shared<CsgSolid>(CsgSolid::kDifference, std::vector<ImplicitPtr>{std::move(a), std::move(b)});
}
ImplicitPtr Transformed(ImplicitPtr a, const Matrix3& R, const Vector3& t) {
  return std::make_shared<TransformedSolid>(std::move(a), R, t, 1.0);
}
ImplicitPtr Scaled(ImplicitPtr a, Scalar s) {
  return std::make_shared<TransformedSolid>(std::move(a), Matrix3::Identity(), Vector3::Zero(), s);
}

ImplicitPtr SdfGrid(const Eigen::Vector3i& size, const Vector3& origin, const Vector3& spacing, std::vector<Scalar> values) {
  return std::make_shared<GridSolid>(size, origin, spacing, std::move(values), "grid(in memory)");
}

ImplicitPtr SdfGridFromFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error(path + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": cannot open the grid file"));
  }
  const auto bytes = std::filesystem::file_size(path, ec);
  std::ifstream in(path);
  if (!in || ec) throw std::runtime_error(path + ": cannot open the grid file");
  std::string magic;
  int version = 0;
  in >> magic >> version;
  if (magic != "sdfgrid" || version != 1) throw std::runtime_error(path + ": not an sdfgrid 1 file (first line must be 'sdfgrid 1')");
  Eigen::Vector3i n;
  Vector3 origin, h;
  if (!(in >> n.x() >> n.y() >> n.z())) throw std::runtime_error(path + ": expected the sample counts NX NY NZ");
  if ((n.array() < 2).any() || (n.cast<double>().prod() > 1e9)) throw std::runtime_error(path + ": sample counts must be 2 or more (and at most 10^9 in all)");
  if (!(in >> origin.x() >> origin.y() >> origin.z())) throw std::runtime_error(path + ": expected the origin X0 Y0 Z0");
  if (!(in >> h.x() >> h.y() >> h.z())) throw std::runtime_error(path + ": expected the spacing HX HY HZ");
  const auto count = static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y()) * static_cast<std::size_t>(n.z());
  // Every value takes at least two bytes of text: a header that promises more than the file can
  // hold is refused before anything is allocated for it.
  if (count > bytes / 2) {
    throw std::runtime_error(path + ": the header promises " + std::to_string(count) + " values, more than the file (" +
                             std::to_string(bytes) + " bytes) can hold");
  }
  std::vector<Scalar> v(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!(in >> v[i])) throw std::runtime_error(path + ": expected " + std::to_string(count) + " values, found " + std::to_string(i));
  }
  try {
    return std::make_shared<GridSolid>(n, origin, h, std::move(v), "grid(file=\"" + path + "\")");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

ImplicitPtr ParseShape(const std::string& text) { return Parser(text).ParseAll(); }

}  // namespace massprops::implicit
