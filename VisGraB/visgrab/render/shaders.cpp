#include "visgrab/render/shaders.hpp"

namespace visgrab::render::detail {

const char* const kShadedVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
uniform mat4 uModel;           // X_WM
uniform mat3 uNormalMatrix;    // rotation of X_WM
uniform mat4 uViewProjection;  // clip from world
uniform mat4 uShadowMatrix;    // shadow-map texture coordinates from world
out vec3 vPositionW;
out vec3 vNormalW;
out vec2 vUv;
out vec4 vShadowCoord;
void main() {
  vec4 positionW = uModel * vec4(aPosition, 1.0);
  vPositionW = positionW.xyz;
  vNormalW = uNormalMatrix * aNormal;
  vUv = aUv;
  vShadowCoord = uShadowMatrix * positionW;
  gl_Position = uViewProjection * positionW;
}
)glsl";

const char* const kShadedFragmentShader = R"glsl(#version 330 core
const int kMaxLights = 8;
in vec3 vPositionW;
in vec3 vNormalW;
in vec2 vUv;
in vec4 vShadowCoord;
uniform vec3 uColour;
uniform float uSpecular;
uniform bool uHasTexture;
uniform sampler2D uTexture;        // sRGB texture, decoded to linear by the sampler
uniform vec3 uEyeW;
uniform vec3 uAmbient;
uniform float uShininess;
uniform int uLightCount;
uniform vec4 uLightVector[kMaxLights];  // w = 0: unit direction towards the light; w = 1: position
uniform vec3 uLightColour[kMaxLights];
uniform int uShadowLight;               // index of the shadow-casting light, -1 for none
uniform sampler2DShadow uShadowMap;
layout(location = 0) out vec4 oColour;

vec3 encodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 low = 12.92 * c;
  vec3 high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), c));
}

float lit(int light) {
  if (light != uShadowLight) return 1.0;
  vec3 p = vShadowCoord.xyz / vShadowCoord.w;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  // Four bilinear depth comparisons half a texel apart: a smooth 3x3-texel percentage-closer
  // filter.
  vec2 texel = 0.5 / vec2(textureSize(uShadowMap, 0));
  float sum = texture(uShadowMap, vec3(p.xy + vec2(-texel.x, -texel.y), p.z)) +
              texture(uShadowMap, vec3(p.xy + vec2(texel.x, -texel.y), p.z)) +
              texture(uShadowMap, vec3(p.xy + vec2(-texel.x, texel.y), p.z)) +
              texture(uShadowMap, vec3(p.xy + vec2(texel.x, texel.y), p.z));
  return 0.25 * sum;
}

void main() {
  vec3 n = normalize(vNormalW);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = uColour;
  if (uHasTexture) albedo *= texture(uTexture, vUv).rgb;
  vec3 v = normalize(uEyeW - vPositionW);
  vec3 diffuse = uAmbient;
  vec3 specular = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = uLightVector[i].w == 0.0 ? uLightVector[i].xyz
                                      : normalize(uLightVector[i].xyz - vPositionW);
    float nl = dot(n, l);
    if (nl <= 0.0) continue;
    float visible = lit(i);
    diffuse += visible * nl * uLightColour[i];
    vec3 h = normalize(l + v);
    specular += visible * uSpecular * pow(max(dot(n, h), 0.0), uShininess) * uLightColour[i];
  }
  oColour = vec4(encodeSrgb(albedo * diffuse + specular), 1.0);
}
)glsl";

const char* const kIdVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uModelView;   // X_CM
uniform mat4 uProjection;  // clip from camera
out float vCameraZ;
void main() {
  vec4 positionC = uModelView * vec4(aPosition, 1.0);
  vCameraZ = positionC.z;
  gl_Position = uProjection * positionC;
}
)glsl";

const char* const kIdFragmentShader = R"glsl(#version 330 core
in float vCameraZ;
uniform uint uInstanceId;
layout(location = 0) out float oDepth;
layout(location = 1) out uint oInstanceId;
void main() {
  oDepth = vCameraZ;
  oInstanceId = uInstanceId;
}
)glsl";

const char* const kShadowVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uLightClipFromModel;
void main() { gl_Position = uLightClipFromModel * vec4(aPosition, 1.0); }
)glsl";

const char* const kShadowFragmentShader = R"glsl(#version 330 core
void main() {}
)glsl";

}  // namespace visgrab::render::detail
