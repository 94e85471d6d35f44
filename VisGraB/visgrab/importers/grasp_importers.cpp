#include "visgrab/importers/grasp_importers.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

#include "visgrab/importers/acronym.hpp"
#include "visgrab/importers/npy.hpp"
#include "visgrab/importers/npz.hpp"

namespace visgrab::importers {

std::string ImportRejection::format() const {
  return file + ": grasp " + std::to_string(index) + ": " + message;
}

std::optional<rw::math::Rotation3D> checkedRotation(const Eigen::Matrix3d& R, std::string& why) {
  if (!R.allFinite()) {
    why = "the rotation has a non-finite value (NaN or infinity)";
    return std::nullopt;
  }
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (error > kRotationTolerance) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer),
                  "the rotation is not orthonormal: max |R^T R - I| = %.3g (expected at most %g)",
                  error, kRotationTolerance);
    why = buffer;
    return std::nullopt;
  }
  if (R.determinant() < 0.0) {
    why = "the rotation is a reflection (determinant -1), expected a proper rotation";
    return std::nullopt;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return rw::math::Rotation3D(svd.matrixU() * svd.matrixV().transpose());
}

namespace {

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", v);
  return buffer;
}

// A grasp with the fields every importer sets.
grasp::GraspRequest jawGrasp(std::size_t index, const std::string& file,
                             const ImportContext& context) {
  grasp::GraspRequest r;
  r.kind = grasp::GraspKind::kJaw;
  r.sceneId = context.sceneId;
  r.method = context.method;
  r.id = std::to_string(index);
  r.sourceFile = file;
  return r;
}

// Why `width` is not an opening the hand has, or empty.
std::string widthProblem(double width, const ImportContext& context) {
  if (!std::isfinite(width)) return "the width is not finite (NaN or infinity)";
  if (width < 0.0) return "width " + number(width) + " m is negative, expected an opening in m";
  if (width > context.jaw.stroke) {
    return "width " + number(width) + " m is more than hand \"" + context.hand +
           "\" opens (expected 0 to its stroke " + number(context.jaw.stroke) + " m)";
  }
  return "";
}

// A 4x4 homogeneous transform at flat offset `at` of `values` (row-major), checked.
std::optional<rw::math::Transform3D> homogeneous(const std::vector<double>& values, std::size_t at,
                                                 std::string& why) {
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = values[at + static_cast<std::size_t>(4 * r + c)];
  }
  if (!M.allFinite()) {
    why = "the transform has a non-finite value (NaN or infinity)";
    return std::nullopt;
  }
  if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6) {
    why = "the transform's last row is not 0 0 0 1 (expected a 4x4 homogeneous transform)";
    return std::nullopt;
  }
  const auto R = checkedRotation(M.topLeftCorner<3, 3>(), why);
  if (!R) return std::nullopt;
  return rw::math::makeTransform(*R, M.topRightCorner<3, 1>());
}

void requireShape(const NdArray& a, const std::vector<std::size_t>& tail, const std::string& where,
                  const std::string& expected) {
  bool ok = a.shape.size() == tail.size() + 1;
  for (std::size_t k = 0; ok && k < tail.size(); ++k) ok = a.shape[k + 1] == tail[k];
  if (!ok) throw ImportError(where + " has shape " + a.shapeText() + ", expected " + expected);
}

void requireLength(const NdArray& a, std::size_t n, const std::string& where) {
  if (a.shape.size() != 1 || a.shape[0] != n) {
    throw ImportError(where + " has shape " + a.shapeText() + ", expected (" + std::to_string(n) +
                      ",): one value per grasp");
  }
}

// Transforms N x 4 x 4 placed as jaw grasps: X_W_jaw = X_W_frame X_frame_hand T(0,0,padDepth).
ImportResult importHandTransforms(const NdArray& transforms, const std::string& file,
                                  const rw::math::Transform3D& X_W_frame,
                                  const ImportContext& context, const NdArray* scores,
                                  const NdArray* widths) {
  ImportResult out;
  const std::size_t n = transforms.shape[0];
  const rw::math::Transform3D X_hand_jaw =
      rw::math::makeTranslation(rw::math::Vector3D(0.0, 0.0, kPandaPadDepth));
  for (std::size_t i = 0; i < n; ++i) {
    std::string why;
    const auto X = homogeneous(transforms.values, 16 * i, why);
    const double width = widths != nullptr ? (*widths)[i] : kPandaOpening;
    if (X && scores != nullptr && !std::isfinite((*scores)[i])) {
      why = "the score is not finite (NaN or infinity)";
    } else if (X) {
      why = widthProblem(width, context);
    }
    if (!why.empty()) {
      out.rejected.push_back({file, i, why});
      continue;
    }
    grasp::GraspRequest r = jawGrasp(i, file, context);
    r.X_W_jaw = X_W_frame * *X * X_hand_jaw;
    r.width = width;
    if (scores != nullptr) r.score = (*scores)[i];
    out.grasps.push_back(std::move(r));
  }
  return out;
}

// The one line of numpy that writes Contact-GraspNet's output as the plain arrays.
constexpr const char* kPlainContactGraspnet =
    "np.savez(\"grasps.npz\", grasps=np.concatenate(list(pred_grasps_cam.values())), "
    "scores=np.concatenate(list(scores.values())))";

}  // namespace

ImportResult importGraspnetArray(const NdArray& array, const std::string& file,
                                 const rw::math::Transform3D& X_W_camera,
                                 const ImportContext& context) {
  requireShape(array, {17}, file,
               "(N, 17): score, width, height, depth, rotation (9, row-major), translation (3), "
               "object id per grasp (graspnetAPI's GraspGroup)");
  ImportResult out;
  const std::size_t n = array.shape[0];
  for (std::size_t i = 0; i < n; ++i) {
    const double* g = array.values.data() + 17 * i;
    std::string why;
    for (int k = 0; k < 17 && why.empty(); ++k) {
      if (!std::isfinite(g[k]))
        why = "a non-finite value (NaN or infinity) in column " + std::to_string(k) + " of 17";
    }
    Eigen::Matrix3d R_gn;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R_gn(r, c) = g[4 + 3 * r + c];
    }
    const double depth = g[3];
    std::optional<rw::math::Rotation3D> R;
    if (why.empty()) R = checkedRotation(R_gn, why);
    if (why.empty() && depth < 0.0) {
      why = "depth " + number(depth) +
            " m is negative, expected the fingertips' depth beyond "
            "the grasp point (>= 0)";
    }
    if (why.empty()) why = widthProblem(g[1], context);
    if (!why.empty()) {
      out.rejected.push_back({file, i, why});
      continue;
    }
    const rw::math::Vector3D approach = R->col(0);
    const rw::math::Vector3D closing = R->col(1);
    rw::math::Rotation3D R_cam_jaw;
    R_cam_jaw.col(0) = closing;
    R_cam_jaw.col(1) = approach.cross(closing);
    R_cam_jaw.col(2) = approach;
    const rw::math::Vector3D t(g[13], g[14], g[15]);
    const rw::math::Vector3D origin = t + (depth - context.jaw.tipDepth) * approach;
    grasp::GraspRequest r = jawGrasp(i, file, context);
    r.X_W_jaw = X_W_camera * rw::math::makeTransform(R_cam_jaw, origin);
    r.width = g[1];
    r.score = g[0];
    out.grasps.push_back(std::move(r));
  }
  return out;
}

ImportResult importGraspnet(const std::filesystem::path& file,
                            const rw::math::Transform3D& X_W_camera, const ImportContext& context) {
  return importGraspnetArray(readNpy(file), file.string(), X_W_camera, context);
}

ImportResult importContactGraspnetArrays(const NdArray& grasps, const NdArray& scores,
                                         const std::optional<NdArray>& widths,
                                         const std::string& file,
                                         const rw::math::Transform3D& X_W_camera,
                                         const ImportContext& context) {
  requireShape(grasps, {4, 4}, file + ": array 'grasps'",
               "(N, 4, 4): the Panda hand's pose in the camera frame per grasp");
  const std::size_t n = grasps.shape[0];
  requireLength(scores, n, file + ": array 'scores'");
  if (widths) requireLength(*widths, n, file + ": array 'widths'");
  return importHandTransforms(grasps, file, X_W_camera, context, &scores,
                              widths ? &*widths : nullptr);
}

ImportResult importContactGraspnet(const std::filesystem::path& file,
                                   const rw::math::Transform3D& X_W_camera,
                                   const ImportContext& context) {
  const NpzFile npz = NpzFile::open(file);
  if (npz.contains("pred_grasps_cam") && !npz.contains("grasps")) {
    throw ImportError(file.string() +
                      ": Contact-GraspNet's inference output (pred_grasps_cam: pickled Python "
                      "dicts, which this reader never loads); write the plain arrays with: " +
                      kPlainContactGraspnet +
                      " (or use visgrab.import_grasps in Python, for trusted files)");
  }
  auto read = [&](const std::string& key) {
    try {
      return npz.array(key);
    } catch (const ImportError& e) {
      const std::string what = e.what();
      if (what.find("object array") != std::string::npos) {
        throw ImportError(what + "; write the plain arrays with: " + kPlainContactGraspnet);
      }
      throw;
    }
  };
  const NdArray grasps = read("grasps");
  const NdArray scores = read("scores");
  std::optional<NdArray> widths;
  if (npz.contains("widths")) widths = read("widths");
  if (npz.contains("segments")) {
    requireLength(read("segments"), grasps.shape.empty() ? 0 : grasps.shape[0],
                  file.string() + ": array 'segments'");
  }
  return importContactGraspnetArrays(grasps, scores, widths, file.string(), X_W_camera, context);
}

ImportResult importAcronymTransforms(const NdArray& transforms, const std::string& file,
                                     const rw::math::Transform3D& X_W_mesh,
                                     const ImportContext& context) {
  requireShape(transforms, {4, 4}, file + ": grasps/transforms",
               "(N, 4, 4): the Panda hand's pose in the mesh frame per grasp");
  return importHandTransforms(transforms, file, X_W_mesh, context, nullptr, nullptr);
}

ImportResult importAcronym(const std::filesystem::path& file, const rw::math::Transform3D& X_W_mesh,
                           const ImportContext& context) {
  return importAcronymTransforms(readAcronymTransforms(file), file.string(), X_W_mesh, context);
}

}  // namespace visgrab::importers
