// The definitions of massprops/export.h: inertial elements for robot descriptions, ready to paste.

#include "massprops/export.h"

#include <charconv>
#include <sstream>

#include <Eigen/Geometry>

namespace massprops {

namespace {
std::string Triple(const Vector3& v) {
  return ExactDecimal(v[0]) + " " + ExactDecimal(v[1]) + " " + ExactDecimal(v[2]);
}
}  // namespace

std::string UrdfInertial(const MassProperties& mp, const std::string& in) {
  const Matrix3& I = mp.inertia_com;
  std::ostringstream o;
  o << in << "<inertial>\n"
    << in << "  <origin xyz=\"" << Triple(mp.center_of_mass) << "\" rpy=\"0 0 0\"/>\n"
    << in << "  <mass value=\"" << ExactDecimal(mp.mass) << "\"/>\n"
    << in << "  <inertia ixx=\"" << ExactDecimal(I(0, 0)) << "\" ixy=\"" << ExactDecimal(I(0, 1)) << "\" ixz=\""
    << ExactDecimal(I(0, 2)) << "\" iyy=\"" << ExactDecimal(I(1, 1)) << "\" iyz=\"" << ExactDecimal(I(1, 2))
    << "\" izz=\"" << ExactDecimal(I(2, 2)) << "\"/>\n"
    << in << "</inertial>\n";
  return o.str();
}

std::string SdfInertial(const MassProperties& mp, const std::string& in) {
  const Matrix3& I = mp.inertia_com;
  std::ostringstream o;
  o << in << "<inertial>\n"
    << in << "  <pose>" << Triple(mp.center_of_mass) << " 0 0 0</pose>\n"
    << in << "  <mass>" << ExactDecimal(mp.mass) << "</mass>\n"
    << in << "  <inertia>\n"
    << in << "    <ixx>" << ExactDecimal(I(0, 0)) << "</ixx>\n"
    << in << "    <ixy>" << ExactDecimal(I(0, 1)) << "</ixy>\n"
    << in << "    <ixz>" << ExactDecimal(I(0, 2)) << "</ixz>\n"
    << in << "    <iyy>" << ExactDecimal(I(1, 1)) << "</iyy>\n"
    << in << "    <iyz>" << ExactDecimal(I(1, 2)) << "</iyz>\n"
    << in << "    <izz>" << ExactDecimal(I(2, 2)) << "</izz>\n"
    << in << "  </inertia>\n"
    << in << "</inertial>\n";
  return o.str();
}

std::string MjcfInertial(const MassProperties& mp, const PrincipalInertia& p, const std::string& in) {
  Eigen::Quaterniond q(p.axes);  // rotation taking principal-frame vectors to mesh axes
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;  // one of the two equal quaternions, w >= 0
  // A flat body's moments sit on the triangle inequality (I1 + I2 = I3), where rounding can put
  // them a few ulps outside it, and MuJoCo refuses an inertia with I1 + I2 < I3 by any amount:
  // the largest moment then takes the sum's value (a change within rounding of the moments).
  Vector3 moments = p.moments;
  if (moments[0] + moments[1] < moments[2] && moments[2] - (moments[0] + moments[1]) <= 1e-12 * moments[2]) {
    moments[2] = moments[0] + moments[1];
  }
  std::ostringstream o;
  o << in << "<inertial pos=\"" << Triple(mp.center_of_mass) << "\" quat=\"" << ExactDecimal(q.w()) << " "
    << ExactDecimal(q.x()) << " " << ExactDecimal(q.y()) << " " << ExactDecimal(q.z()) << "\" mass=\""
    << ExactDecimal(mp.mass) << "\" diaginertia=\"" << Triple(moments) << "\"/>\n";
  return o.str();
}

}  // namespace massprops
