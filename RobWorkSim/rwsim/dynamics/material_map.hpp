#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rwsim::dynamics {

/// Friction between two materials (RobWork's FrictionData): a type ("Coulomb" or a custom name)
/// and named parameter vectors in file order (e.g. Mu, Mud).
struct FrictionData {
  /// "Coulomb" or the custom type name.
  std::string type = "Coulomb";
  /// Named parameter vectors in file order.
  std::vector<std::pair<std::string, std::vector<double>>> parameters;
  /// Coulomb coefficient: the first value of the first parameter, as RobWork uses it
  /// (MaterialMap::kDefaultMu when there is no value).
  double mu() const;
};

/// Materials, object types, the friction map and the restitution map of a dynamic workcell.
class MaterialMap {
 public:
  /// RobWork's friction for a pair missing from the map (Coulomb, reference §2.5).
  static constexpr double kDefaultMu = 0.4;

  /// Declares a material; returns false if it already exists (RobWork ignores duplicates).
  bool addMaterial(const std::string& name, const std::string& description = {});
  /// True if declared.
  bool hasMaterial(const std::string& name) const;
  /// Declared materials in order.
  const std::vector<std::string>& materials() const { return materials_; }
  /// Sets the default material. Precondition: declared.
  void setDefaultMaterial(const std::string& name) { defaultMaterial_ = name; }
  /// The default material (empty if none).
  const std::string& defaultMaterial() const { return defaultMaterial_; }

  /// Declares an object type (for restitution); false if it exists.
  bool addObjectType(const std::string& name);
  /// True if declared.
  bool hasObjectType(const std::string& name) const;
  /// Sets the default object type.
  void setDefaultObjectType(const std::string& name) { defaultObjectType_ = name; }
  /// The default object type (empty if none).
  const std::string& defaultObjectType() const { return defaultObjectType_; }

  /// Sets the friction of an unordered pair (replaces an earlier entry; the loader keeps the
  /// first entry as RobWork does). Materials are not checked.
  void setFriction(const std::string& a, const std::string& b, FrictionData data);
  /// The friction data of a pair, if given.
  const FrictionData* friction(const std::string& a, const std::string& b) const;
  /// Coulomb mu of a pair; kDefaultMu when the pair is not in the map.
  double mu(const std::string& a, const std::string& b) const;
  /// Number of friction pairs.
  std::size_t frictionPairCount() const { return friction_.size(); }

  /// Sets the restitution coefficient of an unordered pair of object types.
  void setRestitution(const std::string& a, const std::string& b, double cr);
  /// Restitution of a pair of object types; 0 when not in the map.
  double restitution(const std::string& a, const std::string& b) const;

 private:
  static std::pair<std::string, std::string> key(const std::string& a, const std::string& b);

  std::vector<std::string> materials_;
  std::string defaultMaterial_;
  std::vector<std::string> objectTypes_;
  std::string defaultObjectType_;
  std::map<std::pair<std::string, std::string>, FrictionData> friction_;
  std::map<std::pair<std::string, std::string>, double> restitution_;
};

}  // namespace rwsim::dynamics
