#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

/// The benchmark's 18 objects and two tables: their description (scenes/objects/objects.xml), the
/// models generated from it and the files written for the simulator and the renderer.
namespace visgrab::objects {

/// The kinds of body shape a spec can give.
enum class ShapeKind {
  kBox,       ///< A box, optionally with rounded edges in the visual mesh.
  kCylinder,  ///< A straight cylinder (a lathe with two profile points of equal radius).
  kLathe,     ///< A body of revolution given by a radius profile.
  kMesh,      ///< A closed triangle mesh read from a file (OBJ, STL, PLY through assimp).
};

/// How an object's surface is textured.
enum class PatternKind {
  kPrintedBox,    ///< Printed cardboard: blocks, stripes, logo, rows of glyphs, fine print.
  kLabelBand,     ///< A printed label band around a lathe body of plain material.
  kMetalCan,      ///< A printed metal can: the label on metal, metal lids.
  kPlainPlastic,  ///< Near-plain plastic with mottling and a little small print.
};

/// Number of PatternKind values.
inline constexpr std::size_t kPatternKindCount = 4;

/// Name of a pattern as written in objects.xml ("printed-box", ...).
std::string_view patternKindName(PatternKind kind);

/// The pattern of a name as written in objects.xml, or nullopt.
std::optional<PatternKind> patternKindFromName(std::string_view name);

/// Surface materials of the plain parts of a lathe (body or lid).
enum class SurfaceMaterial { kPlastic, kMetal, kGlass, kCardboard };

/// Number of SurfaceMaterial values.
inline constexpr std::size_t kSurfaceMaterialCount = 4;

/// Name of a material as written in objects.xml ("plastic", "metal", "glass", "cardboard").
std::string_view surfaceMaterialName(SurfaceMaterial material);

/// The material of a name as written in objects.xml, or nullopt.
std::optional<SurfaceMaterial> surfaceMaterialFromName(std::string_view name);

/// One point of a lathe's radius profile: radius r at height z (metres).
struct ProfilePoint {
  /// Height above the bottom face.
  double z = 0.0;
  /// Radius (> 0).
  double r = 0.0;
};

/// A handle on the +x side of a lathe body: a half-elliptical tube in the xz-plane.
/// Its ends sit inside the body wall; its outer surface reaches `reach` beyond the wall.
struct HandleSpec {
  /// Height of the handle's middle above the bottom face.
  double z = 0.0;
  /// Vertical distance between the centre lines of the two attachments.
  double span = 0.0;
  /// How far the handle's outer surface stands out from the body wall (x direction).
  double reach = 0.0;
  /// Diameter of the handle's tube.
  double thickness = 0.0;
};

/// How an object looks.
struct AppearanceSpec {
  /// Texture recipe.
  PatternKind pattern = PatternKind::kPlainPlastic;
  /// Seed of the texture generator.
  std::uint32_t seed = 0;
  /// Base colour of the body (linear RGB in [0, 1]).
  Eigen::Vector3f body{0.8f, 0.8f, 0.8f};
  /// Material of the plain (unprinted) body surface.
  SurfaceMaterial bodyMaterial = SurfaceMaterial::kCardboard;
  /// Print colours (at least two for printed-box, label-band and metal-can).
  std::vector<Eigen::Vector3f> palette;
  /// Lathes: the label band's lower and upper height; nullopt = the whole side.
  std::optional<std::array<double, 2>> label;
  /// Lathes: height from which the side and the top face are the lid; nullopt = no lid.
  std::optional<double> lidBottom;
  /// Colour of the lid.
  Eigen::Vector3f lid{0.7f, 0.7f, 0.7f};
  /// Material of the lid.
  SurfaceMaterial lidMaterial = SurfaceMaterial::kPlastic;
  /// Specular strength of the printed or plain surface, in [0, 1].
  float specular = 0.1f;
};

/// A mesh file named by an object spec (`<Mesh>` or `<CollisionPiece>`).
struct MeshFileSpec {
  /// The file, resolved against the spec file's folder.
  std::filesystem::path file;
  /// The file name as written in the spec.
  std::string written;
  /// Line of the element in the spec file.
  int line = 0;
};

/// The shape of a mesh object: `<Mesh file scale rpy fillHoles maxPieces concavity>`.
struct MeshShapeSpec {
  /// The mesh (its visual appearance too, when it has a texture).
  MeshFileSpec mesh;
  /// Factor from the file's units to metres (e.g. 0.001 for millimetres).
  double scale = 1.0;
  /// Rotation applied to the file's coordinates, RobWork's RPY in degrees as in workcell files
  /// (R = Rz(r) Ry(p) Rx(y)), before the object frame is placed.
  Eigen::Vector3d rpyDegrees = Eigen::Vector3d::Zero();
  /// Close small holes (each boundary loop gets a fan of triangles) instead of rejecting an
  /// open mesh.
  bool fillHoles = false;
  /// Automatic decomposition: at most this many convex pieces.
  int maxPieces = 16;
  /// Automatic decomposition: a part's hull may exceed its volume by this fraction.
  double concavity = 0.03;
  /// Convex collision pieces given in files (empty: automatic decomposition).
  std::vector<MeshFileSpec> collisionPieces;
};

/// One benchmark object as described in objects.xml.
struct ObjectSpec {
  /// Number in the paper's tables (1..18).
  int id = 0;
  /// Lower-case name (file and frame names): "amicelli", ...
  std::string name;
  /// The everyday product it models (free text, for documentation).
  std::string product;
  /// Mass in kg (0 for a mesh object given by its density).
  double mass = 0.0;
  /// Mesh objects: density in kg/m^3 instead of a mass.
  std::optional<double> density;
  /// Shape kind.
  ShapeKind kind = ShapeKind::kBox;
  /// Box: full edge lengths x, y, z (z up when standing).
  Eigen::Vector3d boxSize = Eigen::Vector3d::Zero();
  /// Box: radius of the rounded edges of the visual mesh (0 = sharp).
  double cornerRadius = 0.0;
  /// Cylinder and lathe: the radius profile, bottom first, z strictly increasing from 0.
  std::vector<ProfilePoint> profile;
  /// Optional handle (lathes and cylinders only).
  std::optional<HandleSpec> handle;
  /// The mesh and collision files of a kMesh object.
  std::optional<MeshShapeSpec> meshShape;
  /// Look (for a mesh object: used when the mesh file brings no texture).
  AppearanceSpec appearance;
  /// False for a mesh object without <Appearance> (it keeps the file's own materials).
  bool hasAppearance = true;
  /// The spec file the object was read from (for messages).
  std::string specFile;
  /// Line of the <Object> element in its file.
  int line = 0;

  /// Height of the body (z extent).
  double height() const;
  /// Largest radius of the profile (0 for a box).
  double maxRadius() const;
  /// Smallest profile radius over [z0, z1] (the profile is linear between its points).
  double minRadiusBetween(double z0, double z1) const;
  /// Profile radius at height z (clamped to the profile's ends).
  double radiusAt(double z) const;
};

/// The two kinds of table surface.
enum class TablePattern {
  kPlain,      ///< A near-uniform light surface with faint low-contrast grain.
  kCluttered,  ///< A colourful, high-frequency cluttered tablecloth print.
};

/// A table surface as described in objects.xml.
struct TableSpec {
  /// "plain" or "textured".
  std::string name;
  /// Size along x and y in metres.
  double x = 0.0;
  /// Size along y in metres.
  double y = 0.0;
  /// Texture recipe.
  TablePattern pattern = TablePattern::kPlain;
  /// Base colour.
  Eigen::Vector3f colour{0.85f, 0.85f, 0.85f};
  /// Seed of the texture generator.
  std::uint32_t seed = 0;
};

/// A pair of objects for the double-object scenes: `<Pair a="name" b="name"/>`.
struct PairSpec {
  /// Name of the first object.
  std::string a;
  /// Name of the second object.
  std::string b;
  /// Line of the element.
  int line = 0;
};

/// The content of objects.xml.
struct ObjectDatabaseSpec {
  /// Objects in file order.
  std::vector<ObjectSpec> objects;
  /// Table surfaces in file order.
  std::vector<TableSpec> tables;
  /// Object pairs in file order (objects.xml has none: the benchmark's pairs are fixed).
  std::vector<PairSpec> pairs;
  /// The object with this name, or nullptr.
  const ObjectSpec* findObject(std::string_view name) const;
  /// The object with this id, or nullptr.
  const ObjectSpec* findObject(int id) const;
  /// The table with this name, or nullptr.
  const TableSpec* findTable(std::string_view name) const;
};

/// Largest edge radius of a box's visual mesh, so that the visual surface stays within 2 mm of
/// the collision box (the corner point lies (1 - 1/sqrt(3)) r inside).
inline constexpr double kMaxCornerRadius = 0.004;

/// Reads an object spec file: checks it against xml/objects.xsd (compiled in), then the meaning
/// (positive sizes, monotonic profiles, handles on the body, unique ids and names, colours in
/// [0, 1], known patterns and materials; mesh objects: the mesh and piece files exist, exactly
/// one of mass and density, positive; pairs name two different objects of the file). The mesh
/// content (closed, positive volume) is checked by generateObject.
/// @throws rw::common::LoadError with every error found, each at file:line:column.
ObjectDatabaseSpec loadObjectSpecs(const std::filesystem::path& file);

/// Same as loadObjectSpecs, reading the XML from `xml`; messages name `virtualFile`.
/// @throws rw::common::LoadError with every error found, each at file:line:column.
ObjectDatabaseSpec loadObjectSpecsFromString(std::string_view xml,
                                             const std::filesystem::path& virtualFile);

}  // namespace visgrab::objects
