#include "rwsim/dynamics/constraint.hpp"

#include <algorithm>
#include <array>
#include <cctype>

namespace rwsim::dynamics {

namespace {

/// One row per ConstraintType, in enum order.
struct TypeInfo {
  ConstraintType type;
  std::string_view name;
  ConstraintDof dof;
  std::string_view dofText;
};

constexpr std::array<TypeInfo, 9> kTypes = {{
    {ConstraintType::kFixed, "Fixed", {0, 0}, "none"},
    {ConstraintType::kPrismatic, "Prismatic", {1, 0}, "translation along z"},
    {ConstraintType::kRevolute, "Revolute", {0, 1}, "rotation about z"},
    {ConstraintType::kUniversal, "Universal", {0, 2}, "rotation about x, rotation about y"},
    {ConstraintType::kSpherical, "Spherical", {0, 3}, "rotation about x, y and z"},
    {ConstraintType::kPiston, "Piston", {1, 1}, "translation along z, rotation about z"},
    {ConstraintType::kPrismaticRotoid,
     "PrismaticRotoid",
     {1, 1},
     "translation along z, rotation about x"},
    {ConstraintType::kPrismaticUniversal,
     "PrismaticUniversal",
     {1, 2},
     "translation along z, rotation about x, rotation about y"},
    {ConstraintType::kFree,
     "Free",
     {3, 3},
     "translation along x, y and z, rotation about x, y "
     "and z"},
}};
static_assert(kTypes.size() == static_cast<std::size_t>(ConstraintType::kFree) + 1,
              "one row per ConstraintType");

const TypeInfo& info(ConstraintType type) { return kTypes[static_cast<std::size_t>(type)]; }

bool sameIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

ConstraintDof constraintDof(ConstraintType type) { return info(type).dof; }

std::string_view constraintTypeName(ConstraintType type) { return info(type).name; }

std::string_view constraintDofText(ConstraintType type) { return info(type).dofText; }

std::optional<ConstraintType> constraintTypeFromName(std::string_view name) {
  for (const TypeInfo& t : kTypes) {
    if (sameIgnoringCase(t.name, name)) return t.type;
  }
  return std::nullopt;
}

std::string constraintTypeNames() {
  std::string out;
  for (const TypeInfo& t : kTypes) {
    if (!out.empty()) out += ", ";
    out += t.name;
  }
  return out;
}

}  // namespace rwsim::dynamics
