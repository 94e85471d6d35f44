#include "visgrab/importers/acronym.hpp"

#include <cmath>
#include <fstream>

#include "visgrab/importers/hdf5_file.hpp"
#include "visgrab/importers/json_value.hpp"
#include "visgrab/importers/npy.hpp"

namespace visgrab::importers {

namespace {

constexpr const char* kLabelsKey = "grasps/qualities/flex/object_in_gripper";

bool isJson(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ImportError(file.string() + ": cannot open the file");
  char first = '\0';
  while (in.get(first) && (first == ' ' || first == '\n' || first == '\r' || first == '\t')) {
  }
  return in && first == '{';
}

const JsonValue& graspgenGrasps(const JsonValue& doc, const std::string& name) {
  const JsonValue* grasps = doc.find("grasps");
  if (grasps == nullptr || grasps->kind != JsonValue::Kind::kObject) {
    throw ImportError(name +
                      ": no object \"grasps\" (expected GraspGen's layout {\"object\": "
                      "{...}, \"grasps\": {\"transforms\": [...], \"object_in_gripper\": "
                      "[...]}})");
  }
  return *grasps;
}

JsonValue readJson(const std::filesystem::path& file) {
  return parseJson(readFileBytes(file, 4 * kMaxArrayBytes), file.string());
}

NdArray graspgenTransforms(const JsonValue& doc, const std::string& name) {
  const JsonValue* list = graspgenGrasps(doc, name).find("transforms");
  if (list == nullptr || list->kind != JsonValue::Kind::kArray) {
    throw ImportError(name + ": no array \"grasps.transforms\" (expected N 4x4 matrices)");
  }
  NdArray out;
  out.dtype = "json";
  out.shape = {list->items.size(), 4, 4};
  out.values.reserve(16 * list->items.size());
  for (std::size_t i = 0; i < list->items.size(); ++i) {
    const JsonValue& m = list->items[i];
    const std::string where = name + ":" + std::to_string(m.line) + ":" + std::to_string(m.column) +
                              ": grasps.transforms[" + std::to_string(i) + "]";
    if (m.kind != JsonValue::Kind::kArray || m.items.size() != 4) {
      throw ImportError(where + " is not a 4x4 matrix (expected 4 rows of 4 numbers)");
    }
    for (const JsonValue& row : m.items) {
      if (row.kind != JsonValue::Kind::kArray || row.items.size() != 4) {
        throw ImportError(where + " is not a 4x4 matrix (expected 4 rows of 4 numbers)");
      }
      for (const JsonValue& v : row.items) {
        if (v.kind != JsonValue::Kind::kNumber) {
          throw ImportError(where + " holds a " + jsonKindName(v.kind) + ", expected numbers");
        }
        out.values.push_back(v.number);
      }
    }
  }
  return out;
}

double positiveScalar(const Hdf5File& h5, const std::string& key, bool zeroAllowed) {
  const NdArray a = h5.numbers(key);
  if (a.values.size() != 1) {
    throw ImportError(h5.name() + ": dataset '" + key + "' has shape " + a.shapeText() +
                      ", expected one number");
  }
  const double v = a.values[0];
  if (!std::isfinite(v) || v < 0.0 || (!zeroAllowed && v == 0.0)) {
    throw ImportError(
        h5.name() + ": dataset '" + key + "' is " + std::to_string(v) +
        (zeroAllowed ? ", expected a finite number >= 0" : ", expected a finite number > 0"));
  }
  return v;
}

}  // namespace

NdArray readAcronymTransforms(const std::filesystem::path& file) {
  if (isJson(file)) return graspgenTransforms(readJson(file), file.string());
  return Hdf5File::open(file).numbers("grasps/transforms", 3, "N x 4 x 4 transforms");
}

std::vector<int> readAcronymLabels(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::vector<double> values;
  std::size_t n = 0;
  std::string key;
  if (isJson(file)) {
    const JsonValue doc = readJson(file);
    n = graspgenTransforms(doc, name).shape[0];
    key = "grasps.object_in_gripper";
    const JsonValue* list = graspgenGrasps(doc, name).find("object_in_gripper");
    if (list == nullptr || list->kind != JsonValue::Kind::kArray) {
      throw ImportError(name + ": no array \"" + key + "\" (expected one label per grasp)");
    }
    for (const JsonValue& v : list->items) {
      if (v.kind == JsonValue::Kind::kBool) {
        values.push_back(v.flag ? 1.0 : 0.0);
      } else if (v.kind == JsonValue::Kind::kNumber) {
        values.push_back(v.number);
      } else {
        throw ImportError(name + ":" + std::to_string(v.line) + ":" + std::to_string(v.column) +
                          ": " + key + " holds a " + jsonKindName(v.kind) +
                          ", expected true/false or 0/1");
      }
    }
  } else {
    const Hdf5File h5 = Hdf5File::open(file);
    n = h5.numbers("grasps/transforms", 3, "N x 4 x 4 transforms").shape[0];
    key = kLabelsKey;
    const NdArray labels = h5.numbers(key, 1, "one label per grasp");
    values = labels.values;
  }
  if (values.size() != n) {
    throw ImportError(name + ": " + key + " has " + std::to_string(values.size()) +
                      " labels, expected " + std::to_string(n) + " (one per grasp)");
  }
  std::vector<int> out;
  out.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] != 0.0 && values[i] != 1.0) {
      throw ImportError(name + ": " + key + "[" + std::to_string(i) + "] is " +
                        std::to_string(values[i]) + ", expected 0 or 1");
    }
    out.push_back(values[i] == 1.0 ? 1 : 0);
  }
  return out;
}

AcronymObject readAcronymObject(const std::filesystem::path& file) {
  const Hdf5File h5 = Hdf5File::open(file);
  AcronymObject o;
  o.file = h5.text("object/file");
  if (o.file.empty()) throw ImportError(file.string() + ": dataset 'object/file' is empty");
  o.scale = positiveScalar(h5, "object/scale", false);
  o.density = positiveScalar(h5, "object/density", false);
  o.friction = positiveScalar(h5, "object/friction", true);
  o.mass = positiveScalar(h5, "object/mass", false);
  const NdArray com = h5.numbers("object/com", 1, "3 numbers");
  if (com.shape[0] != 3 || !Eigen::Vector3d::Map(com.values.data()).allFinite()) {
    throw ImportError(file.string() + ": dataset 'object/com' has shape " + com.shapeText() +
                      ", expected 3 finite numbers");
  }
  o.com = Eigen::Vector3d::Map(com.values.data());
  const NdArray inertia = h5.numbers("object/inertia", 2, "3 x 3");
  if (inertia.shape[0] != 3 || inertia.shape[1] != 3) {
    throw ImportError(file.string() + ": dataset 'object/inertia' has shape " +
                      inertia.shapeText() + ", expected (3, 3)");
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      o.inertia(r, c) = inertia.values[static_cast<std::size_t>(3 * r + c)];
  }
  if (!o.inertia.allFinite() || (o.inertia - o.inertia.transpose()).cwiseAbs().maxCoeff() >
                                    1e-9 * std::max(1.0, o.inertia.cwiseAbs().maxCoeff())) {
    throw ImportError(file.string() +
                      ": dataset 'object/inertia' is not a finite symmetric 3 x 3 matrix");
  }
  if (h5.hasDataset("object/volume")) o.volume = positiveScalar(h5, "object/volume", false);
  return o;
}

}  // namespace visgrab::importers
