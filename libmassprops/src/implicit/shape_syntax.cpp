// The shape syntax (implicit.h, README "Shape syntax"): a small recursive-descent parser with
// positioned errors and a nesting limit.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "implicit/implicit_internal.h"
#include "massprops/primitive.h"

namespace massprops::implicit {
namespace {

struct Value {
  enum Kind { kNumber, kVector, kString, kShape } kind = kNumber;
  Scalar number = 0;
  Vector3 vector = Vector3::Zero();
  std::string text;
  ImplicitPtr shape;
};

class Parser {
 public:
  Parser(const std::string& s, const GridFileReader& read_grid) : s_(s), read_grid_(read_grid) {}

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
      // nan, inf and infinity are numbers strtod reads, not shapes: say that they are not finite.
      std::size_t end = pos_;
      while (end < s_.size() && std::isalpha(static_cast<unsigned char>(s_[end]))) ++end;
      std::string word = s_.substr(pos_, end - pos_);
      for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (word == "nan" || word == "inf" || word == "infinity") {
        Fail("expected a finite number, got '" + s_.substr(pos_, end - pos_) + "'");
      }
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
      if (shapes.size() != n)
        Fail(name + " takes " + std::to_string(n) + " shape" + (n == 1 ? "" : "s") + ", got " +
             std::to_string(shapes.size()));
    };
    ImplicitPtr out;
    try {
      if (const auto& keys = SizeKeys(name, SizeSyntax::kShapeSyntax); !keys.empty()) {
        shapes_exactly(0);
        std::vector<Scalar> sizes;  // the primitive's sizes by their names here (primitive.h)
        for (const SizeKey& k : keys) sizes.push_back(num(k.key));
        out = ToImplicit(MakePrimitive(name, sizes));
      } else if (name == "grid") {
        shapes_exactly(0);
        auto it = named.find("file");
        if (it == named.end() || it->second.kind != Value::kString) Fail("grid: needs file=\"path\"");
        const std::string file = it->second.text;
        named.erase(it);
        if (!read_grid_) Fail("grid: reading grid files needs massprops::io (pass ReadSdfGridFile to ParseShape)");
        out = read_grid_(file);
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
        out = Transformed(shapes[0], Eigen::AngleAxisd(deg * kPi / 180.0, axis.normalized()).toRotationMatrix(),
                          Vector3::Zero());
      } else if (name == "scale") {
        shapes_exactly(1);
        out = Scaled(shapes[0], num("s"));
      } else {
        pos_ = at;
        std::string known;
        for (const char* p : kPrimitiveNames) known += std::string(p) + ", ";
        Fail("unknown shape '" + name + "' (" + known + "grid, union, intersection, difference, move, rotate, scale)");
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
  const GridFileReader& read_grid_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

ImplicitPtr ParseShape(const std::string& text, const GridFileReader& read_grid) {
  return Parser(text, read_grid).ParseAll();
}

}  // namespace massprops::implicit
