#include "visgrab/grasp/grasp_request.hpp"

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
  }
  return "raw";
}

}  // namespace visgrab::grasp
