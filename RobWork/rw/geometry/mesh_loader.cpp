#include "rw/geometry/mesh_loader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "rw/geometry/ac3d_reader.hpp"
#include "rw/geometry/detail/mesh_checks.hpp"
#include "rw/geometry/mesh_parts.hpp"
#include "rw/geometry/ply_reader.hpp"

namespace rw::geometry {
namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;

/// Extension orders of RobWork's GeometryFactory (collision) and Model3DFactory (visual), plus
/// PLY.
constexpr std::array<std::string_view, 11> kCollisionExtensions = {
    ".stl", ".stla", ".stlb", ".pcd", ".tri", ".dae", ".ac", ".ac3d", ".3ds", ".obj", ".ply"};
constexpr std::array<std::string_view, 12> kVisualExtensions = {".tri",  ".ac",   ".ac3d", ".3ds",
                                                                ".obj",  ".ivg",  ".dae",  ".stl",
                                                                ".stla", ".stlb", ".pcd",  ".ply"};

constexpr std::string_view kExpected = "expected an STL, OBJ, PLY or AC3D file";

/// Size of a binary STL header: 80 bytes of text plus the little-endian triangle count.
constexpr std::size_t kStlHeaderSize = 84;
/// Bytes per triangle record of a binary STL.
constexpr std::uint64_t kStlRecordSize = 50;

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw MeshLoadError(file.string() + ": error: " + what + "; " + std::string(kExpected));
}

bool isRegularFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string upperCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

/// Checks that `file` is a non-empty regular file we may open.
void checkReadable(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) fail(file, "file not found");
  if (!fs::is_regular_file(status)) fail(file, "not a regular file");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) fail(file, "cannot get the file size: " + ec.message());
  if (size == 0) fail(file, "file is empty");
  if (!std::ifstream(file, std::ios::binary)) fail(file, "cannot open the file for reading");
}

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(file, "error while reading the file");
  return bytes;
}

bool isStlName(const fs::path& file) {
  const std::string ext = lowerCase(file.extension().string());
  return ext == ".stl" || ext == ".stla" || ext == ".stlb";
}

/// True when `bytes` hold only printable text and ordinary whitespace (never true for a binary
/// STL header, whose triangle count has a zero byte for fewer than 2^24 triangles).
bool looksLikeText(std::string_view bytes) {
  return std::all_of(bytes.begin(), bytes.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u >= 0x20 || u == '\t' || u == '\n' || u == '\r' || u == '\f' || u == '\v';
  });
}

bool startsWithSolid(std::string_view bytes) {
  const std::size_t start = bytes.find_first_not_of(" \t\r\n\f\v");
  return start != std::string_view::npos && bytes.substr(start, 5) == "solid";
}

/// Reads the next whitespace-separated word of `text` from `pos` on (empty at the end).
std::string_view nextWord(std::string_view text, std::size_t& pos) {
  const std::size_t start = text.find_first_not_of(" \t\r\n\f\v", pos);
  if (start == std::string_view::npos) {
    pos = text.size();
    return {};
  }
  pos = std::min(text.find_first_of(" \t\r\n\f\v", start), text.size());
  return text.substr(start, pos - start);
}

/// Checks the structure of an ASCII STL after its "solid" line: every facet holds one outer loop
/// of three vertices of three coordinates each and is closed by endfacet, and there is at least
/// one facet. assimp throws for other
/// shapes and leaks the mesh it was building (found by fuzzing).
std::optional<std::string> asciiStlFacetProblem(std::string_view bytes) {
  std::size_t pos = std::min(bytes.find_first_of("\r\n"), bytes.size());
  std::size_t facet = 0;
  bool inFacet = false;
  bool loopDone = false;
  int vertices = -1;  // -1: outside an outer loop
  const auto problem = [&facet](const std::string& what) {
    return "ASCII STL facet " + std::to_string(facet) + ": " + what;
  };
  for (std::string_view word = nextWord(bytes, pos); !word.empty(); word = nextWord(bytes, pos)) {
    if (word == "facet") {
      if (inFacet) return problem("not closed by endfacet before the next facet");
      inFacet = true;
      loopDone = false;
    } else if (word == "loop") {
      if (!inFacet || loopDone || vertices >= 0) return problem("outer loop out of place");
      vertices = 0;
    } else if (word == "vertex") {
      if (vertices < 0) return problem("vertex outside an outer loop");
      ++vertices;
      for (int k = 0; k < 3; ++k) {
        const std::string_view number = nextWord(bytes, pos);
        if (number.empty() || number == "endloop" || number == "vertex") {
          return problem("vertex " + std::to_string(vertices) + " has fewer than 3 coordinates");
        }
      }
    } else if (word == "endloop") {
      if (vertices != 3) {
        return problem("has " + std::to_string(std::max(vertices, 0)) + " vertices, expected 3");
      }
      vertices = -1;
      loopDone = true;
    } else if (word == "endfacet") {
      if (!inFacet || !loopDone) return problem("endfacet without an outer loop of 3 vertices");
      inFacet = false;
      ++facet;
    }
  }
  if (inFacet) return problem("not closed by endfacet at the end of the file");
  if (facet == 0) return "ASCII STL without a facet";
  return std::nullopt;
}

/// Decides binary versus ASCII STL ourselves (binary iff the size is 84 + 50 * count, so a binary
/// header starting with "solid" is fine) and returns what is wrong, if anything.
std::optional<std::string> stlProblem(std::string_view bytes) {
  const std::uint64_t size = bytes.size();
  const std::string_view head = bytes.substr(0, kStlHeaderSize);
  if (size >= kStlHeaderSize) {
    std::uint64_t count = 0;
    for (int i = 3; i >= 0; --i) count = (count << 8U) | static_cast<unsigned char>(bytes[80 + i]);
    const std::uint64_t expected = kStlHeaderSize + kStlRecordSize * count;
    if (expected == size) return std::nullopt;
    if (!looksLikeText(head)) {
      return "binary STL is truncated or corrupt: its header announces " + std::to_string(count) +
             " triangles (" + std::to_string(expected) + " bytes) but the file has " +
             std::to_string(size) + " bytes";
    }
  }
  if (startsWithSolid(bytes) && looksLikeText(head)) return asciiStlFacetProblem(bytes);
  return std::string(
      "not an STL file: it neither starts with \"solid\" (ASCII STL) nor has the "
      "size of a binary STL (84 bytes plus 50 per triangle)");
}

Eigen::Affine3d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d matrix;
  matrix << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return Eigen::Affine3d(matrix);
}

/// Merges triangles of several sources into one TriMesh, joining vertices at equal positions.
class TriangleCollector {
 public:
  explicit TriangleCollector(const fs::path& file) : file_(file) {}

  /// Adds the triangles of `mesh` placed by `X` (points and lines are dropped).
  void add(const aiMesh& mesh, const Eigen::Affine3d& X) {
    add(
        mesh.mNumVertices, mesh.mNumFaces, X,
        [&mesh](unsigned i) {
          const aiVector3D& v = mesh.mVertices[i];
          return Vector3D(v.x, v.y, v.z);
        },
        [&mesh](unsigned f) -> std::optional<std::array<unsigned, 3>> {
          const aiFace& face = mesh.mFaces[f];
          if (face.mNumIndices != 3) return std::nullopt;
          return std::array<unsigned, 3>{face.mIndices[0], face.mIndices[1], face.mIndices[2]};
        });
  }

  /// Adds the triangles of a part read by our own readers, placed by its pose.
  void add(const MeshPart& part) {
    add(
        part.vertices.size(), part.triangles.size(), part.X_FO,
        [&part](std::size_t i) { return part.vertices[i]; },
        [&part](std::size_t t) -> std::optional<std::array<std::uint32_t, 3>> {
          return part.triangles[t];
        });
  }

  TriMesh take() { return std::move(mesh_); }

 private:
  /// Adds `triangleCount` triangles (`triangle(t)`, nullopt for a face that is not one) over
  /// `vertexCount` vertices at `position(i)`, placed by `X`.
  template <typename Position, typename Triangle>
  void add(std::size_t vertexCount, std::size_t triangleCount, const Eigen::Affine3d& X,
           Position position, Triangle triangle) {
    const bool mirrored = X.linear().determinant() < 0.0;  // keep the winding outward
    std::vector<std::optional<std::uint32_t>> joined(vertexCount);
    for (std::size_t t = 0; t < triangleCount; ++t) {
      const auto corners = triangle(t);
      if (!corners) continue;
      std::array<std::uint32_t, 3> joinedTriangle{};
      for (std::size_t k = 0; k < 3; ++k) {
        const auto index = static_cast<std::size_t>((*corners)[k]);
        if (index >= vertexCount) return;  // ValidateDataStructure and our readers rule it out
        if (!joined[index]) joined[index] = vertex(X * position(index));
        joinedTriangle[k] = *joined[index];
      }
      if (mirrored) std::swap(joinedTriangle[1], joinedTriangle[2]);
      mesh_.triangles.push_back(joinedTriangle);
    }
  }

  std::uint32_t vertex(const Vector3D& p) {
    if (!p.allFinite()) {  // checked before the map, whose ordering NaN would break
      fail(file_,
           "vertex " + std::to_string(mesh_.vertices.size()) + " has a non-finite coordinate");
    }
    const auto [it, inserted] =
        index_.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(index_.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }

  const fs::path& file_;
  TriMesh mesh_;
  std::map<std::array<double, 3>, std::uint32_t> index_;
};

/// Walks the node tree (depth first, without recursion) and merges every referenced mesh.
TriMesh collectTriangles(const aiScene& scene, const fs::path& file) {
  TriangleCollector collector(file);
  std::vector<std::pair<const aiNode*, Eigen::Affine3d>> pending;
  pending.emplace_back(scene.mRootNode, toEigen(scene.mRootNode->mTransformation));
  while (!pending.empty()) {
    const auto [node, X] = pending.back();
    pending.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned m = node->mMeshes[i];
      if (m < scene.mNumMeshes && scene.mMeshes[m] != nullptr) collector.add(*scene.mMeshes[m], X);
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) pending.emplace_back(child, X * toEigen(child->mTransformation));
    }
  }
  return collector.take();
}

using OwnReader = std::vector<MeshPart> (*)(const fs::path&, std::string_view);

/// Our own reader for `file`'s extension, if there is one.
OwnReader ownReader(const fs::path& file) {
  const std::string ext = lowerCase(file.extension().string());
  if (ext == ".ply") return &readPly;
  if (ext == ".ac" || ext == ".ac3d") return &readAc3d;
  return nullptr;
}

/// Runs assimp (never for the formats of our own readers); STL files go through memory with an
/// "stl" hint so that .stla/.stlb work too.
const aiScene* import(Assimp::Importer& importer, const fs::path& file) {
  // Normals etc. are removed so that JoinIdenticalVertices joins by position (STL gives every
  // corner its face normal); ValidateDataStructure rejects broken scenes before we walk them.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS);
  const unsigned flags = aiProcess_ValidateDataStructure | aiProcess_RemoveComponent |
                         aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;
  if (!isStlName(file)) return importer.ReadFile(file.string(), flags);
  const std::string bytes = readBytes(file);
  if (const auto problem = stlProblem(bytes)) fail(file, *problem);
  return importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, "stl");
}

}  // namespace

std::optional<fs::path> resolveMeshFile(const fs::path& baseDir, const std::string& name,
                                        MeshUse use) {
  if (name.empty()) return std::nullopt;
  const fs::path given = baseDir / fs::path(name);  // an absolute name ignores baseDir
  if (isRegularFile(given)) return given;
  const std::span<const std::string_view> extensions =
      use == MeshUse::kCollision ? std::span<const std::string_view>(kCollisionExtensions)
                                 : std::span<const std::string_view>(kVisualExtensions);
  for (const std::string_view extension : extensions) {
    for (const std::string& spelling :
         {std::string(extension), upperCase(std::string(extension))}) {
      fs::path candidate = given;
      candidate += spelling;
      if (isRegularFile(candidate)) return candidate;
    }
  }
  return std::nullopt;
}

namespace detail {

void checkBeforeAssimp(const fs::path& file) {
  checkReadable(file);
  if (const OwnReader reader = ownReader(file)) {
    reader(file, readBytes(file));
  } else if (isStlName(file)) {
    if (const auto problem = stlProblem(readBytes(file))) fail(file, *problem);
  }
}

}  // namespace detail

std::shared_ptr<const TriMesh> loadMesh(const fs::path& file) {
  checkReadable(file);
  TriMesh mesh;
  if (const OwnReader reader = ownReader(file)) {
    TriangleCollector collector(file);
    for (const MeshPart& part : reader(file, readBytes(file))) collector.add(part);
    mesh = collector.take();
  } else {
    Assimp::Importer importer;  // one per call: loadMesh may run on several threads at once
    const aiScene* scene = import(importer, file);
    if (scene == nullptr) {
      fail(file, "cannot read mesh: " + std::string(importer.GetErrorString()));
    }
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0U || scene->mRootNode == nullptr) {
      fail(file, "cannot read mesh: the file holds no complete scene");
    }
    mesh = collectTriangles(*scene, file);
  }
  if (mesh.triangles.empty()) fail(file, "the file holds no triangles (only points or lines)");
  return std::make_shared<const TriMesh>(std::move(mesh));
}

}  // namespace rw::geometry
