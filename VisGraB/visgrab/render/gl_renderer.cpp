#include "visgrab/render/gl_renderer.hpp"

#include "visgrab/render/srgb.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "visgrab/render/gl_api.hpp"
#include "visgrab/render/shaders.hpp"

namespace visgrab::render {

namespace {

using detail::checkGl;

/// Attribute locations shared by all programs.
constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kNormalAttribute = 1;
constexpr GLuint kUvAttribute = 2;
constexpr GLint kTextureUnit = 0;
constexpr GLint kShadowUnit = 1;
/// Interleaved vertex: position (3), normal (3), uv (2).
constexpr std::size_t kFloatsPerVertex = 8;

struct GpuMesh {
  GLuint vao = 0;
  GLuint vertexBuffer = 0;
  GLuint indexBuffer = 0;
  GLsizei indexCount = 0;
  GLuint texture = 0;
  Eigen::Vector3f colour = Eigen::Vector3f::Zero();
  float specular = 0.0f;
  /// Bounding sphere in the mesh frame.
  Eigen::Vector3d centre_M = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

struct ShadedUniforms {
  GLint model = -1, normalMatrix = -1, viewProjection = -1, shadowMatrix = -1;
  GLint colour = -1, specular = -1, hasTexture = -1, texture = -1, eye = -1, ambient = -1;
  GLint shininess = -1, lightCount = -1, lightVector = -1, lightColour = -1;
  GLint shadowLight = -1, shadowMap = -1;
};

struct IdUniforms {
  GLint modelView = -1, projection = -1, instanceId = -1;
};

/// Framebuffers of render(), sized to the last camera.
struct Targets {
  int width = 0, height = 0, samples = 0;
  GLuint colourFramebuffer = 0, colourBuffer = 0, colourDepthBuffer = 0;
  GLuint resolveFramebuffer = 0, resolveBuffer = 0;
  GLuint idFramebuffer = 0, depthValueBuffer = 0, idBuffer = 0, idDepthBuffer = 0;
};

struct ShadowMap {
  int size = 0;
  GLuint framebuffer = 0;
  GLuint texture = 0;
  /// What the map holds: each item's mesh index and model matrix, the light's direction and
  /// the size (empty: nothing). The map does not depend on the camera, so a second render of
  /// the same scene (the other image of a stereo pair) reuses it.
  std::vector<double> key;
  /// The world-to-shadow-texture matrix of `key`.
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
};

Eigen::Matrix4f toFloat(const Eigen::Matrix4d& m) { return m.cast<float>(); }

/// World from mesh coordinates: X_WM * diag(scale).
Eigen::Matrix4d modelMatrix(const SceneItem& item) {
  Eigen::Matrix4d m = item.X_WM.matrix();
  m.topLeftCorner<3, 3>() *= item.scale.asDiagonal();
  return m;
}

/// Centre of the mesh's bounding sphere in the world.
Eigen::Vector3d worldCentre(const SceneItem& item, const GpuMesh& mesh) {
  return item.X_WM * item.scale.cwiseProduct(mesh.centre_M);
}

GLint uniform(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

void deleteTargets(Targets& t) {
  const GLuint framebuffers[] = {t.colourFramebuffer, t.resolveFramebuffer, t.idFramebuffer};
  const GLuint renderbuffers[] = {t.colourBuffer,     t.colourDepthBuffer, t.resolveBuffer,
                                  t.depthValueBuffer, t.idBuffer,          t.idDepthBuffer};
  glDeleteFramebuffers(3, framebuffers);
  glDeleteRenderbuffers(6, renderbuffers);
  t = Targets{};
}

GLuint makeRenderbuffer(GLenum format, int samples, int width, int height) {
  GLuint buffer = 0;
  glGenRenderbuffers(1, &buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, buffer);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  return buffer;
}

void checkFramebuffer(const char* name) {
  const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(std::string("OpenGL: the ") + name +
                             " framebuffer is incomplete (status " + std::to_string(status) + ")");
  }
}

/// Saves the framebuffer bindings and restores them on scope exit.
class FramebufferBindingGuard {
 public:
  FramebufferBindingGuard() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
  }
  ~FramebufferBindingGuard() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_));
  }
  FramebufferBindingGuard(const FramebufferBindingGuard&) = delete;
  FramebufferBindingGuard& operator=(const FramebufferBindingGuard&) = delete;

 private:
  GLint draw_ = 0;
  GLint read_ = 0;
};

/// A unit vector perpendicular to `d`.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& d) {
  const Eigen::Vector3d axis =
      std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return d.cross(axis).normalized();
}

}  // namespace

struct GlRenderer::State {
  /// Item indices sorted front to back (by the camera z of their bounding spheres' centres),
  /// so that early depth tests skip hidden fragments; ties keep the scene's order.
  std::vector<std::size_t> drawOrder(const Scene& scene, const Eigen::Isometry3d& X_CW) const;
  GLuint shadedProgram = 0;
  GLuint idProgram = 0;
  GLuint shadowProgram = 0;
  ShadedUniforms shaded;
  IdUniforms id;
  GLint shadowLightClipFromModel = -1;
  std::vector<GpuMesh> meshes;
  /// GL texture per shared image; the shared_ptr keeps the address from being reused.
  std::map<const visual::RgbImage*, std::pair<std::shared_ptr<const visual::RgbImage>, GLuint>>
      textures;
  Targets targets;
  ShadowMap shadowMap;

  GLuint textureFor(const std::shared_ptr<const visual::RgbImage>& image);
  void ensureTargets(int width, int height, int samples);
  void ensureShadowMap(int size);
  /// Renders the shadow map of `light`; returns the world-to-shadow-texture matrix.
  Eigen::Matrix4d renderShadowMap(const Scene& scene, const Light& light, int size);
  void drawShaded(const Scene& scene, const PinholeCamera& camera, const RenderOptions& options,
                  GLuint framebuffer);
  void drawDepthAndIds(const Scene& scene, const PinholeCamera& camera);
  void validate(const Scene& scene, const PinholeCamera& camera) const;
};

GlRenderer::GlRenderer() : state_(std::make_unique<State>()) {
  // Without a current context glvnd's dispatch returns null; works for EGL and GLX contexts.
  if (glGetString(GL_VERSION) == nullptr) {
    throw std::runtime_error("GlRenderer: no current OpenGL context");
  }
  State& s = *state_;
  s.shadedProgram =
      detail::buildProgram("shaded", detail::kShadedVertexShader, detail::kShadedFragmentShader);
  s.idProgram =
      detail::buildProgram("depth and id", detail::kIdVertexShader, detail::kIdFragmentShader);
  s.shadowProgram = detail::buildProgram("shadow map", detail::kShadowVertexShader,
                                         detail::kShadowFragmentShader);
  const GLuint p = s.shadedProgram;
  s.shaded = ShadedUniforms{
      uniform(p, "uModel"),        uniform(p, "uNormalMatrix"), uniform(p, "uViewProjection"),
      uniform(p, "uShadowMatrix"), uniform(p, "uColour"),       uniform(p, "uSpecular"),
      uniform(p, "uHasTexture"),   uniform(p, "uTexture"),      uniform(p, "uEyeW"),
      uniform(p, "uAmbient"),      uniform(p, "uShininess"),    uniform(p, "uLightCount"),
      uniform(p, "uLightVector"),  uniform(p, "uLightColour"),  uniform(p, "uShadowLight"),
      uniform(p, "uShadowMap")};
  s.id = IdUniforms{uniform(s.idProgram, "uModelView"), uniform(s.idProgram, "uProjection"),
                    uniform(s.idProgram, "uInstanceId")};
  s.shadowLightClipFromModel = uniform(s.shadowProgram, "uLightClipFromModel");
  glUseProgram(s.shadedProgram);
  glUniform1i(s.shaded.texture, kTextureUnit);
  glUniform1i(s.shaded.shadowMap, kShadowUnit);
  glUseProgram(0);
  checkGl("GlRenderer: setting up the programs");
}

GlRenderer::~GlRenderer() {
  State& s = *state_;
  for (GpuMesh& mesh : s.meshes) {
    glDeleteVertexArrays(1, &mesh.vao);
    glDeleteBuffers(1, &mesh.vertexBuffer);
    glDeleteBuffers(1, &mesh.indexBuffer);
  }
  for (auto& entry : s.textures) glDeleteTextures(1, &entry.second.second);
  deleteTargets(s.targets);
  glDeleteFramebuffers(1, &s.shadowMap.framebuffer);
  glDeleteTextures(1, &s.shadowMap.texture);
  glDeleteProgram(s.shadedProgram);
  glDeleteProgram(s.idProgram);
  glDeleteProgram(s.shadowProgram);
}

std::size_t GlRenderer::meshCount() const { return state_->meshes.size(); }

GLuint GlRenderer::State::textureFor(const std::shared_ptr<const visual::RgbImage>& image) {
  if (const auto found = textures.find(image.get()); found != textures.end()) {
    return found->second.second;
  }
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  // Row 0 of the image (its top) goes first, so texture t equals VisualMesh's v (downward).
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8, image->width, image->height, 0, GL_RGB, GL_UNSIGNED_BYTE,
               image->pixels.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D, 0);
  textures.emplace(image.get(), std::make_pair(image, texture));
  return texture;
}

MeshHandle GlRenderer::add(std::shared_ptr<const visual::VisualMesh> mesh) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("GlRenderer::add: " + what);
  };
  if (!mesh) fail("null mesh");
  const std::size_t n = mesh->positions.size();
  if (n > std::numeric_limits<std::uint32_t>::max()) fail("too many vertices");
  if (mesh->normals.size() != n) {
    fail(std::to_string(mesh->normals.size()) + " normals for " + std::to_string(n) + " positions");
  }
  if (!mesh->uvs.empty() && mesh->uvs.size() != n) {
    fail(std::to_string(mesh->uvs.size()) + " uvs for " + std::to_string(n) + " positions");
  }
  for (const auto& triangle : mesh->triangles) {
    for (std::uint32_t index : triangle) {
      if (index >= n) {
        fail("triangle index " + std::to_string(index) + " out of range (" + std::to_string(n) +
             " positions)");
      }
    }
  }
  if (mesh->texture) {
    if (mesh->uvs.empty()) fail("a texture without uvs");
    const auto& image = *mesh->texture;
    if (image.empty() || image.pixels.size() != static_cast<std::size_t>(image.width) *
                                                    static_cast<std::size_t>(image.height) * 3) {
      fail("texture of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           " pixels has " + std::to_string(image.pixels.size()) + " bytes");
    }
  }

  std::vector<float> vertices(n * kFloatsPerVertex, 0.0f);
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < n; ++i) {
    float* v = &vertices[i * kFloatsPerVertex];
    for (int k = 0; k < 3; ++k) {
      v[k] = mesh->positions[i][k];
      v[3 + k] = mesh->normals[i][k];
    }
    if (!mesh->uvs.empty()) {
      v[6] = mesh->uvs[i].x();
      v[7] = mesh->uvs[i].y();
    }
    box.extend(mesh->positions[i].cast<double>());
  }

  State& s = *state_;
  GpuMesh gpu;
  gpu.indexCount = static_cast<GLsizei>(mesh->triangles.size() * 3);
  gpu.colour = mesh->colour;
  gpu.specular = mesh->specular;
  if (n > 0) {
    gpu.centre_M = box.center();
    for (const auto& p : mesh->positions) {
      gpu.radius = std::max(gpu.radius, (p.cast<double>() - gpu.centre_M).norm());
    }
  }
  glGenVertexArrays(1, &gpu.vao);
  glBindVertexArray(gpu.vao);
  glGenBuffers(1, &gpu.vertexBuffer);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gpu.indexBuffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indexBuffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh->triangles.size() * sizeof(mesh->triangles[0])),
               mesh->triangles.data(), GL_STATIC_DRAW);
  constexpr auto kStride = static_cast<GLsizei>(kFloatsPerVertex * sizeof(float));
  glEnableVertexAttribArray(kPositionAttribute);
  glVertexAttribPointer(kPositionAttribute, 3, GL_FLOAT, GL_FALSE, kStride, nullptr);
  glEnableVertexAttribArray(kNormalAttribute);
  glVertexAttribPointer(kNormalAttribute, 3, GL_FLOAT, GL_FALSE, kStride,
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(kUvAttribute);
  glVertexAttribPointer(kUvAttribute, 2, GL_FLOAT, GL_FALSE, kStride,
                        reinterpret_cast<const void*>(6 * sizeof(float)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (mesh->texture) gpu.texture = s.textureFor(mesh->texture);
  try {
    checkGl("GlRenderer::add: uploading a mesh");
  } catch (...) {
    glDeleteVertexArrays(1, &gpu.vao);
    glDeleteBuffers(1, &gpu.vertexBuffer);
    glDeleteBuffers(1, &gpu.indexBuffer);
    throw;
  }
  s.meshes.push_back(gpu);
  return MeshHandle{static_cast<std::uint32_t>(s.meshes.size() - 1)};
}

std::vector<std::size_t> GlRenderer::State::drawOrder(const Scene& scene,
                                                      const Eigen::Isometry3d& X_CW) const {
  std::vector<std::pair<double, std::size_t>> keyed;
  keyed.reserve(scene.items.size());
  for (std::size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    const GpuMesh& mesh = meshes[item.mesh.index];
    keyed.emplace_back((X_CW * worldCentre(item, mesh)).z() - mesh.radius * item.scale.maxCoeff(),
                       i);
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::size_t> order;
  order.reserve(keyed.size());
  for (const auto& entry : keyed) order.push_back(entry.second);
  return order;
}

void GlRenderer::State::validate(const Scene& scene, const PinholeCamera& camera) const {
  camera.validate();
  for (const SceneItem& item : scene.items) {
    if (!(item.scale.array() > 0.0).all() || !item.scale.allFinite()) {
      throw std::invalid_argument("GlRenderer: an item's scale must be positive and finite");
    }
    if (item.mesh.index >= meshes.size()) {
      throw std::invalid_argument("GlRenderer: unknown mesh handle " +
                                  std::to_string(item.mesh.index) + " (" +
                                  std::to_string(meshes.size()) + " meshes uploaded)");
    }
  }
  if (scene.lighting.lights.size() > kMaxLights) {
    throw std::invalid_argument("GlRenderer: " + std::to_string(scene.lighting.lights.size()) +
                                " lights, at most " + std::to_string(kMaxLights));
  }
}

void GlRenderer::State::ensureTargets(int width, int height, int samples) {
  if (targets.width == width && targets.height == height && targets.samples == samples) return;
  deleteTargets(targets);
  Targets& t = targets;
  t.width = width;
  t.height = height;
  t.samples = samples;
  const int msaa = samples > 1 ? samples : 0;
  glGenFramebuffers(1, &t.colourFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.colourFramebuffer);
  t.colourBuffer = makeRenderbuffer(GL_RGBA8, msaa, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            t.colourBuffer);
  t.colourDepthBuffer = makeRenderbuffer(GL_DEPTH_COMPONENT32F, msaa, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            t.colourDepthBuffer);
  checkFramebuffer("multisampled colour");

  glGenFramebuffers(1, &t.resolveFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.resolveFramebuffer);
  t.resolveBuffer = makeRenderbuffer(GL_RGBA8, 0, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            t.resolveBuffer);
  checkFramebuffer("resolved colour");

  glGenFramebuffers(1, &t.idFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.idFramebuffer);
  t.depthValueBuffer = makeRenderbuffer(GL_R32F, 0, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            t.depthValueBuffer);
  t.idBuffer = makeRenderbuffer(GL_R16UI, 0, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.idBuffer);
  t.idDepthBuffer = makeRenderbuffer(GL_DEPTH_COMPONENT32F, 0, width, height);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            t.idDepthBuffer);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, drawBuffers);
  checkFramebuffer("depth and id");
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  checkGl("GlRenderer: creating framebuffers");
}

void GlRenderer::State::ensureShadowMap(int size) {
  if (shadowMap.size == size) return;
  glDeleteFramebuffers(1, &shadowMap.framebuffer);
  glDeleteTextures(1, &shadowMap.texture);
  shadowMap.size = size;
  shadowMap.key.clear();
  glGenTextures(1, &shadowMap.texture);
  glBindTexture(GL_TEXTURE_2D, shadowMap.texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
               nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &shadowMap.framebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadowMap.framebuffer);
  glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowMap.texture,
                         0);
  glDrawBuffer(GL_NONE);
  checkFramebuffer("shadow map");
  checkGl("GlRenderer: creating the shadow map");
}

Eigen::Matrix4d GlRenderer::State::renderShadowMap(const Scene& scene, const Light& light,
                                                   int size) {
  ensureShadowMap(size);
  std::vector<double> key;
  key.reserve(scene.items.size() * 17 + 4);
  for (const SceneItem& item : scene.items) {
    key.push_back(static_cast<double>(item.mesh.index));
    const Eigen::Matrix4d m = modelMatrix(item);
    key.insert(key.end(), m.data(), m.data() + m.size());
  }
  key.insert(key.end(), light.direction_W.data(), light.direction_W.data() + 3);
  key.push_back(size);
  if (key == shadowMap.key) return shadowMap.matrix;
  shadowMap.key.clear();  // until the new map is drawn
  // Bounding sphere of the scene, from the items' spheres.
  Eigen::AlignedBox3d box;
  for (const SceneItem& item : scene.items) {
    const GpuMesh& mesh = meshes[item.mesh.index];
    const Eigen::Vector3d c = worldCentre(item, mesh);
    const double r = mesh.radius * item.scale.maxCoeff();
    box.extend(c - Eigen::Vector3d::Constant(r));
    box.extend(c + Eigen::Vector3d::Constant(r));
  }
  const Eigen::Vector3d centre = box.center();
  double radius = 1e-3;
  for (const SceneItem& item : scene.items) {
    const GpuMesh& mesh = meshes[item.mesh.index];
    radius = std::max(
        radius, (worldCentre(item, mesh) - centre).norm() + mesh.radius * item.scale.maxCoeff());
  }
  // Light frame L: z along the light's travel, origin 2 radii before the centre; orthographic
  // clip x, y in [-r, r], z in [r, 3r].
  const Eigen::Vector3d z = light.direction_W.normalized();
  const Eigen::Vector3d x = perpendicular(z);
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R_WL;
  R_WL << x, y, z;
  const Eigen::Vector3d origin = centre - 2.0 * radius * z;
  Eigen::Matrix4d X_LW = Eigen::Matrix4d::Identity();
  X_LW.topLeftCorner<3, 3>() = R_WL.transpose();
  X_LW.topRightCorner<3, 1>() = -R_WL.transpose() * origin;
  Eigen::Matrix4d ortho = Eigen::Matrix4d::Identity();
  ortho(0, 0) = ortho(1, 1) = ortho(2, 2) = 1.0 / radius;
  ortho(2, 3) = -2.0;
  const Eigen::Matrix4d clipFromWorld = ortho * X_LW;

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadowMap.framebuffer);
  glViewport(0, 0, size, size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);
  glUseProgram(shadowProgram);
  for (const SceneItem& item : scene.items) {
    const GpuMesh& mesh = meshes[item.mesh.index];
    const Eigen::Matrix4f m = toFloat(clipFromWorld * modelMatrix(item));
    glUniformMatrix4fv(shadowLightClipFromModel, 1, GL_FALSE, m.data());
    glBindVertexArray(mesh.vao);
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  Eigen::Matrix4d bias = Eigen::Matrix4d::Identity();
  bias.topLeftCorner<3, 3>() *= 0.5;
  bias.topRightCorner<3, 1>().setConstant(0.5);
  shadowMap.key = std::move(key);
  shadowMap.matrix = bias * clipFromWorld;
  return shadowMap.matrix;
}

void GlRenderer::State::drawShaded(const Scene& scene, const PinholeCamera& camera,
                                   const RenderOptions& options, GLuint framebuffer) {
  int shadowLight = -1;
  Eigen::Matrix4d shadowMatrix = Eigen::Matrix4d::Identity();
  for (std::size_t i = 0; i < scene.lighting.lights.size(); ++i) {
    const Light& light = scene.lighting.lights[i];
    if (light.castsShadows && light.type == Light::Type::kDirectional && !scene.items.empty()) {
      shadowMatrix = renderShadowMap(scene, light, std::max(options.shadowMapSize, 16));
      shadowLight = static_cast<int>(i);
      break;
    }
  }

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, camera.width, camera.height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_MULTISAMPLE);
  glClearColor(encodeSrgb(scene.background.x()), encodeSrgb(scene.background.y()),
               encodeSrgb(scene.background.z()), 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  const Eigen::Matrix4d viewProjection =
      glProjection(camera) * camera.X_WC.inverse(Eigen::Isometry).matrix();
  const Lighting& lighting = scene.lighting;
  std::array<Eigen::Vector4f, kMaxLights> lightVectors{};
  std::array<Eigen::Vector3f, kMaxLights> lightColours{};
  for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
    const Light& light = lighting.lights[i];
    if (light.type == Light::Type::kDirectional) {
      const Eigen::Vector3d towards = -light.direction_W.normalized();
      lightVectors[i] =
          Eigen::Vector4f(static_cast<float>(towards.x()), static_cast<float>(towards.y()),
                          static_cast<float>(towards.z()), 0.0f);
    } else {
      lightVectors[i] = Eigen::Vector4f(static_cast<float>(light.position_W.x()),
                                        static_cast<float>(light.position_W.y()),
                                        static_cast<float>(light.position_W.z()), 1.0f);
    }
    lightColours[i] = light.colour;
  }

  glUseProgram(shadedProgram);
  const Eigen::Matrix4f vp = toFloat(viewProjection);
  glUniformMatrix4fv(shaded.viewProjection, 1, GL_FALSE, vp.data());
  const Eigen::Matrix4f sm = toFloat(shadowMatrix);
  glUniformMatrix4fv(shaded.shadowMatrix, 1, GL_FALSE, sm.data());
  const Eigen::Vector3f eye = camera.X_WC.translation().cast<float>();
  glUniform3fv(shaded.eye, 1, eye.data());
  glUniform3fv(shaded.ambient, 1, lighting.ambient.data());
  glUniform1f(shaded.shininess, lighting.shininess);
  glUniform1i(shaded.lightCount, static_cast<GLint>(lighting.lights.size()));
  glUniform4fv(shaded.lightVector, static_cast<GLsizei>(kMaxLights), lightVectors[0].data());
  glUniform3fv(shaded.lightColour, static_cast<GLsizei>(kMaxLights), lightColours[0].data());
  glUniform1i(shaded.shadowLight, shadowLight);
  glActiveTexture(GL_TEXTURE0 + kShadowUnit);
  glBindTexture(GL_TEXTURE_2D, shadowLight >= 0 ? shadowMap.texture : 0);
  glActiveTexture(GL_TEXTURE0 + kTextureUnit);

  for (std::size_t index : drawOrder(scene, camera.X_WC.inverse(Eigen::Isometry))) {
    const SceneItem& item = scene.items[index];
    const GpuMesh& mesh = meshes[item.mesh.index];
    const Eigen::Matrix4f model = toFloat(modelMatrix(item));
    // Normals transform with the inverse transpose of R * diag(scale): R * diag(1 / scale).
    const Eigen::Matrix3f normalMatrix =
        (item.X_WM.linear() * item.scale.cwiseInverse().asDiagonal()).cast<float>();
    glUniformMatrix4fv(shaded.model, 1, GL_FALSE, model.data());
    glUniformMatrix3fv(shaded.normalMatrix, 1, GL_FALSE, normalMatrix.data());
    glUniform3fv(shaded.colour, 1, item.colour ? item.colour->data() : mesh.colour.data());
    glUniform1f(shaded.specular, item.specular.value_or(mesh.specular));
    glUniform1f(shaded.shininess, item.shininess.value_or(lighting.shininess));
    glUniform1i(shaded.hasTexture, mesh.texture != 0 ? 1 : 0);
    glBindTexture(GL_TEXTURE_2D, mesh.texture);
    glBindVertexArray(mesh.vao);
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0 + kShadowUnit);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
  checkGl("GlRenderer: drawing the shaded scene");
}

void GlRenderer::State::drawDepthAndIds(const Scene& scene, const PinholeCamera& camera) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, targets.idFramebuffer);
  glViewport(0, 0, camera.width, camera.height);
  glDisable(GL_MULTISAMPLE);
  // Camera z 0 marks "nothing drawn" (every visible surface has z >= near > 0).
  const GLfloat zeroDepth[] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint zeroId[] = {0, 0, 0, 0};
  const GLfloat farDepth = 1.0f;
  glClearBufferfv(GL_COLOR, 0, zeroDepth);
  glClearBufferuiv(GL_COLOR, 1, zeroId);
  glClearBufferfv(GL_DEPTH, 0, &farDepth);

  const Eigen::Matrix4f projection = toFloat(glProjection(camera));
  const Eigen::Isometry3d X_CW = camera.X_WC.inverse(Eigen::Isometry);
  glUseProgram(idProgram);
  glUniformMatrix4fv(id.projection, 1, GL_FALSE, projection.data());
  for (std::size_t index : drawOrder(scene, X_CW)) {
    const SceneItem& item = scene.items[index];
    const GpuMesh& mesh = meshes[item.mesh.index];
    const Eigen::Matrix4f modelView = toFloat(X_CW.matrix() * modelMatrix(item));
    glUniformMatrix4fv(id.modelView, 1, GL_FALSE, modelView.data());
    glUniform1ui(id.instanceId, item.instanceId);
    glBindVertexArray(mesh.vao);
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  glEnable(GL_MULTISAMPLE);
  checkGl("GlRenderer: drawing depth and ids");
}

RenderResult GlRenderer::render(const Scene& scene, const PinholeCamera& camera,
                                const RenderOptions& options) {
  State& s = *state_;
  s.validate(scene, camera);
  FramebufferBindingGuard guard;
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  const int samples = std::clamp(options.colourSamples, 1, std::max(1, maxSamples));
  const int w = camera.width;
  const int h = camera.height;
  s.ensureTargets(w, h, samples);
  s.drawShaded(scene, camera, options, s.targets.colourFramebuffer);
  if (options.depthAndIds) s.drawDepthAndIds(scene, camera);

  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.targets.colourFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.targets.resolveFramebuffer);
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);

  const auto width = static_cast<std::size_t>(w);
  const auto height = static_cast<std::size_t>(h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  RenderResult result;
  // OpenGL's rows run bottom to top; the images' rows run top to bottom.
  std::vector<std::uint8_t> rgb(width * height * 3);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.targets.resolveFramebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  result.colour.width = w;
  result.colour.height = h;
  result.colour.pixels.resize(rgb.size());
  for (std::size_t row = 0; row < height; ++row) {
    std::copy_n(&rgb[(height - 1 - row) * width * 3], width * 3,
                &result.colour.pixels[row * width * 3]);
  }

  if (!options.depthAndIds) {
    checkGl("GlRenderer: reading the colour image back");
    return result;
  }
  std::vector<float> z(width * height);
  std::vector<std::uint16_t> ids(width * height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.targets.idFramebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, z.data());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_SHORT, ids.data());
  checkGl("GlRenderer: reading the images back");
  result.depth = DepthImage{w, h, std::vector<float>(width * height)};
  result.instanceIds = InstanceIdImage{w, h, std::vector<std::uint16_t>(width * height)};
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  for (std::size_t row = 0; row < height; ++row) {
    const std::size_t from = (height - 1 - row) * width;
    for (std::size_t col = 0; col < width; ++col) {
      const float value = z[from + col];
      result.depth.values[row * width + col] = value > 0.0f ? value : kInfinity;
      result.instanceIds.values[row * width + col] = ids[from + col];
    }
  }
  return result;
}

void GlRenderer::draw(const Scene& scene, const PinholeCamera& camera,
                      const RenderOptions& options) {
  State& s = *state_;
  s.validate(scene, camera);
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  s.drawShaded(scene, camera, options, static_cast<GLuint>(framebuffer));
}

}  // namespace visgrab::render
