#include "visgrab/request/grasp_request.hpp"

namespace visgrab::grasp {

const char* kindName(GraspKind kind) {
  switch (kind) {
    case GraspKind::kRaw:
      return "raw";
    case GraspKind::kPreshape:
      return "preshape";
    case GraspKind::kPoseAndQ:
      return "pose_q";
    case GraspKind::kContacts:
      return "contacts";
    case GraspKind::kJaw:
      return "jaw";
  }
  return "raw";
}

std::optional<GraspRequest> preshapeFromContacts(const GraspRequest& contacts,
                                                 const std::string& preshape) {
  if (contacts.kind != GraspKind::kContacts || contacts.contacts.size() != 2) return std::nullopt;
  const double approachLength = contacts.approach.norm();
  if (!(approachLength > 1e-12)) return std::nullopt;
  const rw::math::Vector3D z = contacts.approach / approachLength;
  const rw::math::Vector3D across = contacts.contacts[1].position - contacts.contacts[0].position;
  const rw::math::Vector3D x = across - across.dot(z) * z;
  if (!(x.norm() > 1e-6)) return std::nullopt;
  GraspRequest out = contacts;
  out.kind = GraspKind::kPreshape;
  out.preshape = preshape;
  out.contacts.clear();
  rw::math::Rotation3D R;
  R.col(0) = x.normalized();
  R.col(2) = z;
  R.col(1) = z.cross(R.col(0));
  out.X_W_tcp = rw::math::makeTransform(
      R, 0.5 * (contacts.contacts[0].position + contacts.contacts[1].position));
  return out;
}

}  // namespace visgrab::grasp
