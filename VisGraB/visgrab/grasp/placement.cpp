#include "visgrab/grasp/placement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

namespace visgrab::grasp {

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

// A candidate: indices into the solutions and the three option lists, and its fingers.
struct Candidate {
  int solution = 0;
  int roll = 0;
  int backoff = 0;
  int opening = 0;
  long errorMm = 0;
  int moves = 0;
  int placement = 0;  // index of its (solution, roll, back-off) among the refitted bases
  ContactIkResult ik;

  auto key() const { return std::tie(errorMm, moves, solution, roll, backoff, opening); }
};

// Index cost of a roll: 0 for none, then one per pair of turns (+a and -a cost the same).
int rollMoves(int index) { return (index + 1) / 2; }

void checkOptions(const PlacementOptions& o) {
  for (const auto* list : {&o.approachBackoffs, &o.extraOpenings, &o.rolls}) {
    if (list->empty() || list->front() != 0.0) {
      throw std::invalid_argument("placement options: each list of moves must start with 0");
    }
  }
  if (!(o.contactSlack >= 0.0)) {
    throw std::invalid_argument("placement options: contactSlack must not be negative");
  }
}

// `ik` turned by `angle` about the line through the two contacts (both fingertips stay put).
Transform3D rolledBase(const Transform3D& X_W_base, const std::vector<DesiredContact>& contacts,
                       double angle) {
  if (angle == 0.0 || contacts.size() != 2) return X_W_base;
  const Vector3D axis = (contacts[1].position - contacts[0].position).normalized();
  const Vector3D middle = 0.5 * (contacts[0].position + contacts[1].position);
  Transform3D turn = Transform3D::Identity();
  turn.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  turn.translation() = middle - turn.linear() * middle;
  return turn * X_W_base;
}

}  // namespace

std::string Placement::describe() const {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "placement: IK solution %d, backed off %.0f mm along the approach, rolled %.0f "
                "deg, opened %.0f mm more (%d of %d candidates tested)",
                solution + 1, approachBackoff * 1e3, roll * rw::math::kRad2Deg, extraOpening * 1e3,
                tests, candidates);
  return buffer;
}

Placement placeContactGrasp(const HandGraspSetup& setup,
                            const std::vector<DesiredContact>& contacts, const Vector3D& approach,
                            const std::vector<ContactIkResult>& solutions,
                            const PlacementTest& test, const PlacementOptions& options) {
  checkOptions(options);
  if (solutions.empty() || !solutions.front().valid) {
    throw std::invalid_argument("placeContactGrasp: needs a valid contact IK solution");
  }
  const ContactIkSettings& ik = *setup.contactIk();
  Placement out;
  out.ik = solutions.front();
  out.check = test(out.ik.parameters());
  out.tests = 1;
  out.candidates = 1;
  if (!out.check.collides) {
    out.found = true;
    return out;
  }

  // Every candidate within the limits and the slack, then in the documented order. A base
  // placement (solution, roll, back-off) is refitted at once; its openings share its fingertip
  // deviation, so their q_open is solved only when they are tested.
  const Vector3D a = approach.normalized();
  const bool twoContacts = contacts.size() == 2;
  const int nSolutions =
      std::min(static_cast<int>(solutions.size()), std::max(1, options.maxSolutions));
  std::vector<Candidate> candidates;
  int placements = 0;
  for (int s = 0; s < nSolutions; ++s) {
    const ContactIkResult& base = solutions[static_cast<std::size_t>(s)];
    if (!base.valid) continue;
    const double limit = base.positionError + options.contactSlack;
    const int nRolls = twoContacts ? static_cast<int>(options.rolls.size()) : 1;
    for (int r = 0; r < nRolls; ++r) {
      const Transform3D rolled =
          rolledBase(base.X_W_base, contacts, options.rolls[static_cast<std::size_t>(r)]);
      for (int b = 0; b < static_cast<int>(options.approachBackoffs.size()); ++b) {
        Transform3D X = rolled;
        X.translation() -= options.approachBackoffs[static_cast<std::size_t>(b)] * a;
        const ContactIkResult fitted =
            (r == 0 && b == 0) ? base
                               : refitContactIk(setup, contacts, approach, base, X, ik.backoff);
        if (!fitted.valid || fitted.positionError > limit + 1e-12) continue;
        const int placement = placements++;
        for (int o = 0; o < static_cast<int>(options.extraOpenings.size()); ++o) {
          Candidate c;
          c.solution = s;
          c.roll = r;
          c.backoff = b;
          c.opening = o;
          c.moves = rollMoves(r) + b + o;
          c.placement = placement;
          if (c.moves == 0 && s == 0) continue;  // the IK's own choice, tested above
          c.errorMm = static_cast<long>(std::ceil(fitted.positionError * 1e3 - 1e-9));
          c.ik = fitted;
          candidates.push_back(std::move(c));
        }
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.key() < y.key(); });
  out.candidates += static_cast<int>(candidates.size());

  const Candidate* least = nullptr;
  rwsim::simulator::PlacementCheck leastCheck = out.check;
  const auto take = [&](const Candidate& c, const rwsim::simulator::PlacementCheck& check) {
    out.ik = c.ik;
    out.check = check;
    out.solution = c.solution;
    out.roll = twoContacts ? options.rolls[static_cast<std::size_t>(c.roll)] : 0.0;
    out.approachBackoff = options.approachBackoffs[static_cast<std::size_t>(c.backoff)];
    out.extraOpening = options.extraOpenings[static_cast<std::size_t>(c.opening)];
  };
  // The first opening tested of a base placement refits its fingers; the others reuse them.
  std::vector<const ContactIkResult*> opened(static_cast<std::size_t>(placements), nullptr);
  for (Candidate& c : candidates) {
    if (c.opening > 0) {
      // Same base and fingers at the contacts; only q_open is solved again.
      const double backoff =
          ik.backoff + options.extraOpenings[static_cast<std::size_t>(c.opening)];
      const ContactIkResult*& first = opened[static_cast<std::size_t>(c.placement)];
      if (first == nullptr) {
        c.ik = refitContactIk(setup, contacts, approach, c.ik, c.ik.X_W_base, backoff);
        first = &c.ik;
      } else {
        c.ik = reopenContactIk(setup, contacts, approach, *first, backoff);
      }
    }
    const rwsim::simulator::PlacementCheck check = test(c.ik.parameters());
    ++out.tests;
    if (!check.collides) {
      take(c, check);
      out.found = true;
      return out;
    }
    if (check.penetration < leastCheck.penetration) {
      least = &c;
      leastCheck = check;
    }
  }
  if (least != nullptr) take(*least, leastCheck);
  return out;
}

}  // namespace visgrab::grasp
