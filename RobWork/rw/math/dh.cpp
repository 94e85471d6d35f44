#include "rw/math/dh.hpp"

#include <cmath>

namespace rw::math {

Transform3D craigDH(double alpha, double a, double d, double theta) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  const double ct = std::cos(theta), st = std::sin(theta);
  Rotation3D R;
  R << ct, -st, 0,            //
      st * ca, ct * ca, -sa,  //
      st * sa, ct * sa, ca;
  return makeTransform(R, Vector3D(a, -sa * d, ca * d));
}

Transform3D schillingDH(double alpha, double a, double d, double theta) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  const double ct = std::cos(theta), st = std::sin(theta);
  Rotation3D R;
  R << ct, -st * ca, st * sa,  //
      st, ct * ca, -ct * sa,   //
      0, sa, ca;
  return makeTransform(R, Vector3D(a * ct, a * st, d));
}

Transform3D hgpDH(double alpha, double a, double beta, double b) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  const double cb = std::cos(beta), sb = std::sin(beta);
  Rotation3D R;
  R << cb, sa * sb, ca * sb,  //
      0, ca, -sa,             //
      -sb, sa * cb, ca * cb;
  return makeTransform(R, Vector3D(a * cb, b, -a * sb));
}

}  // namespace rw::math
