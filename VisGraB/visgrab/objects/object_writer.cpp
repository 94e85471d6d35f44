#include "visgrab/objects/object_writer.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rw/common/write_error.hpp"
#include "rw/math/rpy.hpp"

namespace visgrab::objects {

namespace fs = std::filesystem;

namespace {

constexpr int kPngCompression = 6;

// Shortest text that reads back to the same value (locale independent).
template <typename T>
std::string number(T value) {
  if (value == T(0)) return "0";  // no "-0"
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

template <typename Vector>
std::string numbers(const Vector& v) {
  std::string text;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) text += ' ';
    text += number(v[i]);
  }
  return text;
}

void writeText(const fs::path& file, std::string_view text) {
  errno = 0;
  std::ofstream out(file, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  // The stream keeps no reason; errno holds the failed system call's (EIO if none set it).
  if (!out) throw rw::common::WriteError(file, {errno != 0 ? errno : EIO, std::generic_category()});
}

void createFolder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw std::runtime_error("cannot create " + folder.string() + ": " + ec.message());
}

struct NamedMesh {
  std::string name;
  const visual::VisualMesh* mesh;
  std::string texture;  // file name, empty for none
};

// OBJ with one group and material per part; v runs bottom to top in OBJ, so vt = 1 - v.
std::string objText(const std::vector<NamedMesh>& parts, const std::string& mtlName) {
  std::string text = "# VisGraB object mesh (visgrab::objects), metres\nmtllib " + mtlName + "\n";
  std::size_t base = 1;
  for (const NamedMesh& part : parts) {
    const visual::VisualMesh& m = *part.mesh;
    text += "o " + part.name + "\n";
    for (const auto& p : m.positions) text += "v " + numbers(p) + "\n";
    const bool uv = m.uvs.size() == m.positions.size();
    if (uv) {
      for (const auto& t : m.uvs) text += "vt " + number(t.x()) + " " + number(1.0f - t.y()) + "\n";
    }
    for (const auto& n : m.normals) text += "vn " + numbers(n) + "\n";
    text += "usemtl " + part.name + "\ns 1\n";
    for (const auto& tri : m.triangles) {
      text += "f";
      for (std::uint32_t i : tri) {
        const std::string k = std::to_string(base + i);
        text += " " + k + (uv ? "/" + k + "/" : "//") + k;
      }
      text += "\n";
    }
    base += m.positions.size();
  }
  return text;
}

std::string mtlText(const std::vector<NamedMesh>& parts) {
  std::string text = "# VisGraB object materials (visgrab::objects)\n";
  for (const NamedMesh& part : parts) {
    const visual::VisualMesh& m = *part.mesh;
    text += "newmtl " + part.name + "\nKa 0 0 0\nKd " + numbers(m.colour) + "\nKs " +
            numbers(Eigen::Vector3f::Constant(m.specular)) + "\nNs 60\nd 1\nillum 2\n";
    if (!part.texture.empty()) text += "map_Kd " + part.texture + "\n";
    text += "\n";
  }
  return text;
}

std::string exampleDynamics(const ObjectModel& model) {
  return "<!-- Example dynamic workcell of object " + std::to_string(model.id) + " \"" +
         model.name + "\" (written by visgrab::objects::writeObjectFiles). -->\n" +
         "<DynamicWorkcell workcell=\"" + model.name + ".wc.xml\">\n" +
         "  <Gravity>0 0 -9.81</Gravity>\n"
         "  <MaterialData>\n"
         "    <Default>Object</Default>\n"
         "    <Material id=\"Object\"/>\n"
         "    <Material id=\"Table\"/>\n"
         "  </MaterialData>\n"
         "  <FrictionMap>\n"
         "    <Pair first=\"Object\" second=\"Table\"><FrictionData type=\"Coulomb\">"
         "<Mu>0.4</Mu></FrictionData></Pair>\n"
         "  </FrictionMap>\n"
         "  <ObjectTypeData>\n"
         "    <Default>hardObj</Default>\n"
         "    <ObjectType id=\"hardObj\"/>\n"
         "  </ObjectTypeData>\n" +
         objectBodyXml(model) + "</DynamicWorkcell>\n";
}

// The element of one collision piece: a Cylinder, a Frustum or the Polytope `file`.
std::string shapeXml(const CollisionPiece& piece, const std::string& file) {
  const auto& g = *piece.geometry;
  const auto& p = g.parameters();
  switch (g.type()) {
    case rw::geometry::GeometryType::kCylinder:
      return "<Cylinder radius=\"" + number(p[0]) + "\" z=\"" + number(p[1]) + "\"/>";
    case rw::geometry::GeometryType::kFrustum:
      return "<Custom type=\"Frustum\" param=\"" + number(p[0]) + " " + number(p[1]) + " " +
             number(p[2]) + "\"/>";
    case rw::geometry::GeometryType::kMesh:
      return "<Polytope file=\"" + file + "\"/>";
    default:
      throw std::logic_error(std::string("objectFrameXml: no writer for a ") +
                             rw::geometry::geometryTypeName(g.type()) + " collision piece");
  }
}

// A mesh object's notes (holes filled, pieces replaced by hulls, the decomposition) as comments.
std::string notesXml(const ObjectModel& model) {
  std::string text;
  for (const std::string& note : model.notes) {
    std::string safe = note;
    for (std::size_t i = safe.find("--"); i != std::string::npos; i = safe.find("--")) {
      safe.replace(i, 2, "- ");
    }
    text += "<!-- " + safe + " -->\n";
  }
  return text;
}

}  // namespace

std::string objectFrameXml(const ObjectModel& model, const std::string& meshPrefix,
                           const std::string& refframe, const rw::math::Transform3D& X_parent) {
  const rw::math::Vector3D rpy = rw::math::rotationToRpy(X_parent.linear()) * rw::math::kRad2Deg;
  std::string text = "<Frame name=\"" + model.name + "\" refframe=\"" + refframe +
                     "\" type=\"Movable\">\n  <RPY>" + numbers(rpy) + "</RPY><Pos>" +
                     numbers(rw::math::Vector3D(X_parent.translation())) + "</Pos>\n";
  text += "  <Drawable name=\"" + model.name + "_visual\" colmodel=\"Disabled\">\n" +
          "    <RPY>0 0 0</RPY><Pos>0 0 0</Pos>\n    <Polytope file=\"" + meshPrefix + model.name +
          ".obj\"/>\n  </Drawable>\n";
  for (std::size_t k = 0; k < model.collision.size(); ++k) {
    const CollisionPiece& piece = model.collision[k];
    const std::string hull = model.name + "_hull" + std::to_string(k);
    text += "  <CollisionModel name=\"" + hull + "\">\n    <RPY>0 0 0</RPY><Pos>" +
            numbers(rw::math::Vector3D(piece.X_OG.translation())) + "</Pos>\n    " +
            shapeXml(piece, meshPrefix + hull + ".stl") + "\n  </CollisionModel>\n";
  }
  return text + "</Frame>\n";
}

std::string objectBodyXml(const ObjectModel& model, const std::string& material, double damping) {
  const auto& m = model.mass;
  const Eigen::Matrix3d I = m.inertia;
  std::string inertia;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) inertia += (r + c > 0 ? " " : "") + number(I(r, c));
  }
  return "<RigidBody frame=\"" + model.name + "\">\n  <Mass>" + number(m.mass) +
         "</Mass>\n  <Integrator>Euler</Integrator>\n  <MaterialID>" + material +
         "</MaterialID>\n  <COG>" + numbers(m.cog) + "</COG>\n  <Inertia>" + inertia +
         "</Inertia>\n" +
         (damping > 0.0 ? "  <Property name=\"LinearDamping\" type=\"float\">" + number(damping) +
                              "</Property>\n  <Property name=\"AngularDamping\" type=\"float\">" +
                              number(damping) + "</Property>\n"
                        : std::string()) +
         "</RigidBody>\n";
}

void writeBinaryStl(const rw::geometry::TriMesh& mesh, const fs::path& file) {
  std::string bytes(80, '\0');
  const std::string header = "VisGraB convex collision piece (binary STL, metres)";
  bytes.replace(0, header.size(), header);
  auto put = [&bytes](const void* data, std::size_t size) {
    bytes.append(static_cast<const char*>(data), size);
  };
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  put(&count, sizeof(count));
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.vertices[t[0]];
    const auto& b = mesh.vertices[t[1]];
    const auto& c = mesh.vertices[t[2]];
    const Eigen::Vector3f n = (b - a).cross(c - a).normalized().cast<float>();
    put(n.data(), 12);
    for (const auto* v : {&a, &b, &c}) {
      const Eigen::Vector3f f = v->cast<float>();
      put(f.data(), 12);
    }
    const std::uint16_t attribute = 0;
    put(&attribute, sizeof(attribute));
  }
  writeText(file, bytes);
}

void writePng(const visual::RgbImage& image, const fs::path& file) {
  if (image.empty()) throw std::runtime_error("cannot write " + file.string() + ": empty image");
  cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  const std::vector<int> params{cv::IMWRITE_PNG_COMPRESSION, kPngCompression};
  std::vector<uchar> encoded;
  bool ok = false;
  try {
    ok = cv::imencode(".png", bgr, encoded, params);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write " + file.string() + ": " + e.what());
  }
  if (!ok) throw std::runtime_error("cannot write " + file.string() + ": cannot encode the PNG");
  writeText(file, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

ObjectFiles writeObjectFiles(const ObjectModel& model, const fs::path& dir) {
  ObjectFiles files;
  files.folder = dir / model.name;
  createFolder(files.folder);
  std::vector<NamedMesh> parts;
  for (const VisualPart& part : model.visual) {
    std::string texture;
    if (part.mesh.texture && !part.mesh.texture->empty()) {
      texture = model.name + "_" + part.name + ".png";
      files.textures.push_back(files.folder / texture);
      writePng(*part.mesh.texture, files.textures.back());
    }
    parts.push_back({part.name, &part.mesh, texture});
  }
  files.obj = files.folder / (model.name + ".obj");
  files.mtl = files.folder / (model.name + ".mtl");
  writeText(files.obj, objText(parts, model.name + ".mtl"));
  writeText(files.mtl, mtlText(parts));
  for (std::size_t k = 0; k < model.collision.size(); ++k) {
    if (model.collision[k].isRound()) continue;
    files.hulls.push_back(files.folder / (model.name + "_hull" + std::to_string(k) + ".stl"));
    writeBinaryStl(*model.collision[k].triangles, files.hulls.back());
  }
  files.workcell = files.folder / (model.name + ".wc.xml");
  writeText(files.workcell, "<!-- Example workcell of object " + std::to_string(model.id) + " \"" +
                                model.name +
                                "\" (written by visgrab::objects::writeObjectFiles). -->\n" +
                                notesXml(model) + "<WorkCell name=\"" + model.name +
                                "_example\">\n" + objectFrameXml(model, "") + "</WorkCell>\n");
  files.dynamics = files.folder / (model.name + ".dwc.xml");
  writeText(files.dynamics, exampleDynamics(model));
  return files;
}

fs::path writeTableFiles(const TableModel& table, const fs::path& dir) {
  const fs::path folder = dir / table.name;
  createFolder(folder);
  const std::string texture = table.name + ".png";
  if (table.surface.texture) writePng(*table.surface.texture, folder / texture);
  const std::vector<NamedMesh> parts{
      {table.name, &table.surface, table.surface.texture ? texture : std::string()}};
  const fs::path obj = folder / (table.name + ".obj");
  writeText(obj, objText(parts, table.name + ".mtl"));
  writeText(folder / (table.name + ".mtl"), mtlText(parts));
  return obj;
}

}  // namespace visgrab::objects
