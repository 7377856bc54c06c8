#include "vtkGlobalIlluminationShadowMaps.h"

#include "vtkMath.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkGlobalIlluminationShadowFS.h"
#include "vtkGlobalIlluminationShadowVS.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
using Vec3 = std::array<double, 3>;
using Mat4 = std::array<double, 16>; // row-major

// Cube faces in layer order +X -X +Y -Y +Z -Z: forward axis F and image axes U, V, as in
// giFaceU / giFaceV of vtkGlobalIlluminationLightDec.glsl.
const double FaceF[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
  { 0, 0, -1 } };
const double FaceU[6][3] = { { 0, 0, -1 }, { 0, 0, 1 }, { 1, 0, 0 }, { 1, 0, 0 }, { 1, 0, 0 },
  { -1, 0, 0 } };
const double FaceV[6][3] = { { 0, -1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }, { 0, -1, 0 },
  { 0, -1, 0 } };

// Spot lights wider than this (half angle) get a cube map.
const double MaxSpotMapAngle = 60.0;

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Rows x = U, y = V, w = F about the light at `eye`, z mapping the distance along F from
/// [near, far] to [-1, 1]; `uvScale` divides x and y (1 / tan of the half field of view).
Mat4 Perspective(const double eye[3], const double u[3], const double v[3], const double f[3],
  double uvScale, double nearZ, double farZ)
{
  const double a = (farZ + nearZ) / (farZ - nearZ), b = -2.0 * farZ * nearZ / (farZ - nearZ);
  Mat4 m{};
  for (int k = 0; k < 3; ++k)
  {
    m[0 + k] = u[k] * uvScale;
    m[4 + k] = v[k] * uvScale;
    m[8 + k] = f[k] * a;
    m[12 + k] = f[k];
  }
  m[3] = -Dot(u, eye) * uvScale;
  m[7] = -Dot(v, eye) * uvScale;
  m[11] = -Dot(f, eye) * a + b;
  m[15] = -Dot(f, eye);
  return m;
}

/// Any unit vectors u, v completing the unit vector f to a right-handed frame.
void Frame(const double f[3], double u[3], double v[3])
{
  const double helper[3] = { std::abs(f[0]) < 0.9 ? 1.0 : 0.0, std::abs(f[0]) < 0.9 ? 0.0 : 1.0,
    0.0 };
  vtkMath::Cross(helper, f, u);
  vtkMath::Normalize(u);
  vtkMath::Cross(f, u, v);
}

/// Largest distance from `p` to a corner of `bounds`.
double FarthestCorner(const double p[3], const double bounds[6])
{
  double farthest = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    const double corner[3] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)],
      bounds[4 + ((c >> 2) & 1)] };
    farthest = std::max(farthest, std::sqrt(vtkMath::Distance2BetweenPoints(p, corner)));
  }
  return farthest;
}

/// Extent [min, max] of the bounds' corners projected on the unit vector `axis`.
void Extent(const double axis[3], const double bounds[6], double range[2])
{
  range[0] = VTK_DOUBLE_MAX;
  range[1] = -VTK_DOUBLE_MAX;
  for (int c = 0; c < 8; ++c)
  {
    const double corner[3] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)],
      bounds[4 + ((c >> 2) & 1)] };
    const double x = Dot(axis, corner);
    range[0] = std::min(range[0], x);
    range[1] = std::max(range[1], x);
  }
}

void ToColumnMajor(const Mat4& m, float* out)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m[r * 4 + c]);
    }
  }
}

vtkGlobalIlluminationShadowMaps::Map CubeMap(
  const double eye[3], const double bounds[6], int resolution)
{
  vtkGlobalIlluminationShadowMaps::Map map;
  map.Kind = 1;
  const double farZ = std::max(FarthestCorner(eye, bounds) * 1.01, 1e-6);
  map.DepthMap = { { 1.0 / farZ, 0.0 } };
  map.Texel = { { 2.0 / resolution, 0.0 } };
  return map;
}

vtkGlobalIlluminationShadowMaps::Map SpotMap(
  const vtkGlobalIlluminationShadowMaps::Light& light, const double bounds[6], int resolution)
{
  vtkGlobalIlluminationShadowMaps::Map map;
  map.Kind = 2;
  const double* eye = light.Position.data();
  const double farZ = std::max(FarthestCorner(eye, bounds) * 1.01, 1e-6);
  // A little wider than the cone, so that the filter and the normal offset stay inside.
  const double cone = std::acos(std::max(-1.0, std::min(1.0, light.CosCone())));
  const double tanHalf = std::tan(cone) * (1.0 + 8.0 / resolution) + 4.0 / resolution;
  double u[3], v[3];
  Frame(light.Direction.data(), u, v);
  map.WorldToClip =
    Perspective(eye, u, v, light.Direction.data(), 1.0 / tanHalf, farZ * 1e-4, farZ);
  map.DepthMap = { { 1.0 / farZ, 0.0 } };
  map.Texel = { { 2.0 * tanHalf / resolution, 0.0 } };
  return map;
}

vtkGlobalIlluminationShadowMaps::Map DirectionalMap(
  const vtkGlobalIlluminationShadowMaps::Light& light, const double bounds[6], int resolution)
{
  vtkGlobalIlluminationShadowMaps::Map map;
  map.Kind = 3;
  const double* f = light.Direction.data();
  double u[3], v[3], ur[2], vr[2], fr[2];
  Frame(f, u, v);
  Extent(u, bounds, ur);
  Extent(v, bounds, vr);
  Extent(f, bounds, fr);
  // Square texels: the larger extent, plus a margin of a few texels for the filter.
  const double half =
    std::max(0.5 * std::max(ur[1] - ur[0], vr[1] - vr[0]), 1e-6) * (1.0 + 8.0 / resolution);
  const double cu = 0.5 * (ur[0] + ur[1]), cv = 0.5 * (vr[0] + vr[1]);
  const double depth = std::max(fr[1] - fr[0], 1e-6) * 1.02, start = fr[0] - 0.01 * depth;
  Mat4& m = map.WorldToClip;
  m = Mat4{};
  for (int k = 0; k < 3; ++k)
  {
    m[0 + k] = u[k] / half;
    m[4 + k] = v[k] / half;
    m[8 + k] = 2.0 * f[k] / depth;
  }
  m[3] = -cu / half;
  m[7] = -cv / half;
  m[11] = -2.0 * start / depth - 1.0;
  m[15] = 1.0;
  map.DepthMap = { { 1.0 / depth, -start / depth } };
  map.Texel = { { 0.0, 2.0 * half / resolution } };
  return map;
}
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationShadowMaps::vtkGlobalIlluminationShadowMaps()
{
  this->Texture->SetAutoParameters(0);
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationShadowMaps::~vtkGlobalIlluminationShadowMaps() = default;

//------------------------------------------------------------------------------
std::vector<vtkGlobalIlluminationShadowMaps::Map> vtkGlobalIlluminationShadowMaps::Plan(
  const std::vector<Light>& lights, const std::vector<bool>& atEye, const double bounds[6],
  int resolution, int& layers) const
{
  std::vector<Map> maps;
  int layer = 0;
  const double wideSpot = std::cos(vtkMath::RadiansFromDegrees(MaxSpotMapAngle));
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const Light& light = lights[i];
    Map map;
    if (i < atEye.size() && atEye[i])
    {
      maps.push_back(map); // kind 0: no map, no lookup in the shader
      continue;
    }
    if (light.Type == Light::DIRECTIONAL)
    {
      map = DirectionalMap(light, bounds, resolution);
    }
    else if (light.Type == Light::SPOT && light.CosCone() > wideSpot)
    {
      map = SpotMap(light, bounds, resolution);
    }
    else
    {
      map = CubeMap(light.Position.data(), bounds, resolution);
    }
    map.Layer = layer;
    layer += map.Kind == 1 ? 6 : 1;
    maps.push_back(map);
  }
  layers = layer;
  return maps;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationShadowMaps::Update(vtkOpenGLRenderWindow* window,
  const std::vector<Light>& lights, const std::vector<bool>& atEye, bool shadows,
  const Casters& casters, int resolution)
{
  // Everything the depth images depend on; colours and intensities are not part of it, nor
  // is where a light at the eye is.
  const bool remote = casters.Remote && !casters.Remote->empty();
  // The version is a hash: all its 64 bits, in two exact halves.
  std::vector<double> signature{ shadows ? 1.0 : 0.0, double(resolution),
    double(casters.Version >> 32), double(casters.Version & 0xffffffffu),
    remote ? double(casters.RemoteVersion) : -1.0 };
  signature.insert(signature.end(), casters.ModelToWorld.begin(), casters.ModelToWorld.end());
  if (remote)
  {
    signature.insert(signature.end(), casters.RemoteToWorld.begin(), casters.RemoteToWorld.end());
  }
  signature.insert(signature.end(), casters.WorldBounds.begin(), casters.WorldBounds.end());
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const Light& light = lights[i];
    if (i < atEye.size() && atEye[i])
    {
      signature.push_back(-1.0);
      continue;
    }
    signature.push_back(light.Type);
    signature.insert(signature.end(), light.Position.begin(), light.Position.end());
    signature.insert(signature.end(), light.Direction.begin(), light.Direction.end());
    signature.push_back(light.CosCone());
  }
  if (signature == this->Signature && window == this->Context && this->TextureHandle)
  {
    return false;
  }
  if (window != this->Context)
  {
    this->ReleaseGraphicsResources(this->Context);
    this->Context = window;
  }
  this->Signature = signature;
  this->Maps.clear();
  int layers = 0;
  if (shadows && casters.Draw)
  {
    this->Maps = this->Plan(lights, atEye, casters.WorldBounds.data(), resolution, layers);
  }
  const bool empty = layers == 0;
  if (empty)
  {
    this->Maps.clear();
  }
  this->Allocate(window, empty ? 1 : layers, empty ? 1 : resolution);
  this->Render(window, empty ? std::vector<Light>() : lights, casters);
  ++this->RenderCount;
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShadowMaps::Allocate(
  vtkOpenGLRenderWindow* window, int layers, int resolution)
{
  if (this->TextureHandle && layers == this->Layers && resolution == this->Resolution)
  {
    return;
  }
  if (!this->TextureHandle)
  {
    glGenTextures(1, &this->TextureHandle);
    glGenFramebuffers(1, &this->Framebuffer);
    this->Texture->SetContext(window);
    this->Texture->AssignToExistingTexture(this->TextureHandle, GL_TEXTURE_2D_ARRAY);
  }
  this->Layers = layers;
  this->Resolution = resolution;
  this->Texture->Activate();
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, resolution, resolution, layers, 0,
    GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  // Linear filtering of a depth comparison gives a free 2x2 percentage-closer filter.
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  this->Texture->Deactivate();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShadowMaps::Render(
  vtkOpenGLRenderWindow* window, const std::vector<Light>& lights, const Casters& casters)
{
  vtkOpenGLState* state = window->GetState();
  state->PushFramebufferBindings();
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, this->Framebuffer);
  state->vtkglDrawBuffer(GL_NONE);
  state->vtkglReadBuffer(GL_NONE);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  state->vtkglViewport(0, 0, this->Resolution, this->Resolution);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglDepthFunc(GL_LESS);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_CULL_FACE); // open surfaces cast shadows from both sides
  state->vtkglClearDepth(1.0);

  float modelToWorld[16], remoteToWorld[16];
  ToColumnMajor(casters.ModelToWorld, modelToWorld);
  ToColumnMajor(casters.RemoteToWorld, remoteToWorld);
  const bool remote = !lights.empty() && casters.Remote && !casters.Remote->empty();
  if (remote && this->RemoteUploaded != casters.RemoteVersion)
  {
    // Uploaded once per gather, not per render of the maps.
    this->RemoteBuffer->Upload(*casters.Remote, vtkOpenGLBufferObject::ArrayBuffer);
    this->RemoteUploaded = casters.RemoteVersion;
    this->RemoteVertices = static_cast<int>(casters.Remote->size() / 3);
  }
  for (int layer = 0; layer < this->Layers; ++layer)
  {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, this->TextureHandle, 0, layer);
    state->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
  // Two programs, each with its vertex array: the radial depth (cube and spot maps) and the
  // projection's own (directional maps).
  std::string radialFS = vtkGlobalIlluminationShadowFS, planarFS = vtkGlobalIlluminationShadowFS;
  vtkShaderProgram::Substitute(radialFS, "//VTK::ShadowDepth::Dec", "#define giRadial");
  vtkNew<vtkOpenGLVertexArrayObject> radialVao, planarVao;
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const Light& light = lights[i];
    const Map& map = this->Maps[i];
    if (map.Kind == 0)
    {
      continue;
    }
    const bool radial = map.Kind != 3;
    vtkShaderProgram* program = window->GetShaderCache()->ReadyShaderProgram(
      vtkGlobalIlluminationShadowVS, radial ? radialFS.c_str() : planarFS.c_str(), "");
    if (!program)
    {
      continue; // the shader cache has reported why
    }
    vtkOpenGLVertexArrayObject* vao = radial ? radialVao.GetPointer() : planarVao.GetPointer();
    vao->Bind();
    if (radial)
    {
      program->SetUniform3f("giLightPosition", light.Position.data());
      const float depthMap[2] = { float(map.DepthMap[0]), float(map.DepthMap[1]) };
      program->SetUniform2f("giDepthMap", depthMap);
    }
    const int faces = map.Kind == 1 ? 6 : 1;
    for (int face = 0; face < faces; ++face)
    {
      Mat4 worldToClip = map.WorldToClip;
      if (map.Kind == 1)
      {
        const double farZ = 1.0 / map.DepthMap[0];
        worldToClip = Perspective(
          light.Position.data(), FaceU[face], FaceV[face], FaceF[face], 1.0, farZ * 1e-4, farZ);
      }
      float clip[16];
      ToColumnMajor(worldToClip, clip);
      program->SetUniformMatrix4x4("giWorldToClip", clip);
      glFramebufferTextureLayer(
        GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, this->TextureHandle, 0, map.Layer + face);
      program->SetUniformMatrix4x4("giModelToWorld", modelToWorld);
      casters.Draw(program, vao);
      if (remote)
      {
        program->SetUniformMatrix4x4("giModelToWorld", remoteToWorld);
        vao->AddAttributeArray(
          program, this->RemoteBuffer, "vertexMC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false);
        glDrawArrays(GL_TRIANGLES, 0, this->RemoteVertices);
      }
    }
    vao->Release();
  }
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, 0, 0, 0);
  state->PopFramebufferBindings();
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationShadowMaps::Activate()
{
  if (!this->TextureHandle)
  {
    return false;
  }
  this->Texture->Activate();
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShadowMaps::Deactivate()
{
  this->Texture->Deactivate();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShadowMaps::SetUniforms(
  vtkShaderProgram* program, int lightCount, double filterRadius, double bias)
{
  const int unit = this->TextureHandle ? this->Texture->GetTextureUnit() : -1;
  if (unit >= 0)
  {
    program->SetUniformi("giShadowMaps", unit);
  }
  const float filter[3] = { 1.f / float(std::max(this->Resolution, 1)), float(filterRadius),
    float(bias) };
  program->SetUniform3f("giShadowFilter", filter);
  if (lightCount <= 0)
  {
    return;
  }
  std::vector<int> layers(lightCount, 0);
  std::vector<float> matrices(16 * lightCount, 0.f), depths(4 * lightCount, 0.f);
  for (int i = 0; i < lightCount && i < static_cast<int>(this->Maps.size()); ++i)
  {
    const Map& map = this->Maps[i];
    layers[i] = map.Layer;
    ToColumnMajor(map.WorldToClip, &matrices[16 * i]);
    depths[4 * i] = float(map.DepthMap[0]);
    depths[4 * i + 1] = float(map.DepthMap[1]);
    depths[4 * i + 2] = float(map.Texel[0]);
    depths[4 * i + 3] = float(map.Texel[1]);
  }
  program->SetUniform1iv("giShadowLayer", lightCount, layers.data());
  program->SetUniformMatrix4x4v("giShadowMatrix", lightCount, matrices.data());
  program->SetUniform4fv("giShadowDepth", lightCount, depths.data());
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationShadowMaps::GetKinds(int lightCount) const
{
  std::string kinds;
  for (int i = 0; i < lightCount; ++i)
  {
    // Lights without a map (shadows off) are kind 0: the shader has no lookup for them.
    const int kind = i < static_cast<int>(this->Maps.size()) ? this->Maps[i].Kind : 0;
    kinds += (i > 0 ? ", " : "") + std::to_string(kind);
  }
  return kinds;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShadowMaps::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->TextureHandle && window && window == this->Context)
  {
    this->Texture->ReleaseGraphicsResources(window);
    glDeleteTextures(1, &this->TextureHandle);
    glDeleteFramebuffers(1, &this->Framebuffer);
  }
  if (window && window == this->Context)
  {
    this->RemoteBuffer->ReleaseGraphicsResources();
  }
  this->RemoteUploaded = 0;
  this->RemoteVertices = 0;
  this->TextureHandle = 0;
  this->Framebuffer = 0;
  this->Layers = 0;
  this->Resolution = 0;
  this->Signature.clear();
  this->Context = nullptr;
}
