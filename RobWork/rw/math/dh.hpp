#pragma once

#include "rw/math/types.hpp"

/// Denavit-Hartenberg transforms in RobWork's three conventions (angles in radians).
namespace rw::math {

/// Craig's modified DH: Rx(alpha) Tx(a) Rz(theta) Tz(d).
Transform3D craigDH(double alpha, double a, double d, double theta);

/// Schilling's (classic) DH: Rz(theta) Tz(d) Tx(a) Rx(alpha).
Transform3D schillingDH(double alpha, double a, double d, double theta);

/// The "HGP" variant for parallel axes: Ty(b) Ry(beta) Tx(a) Rx(alpha).
Transform3D hgpDH(double alpha, double a, double beta, double b);

}  // namespace rw::math
