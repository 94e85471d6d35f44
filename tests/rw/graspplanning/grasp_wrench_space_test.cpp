#include "rw/graspplanning/grasp_wrench_space.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "support/test_support.hpp"

namespace {

using rw::graspplanning::Contact3D;
using rw::graspplanning::contactWrenches;
using rw::graspplanning::gwsEpsilon;
using rw::graspplanning::gwsEpsilonOfWrenches;
using rw::graspplanning::GwsForce;
using rw::graspplanning::GwsHull;
using rw::graspplanning::GwsOptions;
using rw::graspplanning::GwsResult;
using rw::graspplanning::GwsStatus;
using rw::graspplanning::Wrench6D;
using rw::math::Vector3D;

constexpr double kRadius = 0.05;  // sphere radius = r, centre at the origin
// The exact (merging) hull matches the brute force to rounding (~1e-15 relative measured).
constexpr double kExactRelative = 1e-12;
const double kPi = std::numbers::pi;

// A contact on the sphere in direction u, pushing towards the centre.
Contact3D sphereContact(const Vector3D& u, double mu) {
  Contact3D c;
  c.position = kRadius * u.normalized();
  c.normal = -u.normalized();
  c.mu = mu;
  return c;
}

std::vector<Contact3D> equatorGrasp(double mu) {
  std::vector<Contact3D> contacts;
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * kPi * i / 3.0;
    contacts.push_back(sphereContact(Vector3D(std::cos(a), std::sin(a), 0.0), mu));
  }
  return contacts;
}

std::vector<Contact3D> tetrahedralGrasp(double mu) {
  return {sphereContact(Vector3D(1, 1, 1), mu), sphereContact(Vector3D(1, -1, -1), mu),
          sphereContact(Vector3D(-1, 1, -1), mu), sphereContact(Vector3D(-1, -1, 1), mu)};
}

// The paper's wrench points (eq. 6) written independently of the library: the cone edge is the
// RobWork tangent turned about n with an angle-axis rotation.
std::vector<Wrench6D> referenceWrenches(const std::vector<Contact3D>& contacts, const Vector3D& c,
                                        double r, int edges) {
  std::vector<Wrench6D> points;
  for (const Contact3D& contact : contacts) {
    const Vector3D n = contact.normal.normalized();
    const bool alongZ = std::abs(n.x()) < 1e-6 && std::abs(n.y()) < 1e-6;
    const Vector3D t =
        alongZ ? Vector3D(0, -n.z(), n.y()).normalized() : Vector3D(-n.y(), n.x(), 0).normalized();
    for (int k = 0; k < edges; ++k) {
      const Eigen::AngleAxisd turn(2.0 * kPi * k / edges, n);
      const Vector3D f = n + contact.mu * (turn * t);
      Wrench6D w;
      w << f, (contact.position - c).cross(f) / r;
      points.push_back(w);
    }
  }
  return points;
}

// Ferrari-Canny epsilon by brute force over all 6-subsets of the points: every hyperplane through
// 6 affinely independent points that has all points on one side (within 1e-12) is recorded with
// the origin's distance on the points' side (negative if the origin is beyond it). Every such
// supporting hyperplane is at least epsilon from an inside origin and the nearest facet is among
// them, so epsilon is the minimum (0 if it is not positive). Subsets are built by nested choice
// with Gram-Schmidt: the edges from the first point span a 4-D space after 4 more points, its
// 2-D orthogonal complement is computed once, and each sixth point then needs two dot products.
class BruteForceGws {
 public:
  explicit BruteForceGws(std::vector<Wrench6D> points) : pts_(std::move(points)) {}

  double epsilon() {
    for (int anchor = 0; anchor < size(); ++anchor) extend(anchor, anchor + 1, 0);
    return std::isfinite(minDistance_) && minDistance_ > 0.0 ? minDistance_ : 0.0;
  }

 private:
  static constexpr double kDegenerate = 1e-9;
  static constexpr double kSideTolerance = 1e-12;

  int size() const { return static_cast<int>(pts_.size()); }

  // Removes the components along the first `count` basis vectors (twice, for accuracy).
  Wrench6D orthogonalise(Wrench6D e, int count) const {
    for (int pass = 0; pass < 2; ++pass) {
      for (int k = 0; k < count; ++k) e -= basis_[k].dot(e) * basis_[k];
    }
    return e;
  }

  void extend(int anchor, int from, int depth) {
    for (int i = from; i < size(); ++i) {
      const Wrench6D edge = pts_[i] - pts_[anchor];
      const Wrench6D e = orthogonalise(edge, depth);
      if (e.norm() <= kDegenerate * edge.norm()) continue;
      basis_[depth] = e.normalized();
      if (depth == 3) {
        closeFacets(anchor, i + 1);
      } else {
        extend(anchor, i + 1, depth + 1);
      }
    }
  }

  // Orthonormal u, v spanning the complement of basis_[0..3]: the two longest residuals of the
  // coordinate axes (their squared lengths sum to 2, so the longest is at least 1/sqrt(3)).
  std::array<Wrench6D, 2> complement() const {
    std::array<Wrench6D, 6> residuals;
    for (int j = 0; j < 6; ++j) residuals[j] = orthogonalise(Wrench6D::Unit(j), 4);
    auto longest = [&] {
      return *std::max_element(
          residuals.begin(), residuals.end(),
          [](const Wrench6D& a, const Wrench6D& b) { return a.norm() < b.norm(); });
    };
    const Wrench6D u = longest().normalized();
    for (Wrench6D& r : residuals) r -= u.dot(r) * u;
    return {u, longest().normalized()};
  }

  void closeFacets(int anchor, int from) {
    const auto [u, v] = complement();
    for (int i = from; i < size(); ++i) {
      const Wrench6D edge = pts_[i] - pts_[anchor];
      const double alpha = u.dot(edge);
      const double beta = v.dot(edge);
      const double length = std::hypot(alpha, beta);
      if (length <= kDegenerate * edge.norm()) continue;
      // Orthogonal to the 4 basis vectors and to this edge: the hyperplane's unit normal.
      const Wrench6D normal = (alpha * v - beta * u) / length;
      record(normal, -normal.dot(pts_[anchor]));
    }
  }

  void record(const Wrench6D& normal, double offset) {
    double lo = 0.0;
    double hi = 0.0;
    for (const Wrench6D& p : pts_) {
      const double s = normal.dot(p) + offset;
      lo = std::min(lo, s);
      hi = std::max(hi, s);
      if (lo < -kSideTolerance && hi > kSideTolerance) return;
    }
    // The origin's value is `offset`; it is inside when its sign is opposite to the points'.
    minDistance_ = std::min(minDistance_, hi <= kSideTolerance ? -offset : offset);
  }

  std::vector<Wrench6D> pts_;
  std::array<Wrench6D, 4> basis_;
  double minDistance_ = std::numeric_limits<double>::infinity();
};

double bruteForceEpsilon(std::vector<Wrench6D> points) {
  return BruteForceGws(std::move(points)).epsilon();
}

void expectZero(const GwsResult& r, GwsStatus status) {
  EXPECT_EQ(r.epsilon, 0.0);
  EXPECT_FALSE(r.forceClosure);
  EXPECT_EQ(r.status, status) << "got " << rw::graspplanning::toString(r.status) << ": "
                              << r.detail;
}

TEST(GwsEpsilon, NoContactsGivesZero) {
  expectZero(gwsEpsilon({}, Vector3D::Zero(), kRadius), GwsStatus::kTooFewPoints);
}

TEST(GwsEpsilon, OneContactGivesZero) {
  // One cone is a 2-D set of wrenches: Qhull finds it flat.
  const std::vector<Contact3D> one = {sphereContact(Vector3D::UnitX(), 0.6)};
  expectZero(gwsEpsilon(one, Vector3D::Zero(), kRadius), GwsStatus::kFlat);
}

TEST(GwsEpsilon, TwoFrictionlessAntipodalContactsGiveZero) {
  // mu = 0: every cone edge is the normal, so only 2 distinct wrench points remain.
  const std::vector<Contact3D> two = {sphereContact(Vector3D::UnitX(), 0.0),
                                      sphereContact(-Vector3D::UnitX(), 0.0)};
  const GwsResult r = gwsEpsilon(two, Vector3D::Zero(), kRadius);
  expectZero(r, GwsStatus::kTooFewPoints);
  EXPECT_EQ(r.points, 2);
}

TEST(GwsEpsilon, TwoAntipodalContactsWithFrictionAreFlat) {
  // Torque about the contact axis is impossible: the 20 wrenches span only 5 dimensions.
  const std::vector<Contact3D> two = {sphereContact(Vector3D::UnitX(), 0.6),
                                      sphereContact(-Vector3D::UnitX(), 0.6)};
  const GwsResult r = gwsEpsilon(two, Vector3D::Zero(), kRadius);
  expectZero(r, GwsStatus::kFlat);
  EXPECT_EQ(r.points, 20);
  EXPECT_NE(r.detail.find("fewer than 6 dimensions"), std::string::npos) << r.detail;
}

TEST(GwsEpsilon, FewerThanSevenDistinctPointsGiveZero) {
  const std::vector<Contact3D> two = {sphereContact(Vector3D::UnitX(), 0.6),
                                      sphereContact(Vector3D::UnitY(), 0.6)};
  const GwsResult r = gwsEpsilon(two, Vector3D::Zero(), kRadius, GwsOptions{.coneEdges = 3});
  expectZero(r, GwsStatus::kTooFewPoints);
  EXPECT_EQ(r.points, 6);
}

TEST(GwsEpsilon, InvalidInputGivesZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Contact3D> good = equatorGrasp(0.6);
  auto withChange = [&](auto change) {
    std::vector<Contact3D> contacts = good;
    change(contacts[1]);
    return contacts;
  };
  const Vector3D c = Vector3D::Zero();
  const GwsStatus bad = GwsStatus::kInvalidInput;
  expectZero(gwsEpsilon(withChange([&](Contact3D& k) { k.position.x() = nan; }), c, kRadius), bad);
  expectZero(gwsEpsilon(withChange([&](Contact3D& k) { k.normal.y() = inf; }), c, kRadius), bad);
  expectZero(gwsEpsilon(withChange([&](Contact3D& k) { k.mu = nan; }), c, kRadius), bad);
  expectZero(gwsEpsilon(withChange([](Contact3D& k) { k.mu = -0.1; }), c, kRadius), bad);
  expectZero(gwsEpsilon(withChange([](Contact3D& k) { k.normal.setZero(); }), c, kRadius), bad);
  expectZero(gwsEpsilon(good, Vector3D(0, nan, 0), kRadius), bad);
  expectZero(gwsEpsilon(good, c, 0.0), bad);
  expectZero(gwsEpsilon(good, c, -kRadius), bad);
  expectZero(gwsEpsilon(good, c, inf), bad);
  expectZero(gwsEpsilon(good, c, nan), bad);
  const GwsOptions measured{.force = GwsForce::kMeasuredNormalForce};
  expectZero(
      gwsEpsilon(withChange([](Contact3D& k) { k.normalForce = -1.0; }), c, kRadius, measured),
      bad);
  // The measured force is ignored unless asked for.
  EXPECT_TRUE(
      gwsEpsilon(withChange([&](Contact3D& k) { k.normalForce = nan; }), c, kRadius).forceClosure);
  std::vector<Wrench6D> points(8, Wrench6D::Ones());
  points[3](4) = nan;
  expectZero(gwsEpsilonOfWrenches(points), bad);
}

TEST(GwsEpsilon, TooFewConeEdgesIsAProgrammerError) {
  const std::vector<Contact3D> contacts = equatorGrasp(0.6);
  EXPECT_THROW(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, GwsOptions{.coneEdges = 2}),
               std::invalid_argument);
  EXPECT_THROW(contactWrenches(contacts, Vector3D::Zero(), kRadius, GwsOptions{.coneEdges = 0}),
               std::invalid_argument);
}

TEST(GwsEpsilon, StatusNames) {
  EXPECT_EQ(rw::graspplanning::toString(GwsStatus::kForceClosure), "ForceClosure");
  EXPECT_EQ(rw::graspplanning::toString(GwsStatus::kFlat), "Flat");
  EXPECT_EQ(rw::graspplanning::toString(GwsStatus::kQhullError), "QhullError");
}

TEST(GwsEpsilonOfWrenches, CrossPolytopeHasEpsilonOneOverRootSix) {
  // conv{+-e_i}: its 64 facets are s . x = 1 for sign vectors s, all at distance 1/sqrt(6).
  std::vector<Wrench6D> points;
  for (int i = 0; i < 6; ++i) {
    points.emplace_back(Wrench6D::Unit(i));
    points.emplace_back(-Wrench6D::Unit(i));
  }
  const GwsResult r = gwsEpsilonOfWrenches(points);
  EXPECT_TRUE(r.forceClosure);
  EXPECT_NEAR(r.epsilon, 1.0 / std::sqrt(6.0), 1e-14);
  EXPECT_EQ(r.facets, 64);
  // The brute-force checker used below agrees with the analytic value too.
  EXPECT_NEAR(bruteForceEpsilon(points), 1.0 / std::sqrt(6.0), 1e-14);
}

TEST(GwsEpsilonOfWrenches, HypercubeHasEpsilonOne) {
  std::vector<Wrench6D> points;
  for (int bits = 0; bits < 64; ++bits) {
    Wrench6D w;
    for (int i = 0; i < 6; ++i) w(i) = (bits >> i & 1) != 0 ? 1.0 : -1.0;
    points.push_back(w);
  }
  const GwsResult r = gwsEpsilonOfWrenches(points);
  EXPECT_NEAR(r.epsilon, 1.0, 1e-14);
  EXPECT_EQ(r.status, GwsStatus::kForceClosure);
}

TEST(GwsEpsilonOfWrenches, OriginOnBoundaryOrOutsideGivesZero) {
  // A simplex with the origin as a vertex, then shifted so the origin is outside.
  std::vector<Wrench6D> points = {Wrench6D::Zero()};
  for (int i = 0; i < 6; ++i) points.emplace_back(Wrench6D::Unit(i));
  expectZero(gwsEpsilonOfWrenches(points), GwsStatus::kNotForceClosure);
  for (Wrench6D& p : points) p.array() += 0.5;
  expectZero(gwsEpsilonOfWrenches(points), GwsStatus::kNotForceClosure);
}

TEST(GwsEpsilon, ParallelNormalsAreFlat) {
  // With unit normal forces every wrench has n . f = 1: all points lie in one hyperplane.
  std::vector<Contact3D> contacts;
  for (int i = 0; i < 4; ++i) {
    Contact3D c;
    c.position = Vector3D(0.03 * std::cos(i), 0.03 * std::sin(i), -0.02);
    c.normal = Vector3D::UnitZ();
    contacts.push_back(c);
  }
  expectZero(gwsEpsilon(contacts, Vector3D::Zero(), kRadius), GwsStatus::kFlat);
}

TEST(GwsEpsilon, AllForcesUpwardsIsNotForceClosure) {
  // Full-dimensional, but no force can pull the object up: the origin is outside.
  std::vector<Contact3D> contacts;
  for (int i = 0; i < 4; ++i) {
    const Vector3D u(std::cos(2.0 * i), std::sin(2.0 * i), -1.0);
    contacts.push_back(sphereContact(u, 0.3));
  }
  const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  expectZero(r, GwsStatus::kNotForceClosure);
  EXPECT_GT(r.facets, 0);
}

TEST(GwsEpsilon, ThreeContactsOnEquatorMatchBruteForce) {
  const std::vector<Contact3D> contacts = equatorGrasp(0.6);
  const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  ASSERT_TRUE(r.forceClosure) << r.detail;
  EXPECT_GT(r.epsilon, 0.0);
  EXPECT_EQ(r.points, 30);
  const double truth =
      bruteForceEpsilon(referenceWrenches(contacts, Vector3D::Zero(), kRadius, 10));
  ASSERT_GT(truth, 0.0);
  EXPECT_FALSE(r.joggled);
  EXPECT_NEAR(r.epsilon, truth, kExactRelative * truth);
  RecordProperty("epsilon", std::to_string(r.epsilon));
}

TEST(GwsEpsilon, FourTetrahedralContactsMatchBruteForce) {
  // 4 x 10 = 40 points: 3.8 million 6-subsets, a few seconds of brute force.
  const std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  ASSERT_TRUE(r.forceClosure) << r.detail;
  const double truth =
      bruteForceEpsilon(referenceWrenches(contacts, Vector3D::Zero(), kRadius, 10));
  ASSERT_GT(truth, 0.0);
  EXPECT_FALSE(r.joggled);
  EXPECT_NEAR(r.epsilon, truth, kExactRelative * truth);
}

TEST(GwsEpsilon, RandomGraspsMatchBruteForce) {
  std::mt19937 rng(20240611);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.1, 0.9);
  auto randomUnit = [&] { return Vector3D(gauss(rng), gauss(rng), gauss(rng)).normalized(); };
  int forceClosures = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Contact3D> contacts;
    const int count = 3 + trial % 2;
    for (int i = 0; i < count; ++i) {
      Contact3D c = sphereContact(randomUnit(), uniform(rng));
      c.normal = (c.normal + 0.4 * randomUnit()).normalized();  // off-centre pushes too
      contacts.push_back(c);
    }
    const Vector3D com(0.01, -0.005, 0.002);
    const GwsResult r = gwsEpsilon(contacts, com, kRadius, GwsOptions{.coneEdges = 4});
    const double truth = bruteForceEpsilon(referenceWrenches(contacts, com, kRadius, 4));
    EXPECT_NEAR(r.epsilon, truth, 1e-12 + kExactRelative * truth) << "trial " << trial;
    EXPECT_FALSE(r.joggled) << "trial " << trial;
    EXPECT_EQ(r.forceClosure, truth > 0.0) << "trial " << trial;
    forceClosures += r.forceClosure ? 1 : 0;
  }
  // Both outcomes must be exercised for the comparison to mean something.
  EXPECT_GT(forceClosures, 5);
  EXPECT_LT(forceClosures, 35);
}

TEST(GwsEpsilon, NearlyFlatInputMatchesBruteForceLazyAndWholeWithJoggle) {
  // Two antipodal contacts plus a copy of each moved by ~0.2 mm: with Qhull 2020.2 the exact
  // (merging) whole hull fails here with QH6271 (dupridge), so the fixed-seed joggle retry is
  // used. The lazily grown hull never meets the failing merge and is exact.
  auto contact = [](double px, double py, double pz, double nx, double ny, double nz) {
    Contact3D c;
    c.position = Vector3D(px, py, pz);
    c.normal = Vector3D(nx, ny, nz);
    c.mu = 0.5;
    return c;
  };
  const std::vector<Contact3D> contacts = {
      contact(0.019861031407239965, 0.044959368815569528, 0.0091757608483559617,
              -0.39722062814479925, -0.89918737631139045, -0.18351521696711923),
      contact(-0.019861031407239965, -0.044959368815569528, -0.0091757608483559617,
              0.39722062814479925, 0.89918737631139045, 0.18351521696711923),
      contact(0.019896143526838061, 0.044788633149201486, 0.0094282651469382514,
              -0.39710529378657061, -0.89920084991240368, -0.1836987130153411),
      contact(-0.019801494080376687, -0.044759903165769256, -0.0092363935045969882,
              0.39722062814479925, 0.89918737631139045, 0.18351521696711923)};
  const GwsResult lazy = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  const GwsResult r =
      gwsEpsilon(contacts, Vector3D::Zero(), kRadius, GwsOptions{.hull = GwsHull::kWhole});
  EXPECT_TRUE(r.wholeHull);
  // Joggle moves the points by ~1e-10, so epsilon is only that accurate (2e-8 relative here).
  EXPECT_TRUE(r.joggled) << "Qhull now builds this hull exactly; pick another input to keep "
                            "the joggle fallback covered";
  ASSERT_TRUE(r.forceClosure) << r.detail;
  const double truth =
      bruteForceEpsilon(referenceWrenches(contacts, Vector3D::Zero(), kRadius, 10));
  EXPECT_NEAR(r.epsilon, truth, 1e-6 * truth);
  EXPECT_EQ(
      gwsEpsilon(contacts, Vector3D::Zero(), kRadius, GwsOptions{.hull = GwsHull::kWhole}).epsilon,
      r.epsilon);
  EXPECT_FALSE(lazy.wholeHull);
  EXPECT_FALSE(lazy.joggled);
  EXPECT_NEAR(lazy.epsilon, truth, kExactRelative * truth);
}

TEST(GwsEpsilon, IndependentOfContactOrder) {
  std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  const GwsResult reference = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  std::sort(contacts.begin(), contacts.end(), [](const Contact3D& a, const Contact3D& b) {
    return a.position.x() < b.position.x() ||
           (a.position.x() == b.position.x() && a.position.y() < b.position.y());
  });
  int permutations = 0;
  do {
    const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
    EXPECT_EQ(r.epsilon, reference.epsilon);
    EXPECT_EQ(r.facets, reference.facets);
    ++permutations;
  } while (std::next_permutation(
      contacts.begin(), contacts.end(), [](const Contact3D& a, const Contact3D& b) {
        return a.position.x() < b.position.x() ||
               (a.position.x() == b.position.x() && a.position.y() < b.position.y());
      }));
  EXPECT_EQ(permutations, 24);
}

TEST(GwsEpsilon, DuplicateContactsAreMerged) {
  const std::vector<Contact3D> contacts = equatorGrasp(0.6);
  const GwsResult reference = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  std::vector<Contact3D> doubled = contacts;
  doubled.push_back(contacts[0]);
  Contact3D nearCopy = contacts[2];
  nearCopy.position.x() += 4e-10;
  nearCopy.normal.z() += 3e-10;
  doubled.insert(doubled.begin(), nearCopy);
  const GwsResult r = gwsEpsilon(doubled, Vector3D::Zero(), kRadius);
  EXPECT_NEAR(r.epsilon, reference.epsilon, 1e-12);
  EXPECT_EQ(r.points, reference.points);
  // An exact copy changes nothing at all.
  std::vector<Contact3D> exact = contacts;
  exact.push_back(contacts[1]);
  exact.push_back(contacts[1]);
  EXPECT_EQ(gwsEpsilon(exact, Vector3D::Zero(), kRadius).epsilon, reference.epsilon);
}

TEST(GwsEpsilon, DoublingRadiusHalvesTorqueRows) {
  const std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  const auto w1 = contactWrenches(contacts, Vector3D::Zero(), kRadius);
  const auto w2 = contactWrenches(contacts, Vector3D::Zero(), 2.0 * kRadius);
  ASSERT_EQ(w1.size(), w2.size());
  for (std::size_t i = 0; i < w1.size(); ++i) {
    EXPECT_TRUE((w2[i].head<3>().array() == w1[i].head<3>().array()).all());
    EXPECT_TRUE((w2[i].tail<3>().array() == 0.5 * w1[i].tail<3>().array()).all());
  }
}

TEST(GwsEpsilon, DoublingRadiusBoundsEpsilon) {
  // With D = diag(I, I/2) the new hull is D W. A ball of radius e in W maps into D W and covers a
  // ball of radius e/2; D^-1 stretches by at most 2. Hence eps(r)/2 <= eps(2r) <= eps(r).
  for (const auto& contacts : {equatorGrasp(0.6), tetrahedralGrasp(0.3)}) {
    const double e1 = gwsEpsilon(contacts, Vector3D::Zero(), kRadius).epsilon;
    const double e2 = gwsEpsilon(contacts, Vector3D::Zero(), 2.0 * kRadius).epsilon;
    ASSERT_GT(e1, 0.0);
    EXPECT_LE(e2, e1 * (1 + 1e-12));
    EXPECT_GE(e2, 0.5 * e1 * (1 - 1e-12));
  }
}

TEST(GwsEpsilon, ScalingTheWholeGraspKeepsEpsilon) {
  // (p - c) / r is unchanged when p, c and r are all doubled (exactly, in binary).
  const Vector3D com(0.004, -0.003, 0.001);
  std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  const double e1 = gwsEpsilon(contacts, com, kRadius).epsilon;
  for (Contact3D& c : contacts) c.position *= 2.0;
  EXPECT_EQ(gwsEpsilon(contacts, 2.0 * com, 2.0 * kRadius).epsilon, e1);
}

TEST(GwsEpsilon, MeasuredNormalForcesScaleEpsilon) {
  std::vector<Contact3D> contacts = equatorGrasp(0.6);
  const GwsOptions measured{.force = GwsForce::kMeasuredNormalForce};
  const double unit = gwsEpsilon(contacts, Vector3D::Zero(), kRadius).epsilon;
  EXPECT_EQ(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, measured).epsilon, unit);
  for (Contact3D& c : contacts) c.normalForce = 3.0;
  EXPECT_NEAR(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, measured).epsilon, 3.0 * unit,
              1e-12 * unit);
  // A contact without force adds nothing.
  std::vector<Contact3D> withIdle = equatorGrasp(0.6);
  Contact3D idle = sphereContact(Vector3D::UnitZ(), 0.6);
  idle.normalForce = 0.0;
  withIdle.push_back(idle);
  EXPECT_EQ(gwsEpsilon(withIdle, Vector3D::Zero(), kRadius, measured).epsilon, unit);
}

TEST(GwsEpsilon, ConcurrentCallsAgree) {
  const std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  const GwsResult reference = gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
  constexpr int kThreads = 4;
  constexpr int kRepeats = 8;
  std::vector<std::vector<double>> results(kThreads);
  {
    std::vector<std::jthread> threads;
    threads.reserve(kThreads);
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&contacts, &out = results[t]] {
        for (int i = 0; i < kRepeats; ++i) {
          out.push_back(gwsEpsilon(contacts, Vector3D::Zero(), kRadius).epsilon);
        }
      });
    }
  }
  for (const auto& perThread : results) {
    ASSERT_EQ(perThread.size(), static_cast<std::size_t>(kRepeats));
    for (double e : perThread) EXPECT_EQ(e, reference.epsilon);
  }
}

// ---- The paper's Q_GWS: cones on the measured contact forces, the VisGraB-era jitter rule ----

// A contact on the sphere in direction u that applies `force` (normal and friction) to it.
Contact3D forceContact(const Vector3D& u, const Vector3D& force, double mu) {
  Contact3D c = sphereContact(u, mu);
  c.force = force;
  c.normalForce = force.dot(c.normal);
  return c;
}

// Eq. 6 with the cone centred on the force f (written independently of the library, like
// referenceWrenches): edges |f| (f/|f| + mu R(2 pi k/m, f/|f|) t).
std::vector<Wrench6D> referenceForceWrenches(const std::vector<Contact3D>& contacts,
                                             const Vector3D& c, double r, int edges) {
  std::vector<Contact3D> axes = contacts;
  for (Contact3D& k : axes) k.normal = k.force.normalized();
  std::vector<Wrench6D> points = referenceWrenches(axes, c, r, edges);
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] *= contacts[i / static_cast<std::size_t>(edges)].force.norm();
  }
  return points;
}

const GwsOptions kPaper{.force = GwsForce::kMeasuredForce};

// Three contacts 120 degrees apart on the equator, each pushing with its own force (different
// magnitudes, tilted out of the normal by friction).
std::vector<Contact3D> paperThreeContacts() {
  std::vector<Contact3D> contacts;
  const std::array<Vector3D, 3> friction = {Vector3D(0, 0, 0.4), Vector3D(0, 0.1, -0.2),
                                            Vector3D(0, 0, 0.1)};
  const std::array<double, 3> magnitude = {2.0, 1.0, 3.5};
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * kPi * i / 3.0;
    const Vector3D u(std::cos(a), std::sin(a), 0.0);
    contacts.push_back(forceContact(u, -magnitude[i] * u + friction[i], 0.5));
  }
  return contacts;
}

TEST(GwsPaper, EqualForcesOnTheNormalsScaleTheUnitEpsilon) {
  // Worked by hand: with f_i = F n_i every edge wrench is F times the unit one, so the hull is
  // F times the unit hull and epsilon is F times the unit epsilon.
  std::vector<Contact3D> contacts = equatorGrasp(0.6);
  for (Contact3D& c : contacts) c.force = 2.5 * c.normal;
  const double unit = gwsEpsilon(contacts, Vector3D::Zero(), kRadius).epsilon;
  ASSERT_GT(unit, 0.0);
  EXPECT_NEAR(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper).epsilon, 2.5 * unit,
              1e-12 * unit);
}

TEST(GwsPaper, ThreeContactsAt120DegreesWithDifferentForcesMatchBruteForce) {
  const std::vector<Contact3D> contacts = paperThreeContacts();
  const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper);
  ASSERT_TRUE(r.forceClosure) << r.detail;
  EXPECT_EQ(r.cones, 3);
  EXPECT_EQ(r.points, 30);
  const double truth =
      bruteForceEpsilon(referenceForceWrenches(contacts, Vector3D::Zero(), kRadius, 10));
  ASSERT_GT(truth, 0.0);
  EXPECT_NEAR(r.epsilon, truth, kExactRelative * truth);
  // The definition matters: neither the unit cones nor the measured normal forces give it.
  const double unit = gwsEpsilon(contacts, Vector3D::Zero(), kRadius).epsilon;
  const double normal = gwsEpsilon(contacts, Vector3D::Zero(), kRadius,
                                   GwsOptions{.force = GwsForce::kMeasuredNormalForce})
                            .epsilon;
  EXPECT_GT(std::abs(r.epsilon - unit), 1e-3 * truth);
  EXPECT_GT(std::abs(r.epsilon - normal), 1e-3 * truth);
  RecordProperty("epsilon", std::to_string(r.epsilon));
}

TEST(GwsPaper, ForcesBelowTheThresholdAreSkipped) {
  std::vector<Contact3D> contacts = paperThreeContacts();
  const double reference = gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper).epsilon;
  contacts.push_back(
      forceContact(Vector3D::UnitZ(), Vector3D(0, 0, -0.5 * rw::graspplanning::kGwsMinForce), 0.5));
  EXPECT_EQ(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper).epsilon, reference);
  contacts.back().force.z() = std::numeric_limits<double>::quiet_NaN();
  expectZero(gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper), GwsStatus::kInvalidInput);
}

// Uniform in [-a, a] from the top 53 bits of one 64-bit Mersenne Twister draw (the documented
// rule, written here again).
double referenceJitter(std::mt19937_64& rng, double a) {
  return a * (2.0 * std::ldexp(static_cast<double>(rng() >> 11), -53) - 1.0);
}

TEST(GwsPaper, TwoAntipodalContactsGetJitteredCopies) {
  // Antipodal along x, squeezed with 2 N and 3 N (the forces need not balance for the measure).
  const std::vector<Contact3D> two = {
      forceContact(Vector3D::UnitX(), Vector3D(-3.0, 0.0, 0.2), 0.6),
      forceContact(-Vector3D::UnitX(), Vector3D(2.0, 0.1, 0.0), 0.6)};
  // Without the rule the wrenches span 5 dimensions: no torque about the x axis.
  expectZero(gwsEpsilon(two, Vector3D::Zero(), kRadius, kPaper), GwsStatus::kFlat);

  GwsOptions rule = kPaper;
  rule.duplicateBelow = 4;
  const GwsResult r = gwsEpsilon(two, Vector3D::Zero(), kRadius, rule);
  ASSERT_TRUE(r.forceClosure) << rw::graspplanning::toString(r.status) << ": " << r.detail;
  EXPECT_EQ(r.cones, 4);
  EXPECT_EQ(r.points, 40);

  // The same jitter built independently: canonical order is by position (x first), so the
  // contact at -x comes first; per contact three axis draws, then three position draws.
  std::vector<Contact3D> ordered = {two[1], two[0]};
  std::mt19937_64 rng(rw::graspplanning::kGwsJitterSeed);
  std::vector<Contact3D> jittered;
  for (const Contact3D& c : ordered) {
    jittered.push_back(c);
    Contact3D copy = c;
    Vector3D axis = c.force.normalized();
    for (int k = 0; k < 3; ++k) axis(k) += referenceJitter(rng, 0.1);
    for (int k = 0; k < 3; ++k) copy.position(k) += referenceJitter(rng, 0.002);
    copy.force = c.force.norm() * axis.normalized();
    jittered.push_back(copy);
  }
  const double truth =
      bruteForceEpsilon(referenceForceWrenches(jittered, Vector3D::Zero(), kRadius, 10));
  ASSERT_GT(truth, 0.0);
  EXPECT_NEAR(r.epsilon, truth, 1e-9 * truth);

  // Bounds by hand: a ball of radius epsilon fits in the hull, so epsilon is at most the largest
  // torque about x over r of any edge, |p_y f_z - p_z f_y| / r. The originals lie on the x axis
  // (no such torque); the copies have |p_y|, |p_z| <= 2 mm, and |f_y|, |f_z| <= |f| (|a_y| + mu)
  // where the jittered axis has |a_y|, |a_z| <= (0.07 + 0.1) / 0.89 (both forces are within 0.07
  // of the x axis per component, and |a_x| >= 0.99 - 0.1 before renormalising).
  const double fMax = std::hypot(3.0, 0.2);
  const double torqueBound = 2.0 * 0.002 * fMax * ((0.07 + 0.1) / 0.89 + 0.6) / kRadius;
  EXPECT_LE(r.epsilon, torqueBound);
  EXPECT_GT(r.epsilon, 1e-4);
  RecordProperty("epsilon", std::to_string(r.epsilon));

  // Deterministic: again, in reverse order, and in other threads.
  const std::vector<Contact3D> reversed = {two[1], two[0]};
  EXPECT_EQ(gwsEpsilon(two, Vector3D::Zero(), kRadius, rule).epsilon, r.epsilon);
  EXPECT_EQ(gwsEpsilon(reversed, Vector3D::Zero(), kRadius, rule).epsilon, r.epsilon);
  std::vector<double> inThreads(3, 0.0);
  {
    std::vector<std::jthread> threads;
    for (double& out : inThreads) {
      threads.emplace_back(
          [&two, &rule, &out] { out = gwsEpsilon(two, Vector3D::Zero(), kRadius, rule).epsilon; });
    }
  }
  for (double e : inThreads) EXPECT_EQ(e, r.epsilon);
}

TEST(GwsPaper, FourContactsAreNotJittered) {
  std::vector<Contact3D> contacts = tetrahedralGrasp(0.3);
  for (Contact3D& c : contacts) c.force = 1.5 * c.normal;
  GwsOptions rule = kPaper;
  rule.duplicateBelow = 4;
  const GwsResult r = gwsEpsilon(contacts, Vector3D::Zero(), kRadius, rule);
  EXPECT_EQ(r.cones, 4);
  EXPECT_EQ(r.epsilon, gwsEpsilon(contacts, Vector3D::Zero(), kRadius, kPaper).epsilon);
}

TEST(GwsPaper, PermutedContactsGiveIdenticalValues) {
  // Five contacts, two of them in one cluster, with merging and the jitter rule on: every
  // permutation gives the same bits.
  std::vector<Contact3D> contacts = paperThreeContacts();
  contacts.push_back(forceContact(Vector3D(0.2, 0.1, 1.0), Vector3D(0.0, 0.05, -1.0), 0.5));
  contacts.push_back(forceContact(Vector3D(-0.3, 0.1, -1.0), Vector3D(0.1, 0.0, 0.8), 0.5));
  contacts[1].cluster = 7;
  contacts[3].cluster = 7;
  GwsOptions options = kPaper;
  options.mergeClusters = true;
  options.duplicateBelow = 5;  // 4 cones after merging: jittered
  options.coneEdges = 6;       // 48 points keep 120 hulls quick
  const GwsResult reference = gwsEpsilon(contacts, Vector3D::Zero(), kRadius, options);
  ASSERT_TRUE(reference.forceClosure);
  EXPECT_EQ(reference.cones, 8);
  std::vector<int> order = {0, 1, 2, 3, 4};
  int permutations = 0;
  do {
    std::vector<Contact3D> permuted;
    for (int i : order) permuted.push_back(contacts[static_cast<std::size_t>(i)]);
    const GwsResult r = gwsEpsilon(permuted, Vector3D::Zero(), kRadius, options);
    EXPECT_EQ(r.epsilon, reference.epsilon);
    EXPECT_EQ(r.facets, reference.facets);
    ++permutations;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(permutations, 120);
}

TEST(GwsPaper, MergingAClusterGivesOneConeAtTheForceWeightedMean) {
  // Two contacts of one finger link, 1 N and 3 N on the same axis: one cone of 4 N at the
  // 1:3 point between them.
  std::vector<Contact3D> contacts = paperThreeContacts();
  Contact3D a = contacts[0];
  Contact3D b = contacts[0];
  a.position += Vector3D(0.0, 0.004, 0.0);
  b.position += Vector3D(0.0, -0.002, 0.002);
  const Vector3D axis = contacts[0].force.normalized();
  a.force = 1.0 * axis;
  b.force = 3.0 * axis;
  a.cluster = 0;
  b.cluster = 0;
  Contact3D merged = contacts[0];
  merged.position = (1.0 * a.position + 3.0 * b.position) / 4.0;
  merged.force = 4.0 * axis;
  GwsOptions merge = kPaper;
  merge.mergeClusters = true;
  const GwsResult r = gwsEpsilon(std::vector<Contact3D>{a, b, contacts[1], contacts[2]},
                                 Vector3D::Zero(), kRadius, merge);
  EXPECT_EQ(r.cones, 3);
  const double expected = gwsEpsilon(std::vector<Contact3D>{merged, contacts[1], contacts[2]},
                                     Vector3D::Zero(), kRadius, kPaper)
                              .epsilon;
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(r.epsilon, expected, 1e-12 * expected);
  // Without merging both cones stay.
  EXPECT_EQ(gwsEpsilon(std::vector<Contact3D>{a, b, contacts[1], contacts[2]}, Vector3D::Zero(),
                       kRadius, kPaper)
                .cones,
            4);
}

TEST(GwsPaper, NegativeDuplicateBelowIsAProgrammerError) {
  EXPECT_THROW(
      gwsEpsilon(equatorGrasp(0.6), Vector3D::Zero(), kRadius, GwsOptions{.duplicateBelow = -1}),
      std::invalid_argument);
}

TEST(GwsLazyHull, EqualsTheWholeHullOnRandomGrasps) {
  // Both exact: the lazy hull's epsilon is the whole hull's to 1e-12 of the largest wrench, on
  // 60 random grasps of 2-8 contacts (measured forces, the jitter rule), both outcomes included.
  std::mt19937 rng(20261124);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.2, 3.0);
  auto randomUnit = [&] { return Vector3D(gauss(rng), gauss(rng), gauss(rng)).normalized(); };
  int forceClosures = 0;
  int lazy = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<Contact3D> contacts;
    const int count = 2 + trial % 7;
    for (int i = 0; i < count; ++i) {
      const Vector3D u = randomUnit();
      const Vector3D f = uniform(rng) * (-u + 0.3 * randomUnit());
      contacts.push_back(forceContact(u, f, 0.3 + 0.1 * (trial % 5)));
    }
    GwsOptions options = kPaper;
    options.duplicateBelow = 4;
    const GwsResult a = gwsEpsilon(contacts, Vector3D(0.003, 0, -0.002), kRadius, options);
    options.hull = GwsHull::kWhole;
    const GwsResult b = gwsEpsilon(contacts, Vector3D(0.003, 0, -0.002), kRadius, options);
    double maxNorm = 0.0;
    for (const Wrench6D& w : contactWrenches(contacts, Vector3D::Zero(), kRadius, kPaper)) {
      maxNorm = std::max(maxNorm, w.norm());
    }
    EXPECT_NEAR(a.epsilon, b.epsilon, 1e-12 * 2.0 * maxNorm) << "trial " << trial;
    EXPECT_EQ(a.forceClosure, b.forceClosure) << "trial " << trial;
    EXPECT_TRUE(b.wholeHull);
    forceClosures += a.forceClosure ? 1 : 0;
    lazy += a.wholeHull ? 0 : 1;
  }
  EXPECT_GT(forceClosures, 10);
  EXPECT_LT(forceClosures, 55);
  EXPECT_GT(lazy, 50);
}

TEST(GwsLazyHull, GrowsAFlatStart) {
  // A = (1, ..., 1) and -A win all 12 axis directions, so the start is a segment; it must grow
  // along its flat directions into the small cross-polytope around the origin.
  std::vector<Wrench6D> points = {Wrench6D::Ones(), -Wrench6D::Ones()};
  for (int i = 0; i < 6; ++i) {
    points.emplace_back(0.1 * Wrench6D::Unit(i));
    points.emplace_back(-0.1 * Wrench6D::Unit(i));
  }
  const GwsResult lazy = gwsEpsilonOfWrenches(points);
  const GwsResult whole = gwsEpsilonOfWrenches(points, GwsHull::kWhole);
  ASSERT_TRUE(whole.forceClosure);
  EXPECT_FALSE(lazy.wholeHull);
  EXPECT_NEAR(lazy.epsilon, whole.epsilon, kExactRelative * whole.epsilon);
  EXPECT_NEAR(lazy.epsilon, bruteForceEpsilon(points), kExactRelative * whole.epsilon);
}

}  // namespace
