#include "vtkGlobalIlluminationMapperCore.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationGeometry.h"
#include "vtkGlobalIlluminationGlobalCasters.h"
#include "vtkGlobalIlluminationLights.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include "vtkGlobalIlluminationLightDec.h"
#include "vtkGlobalIlluminationLightImpl.h"
#include "vtkGlobalIlluminationUniformFlow.h"
#include "vtkGlobalIlluminationVertexDec.h"
#include "vtkGlobalIlluminationVertexImpl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace
{
using ShadowMaps = vtkGlobalIlluminationShadowMaps;

/// A row-major double matrix as the column-major floats a uniform takes.
void ToColumnMajor(const std::array<double, 16>& m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m[4 * r + c]);
    }
  }
}

/// The positions as the VBO holds them (possibly shifted and scaled) to world coordinates.
std::array<double, 16> ModelToWorld(vtkOpenGLVertexBufferObject* positions, vtkActor* actor)
{
  vtkNew<vtkMatrix4x4> unshift;
  if (positions->GetCoordShiftAndScaleEnabled())
  {
    const std::vector<double>& shift = positions->GetShift();
    const std::vector<double>& scale = positions->GetScale();
    for (int k = 0; k < 3; ++k)
    {
      unshift->SetElement(k, k, 1.0 / scale[k]);
      unshift->SetElement(k, 3, shift[k]);
    }
  }
  vtkNew<vtkMatrix4x4> result;
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), unshift, result);
  std::array<double, 16> m;
  std::copy(&result->Element[0][0], &result->Element[0][0] + 16, m.begin());
  return m;
}

/// `m` (row-major) followed by a translation by -origin.
void MoveOrigin(std::array<double, 16>& m, const std::array<double, 3>& origin)
{
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[4 * r + c] -= origin[r] * m[12 + c];
    }
  }
}

/// One number for the drawn blocks' geometry: a hash of each block's
/// vtkGlobalIlluminationGeometry::Sources and their modification times. Not the
/// buffers' upload time: the same surface handed over as a new data object (a new
/// solution's arrays beside the same points and cells) is uploaded again, and its maps
/// would be rendered again for nothing.
vtkMTimeType CastersVersion(const std::vector<vtkPolyData*>& drawn)
{
  std::uint64_t hash = 0;
  const auto mix = [&hash](std::uint64_t value)
  {
    // splitmix64's finalizer over the running hash and the value
    std::uint64_t z = hash ^ (value + 0x9e3779b97f4a7c15ull + (hash << 6) + (hash >> 2));
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    hash = z ^ (z >> 31);
  };
  for (vtkPolyData* poly : drawn)
  {
    mix(poly != nullptr); // one entry per block, a missing one too
    for (vtkObject* o : vtkGlobalIlluminationGeometry::Sources(poly))
    {
      mix(reinterpret_cast<std::uintptr_t>(o));
      mix(o ? o->GetMTime() : 0);
    }
  }
  return hash;
}

/// The centre of `bounds`, or the origin for empty bounds.
std::array<double, 3> Centre(const std::array<double, 6>& bounds)
{
  std::array<double, 3> centre{};
  for (int k = 0; k < 3; ++k)
  {
    const double lo = bounds[2 * k], hi = bounds[2 * k + 1];
    centre[k] = lo <= hi && std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : 0.0;
  }
  return centre;
}
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapperCore::vtkGlobalIlluminationMapperCore(vtkObject* owner)
  : Owner(owner)
{
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapperCore::~vtkGlobalIlluminationMapperCore() = default;

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationMapperCore::Shades(
  int primitiveType, int lightComplexity, vtkActor* actor)
{
  const bool surface = primitiveType == vtkOpenGLPolyDataMapper::PrimitiveTris ||
    primitiveType == vtkOpenGLPolyDataMapper::PrimitiveTriStrips;
  return surface && lightComplexity > 0 && actor &&
    actor->GetProperty()->GetInterpolation() != VTK_PBR;
}

//------------------------------------------------------------------------------
ShadowMaps::Casters vtkGlobalIlluminationMapperCore::MakeCasters(
  vtkOpenGLVertexBufferObjectGroup* vbos, vtkOpenGLHelper* primitives, vtkActor* actor,
  const std::vector<vtkPolyData*>& drawn)
{
  ShadowMaps::Casters casters;
  vtkOpenGLVertexBufferObject* positions = vbos->GetVBO("vertexMC");
  // Wireframe and point representations draw no surfaces and cast no shadows.
  if (!positions || actor->GetProperty()->GetRepresentation() != VTK_SURFACE)
  {
    return casters;
  }
  casters.ModelToWorld = ModelToWorld(positions, actor);
  actor->GetBounds(casters.WorldBounds.data());
  casters.Version = CastersVersion(drawn);
  casters.Draw = [vbos, primitives](vtkShaderProgram* program, vtkOpenGLVertexArrayObject* vao)
  {
    vtkOpenGLVertexBufferObject* vbo = vbos->GetVBO("vertexMC");
    vao->AddAttributeArray(program, vbo, "vertexMC", 0, false);
    const GLuint last = static_cast<GLuint>(std::max(vbo->GetNumberOfTuples(), 1u) - 1);
    for (int type :
      { vtkOpenGLPolyDataMapper::PrimitiveTris, vtkOpenGLPolyDataMapper::PrimitiveTriStrips })
    {
      vtkOpenGLIndexBufferObject* ibo = primitives[type].IBO;
      if (ibo->IndexCount == 0)
      {
        continue;
      }
      ibo->Bind();
      glDrawRangeElements(
        GL_TRIANGLES, 0, last, static_cast<GLsizei>(ibo->IndexCount), GL_UNSIGNED_INT, nullptr);
      ibo->Release();
    }
  };
  return casters;
}

//------------------------------------------------------------------------------
ShadowMaps::Casters vtkGlobalIlluminationMapperCore::AddGlobalCasters(
  const ShadowMaps::Casters& own, vtkActor* actor) const
{
  vtkGlobalIlluminationGlobalCasters* global =
    this->Shading ? this->Shading->GetGlobalCasters() : nullptr;
  if (!global || global->GetNumberOfTriangles() == 0 || !own.Draw || !actor)
  {
    return own;
  }
  ShadowMaps::Casters casters = own;
  casters.Remote = &global->GetPositions();
  casters.RemoteVersion = global->GetMTime(); // changes with every exchange, unique per object
  // The actor's matrix after the translation by the positions' origin.
  vtkNew<vtkMatrix4x4> origin;
  for (int k = 0; k < 3; ++k)
  {
    origin->SetElement(k, 3, global->GetOrigin()[k]);
  }
  vtkNew<vtkMatrix4x4> remoteToWorld;
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), origin, remoteToWorld);
  std::copy(&remoteToWorld->Element[0][0], &remoteToWorld->Element[0][0] + 16,
    casters.RemoteToWorld.begin());
  // The maps' frusta cover both: the world bounds of the remote box's corners.
  const double* b = global->GetBounds();
  double* w = casters.WorldBounds.data();
  for (int corner = 0; corner < 8; ++corner)
  {
    double p[4] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1.0 };
    actor->GetMatrix()->MultiplyPoint(p, p);
    for (int k = 0; k < 3; ++k)
    {
      w[2 * k] = std::min(w[2 * k], p[k] / p[3]);
      w[2 * k + 1] = std::max(w[2 * k + 1], p[k] / p[3]);
    }
  }
  return casters;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::Prepare(vtkRenderer* renderer, vtkActor* actor,
  const ShadowMaps::Casters& ownCasters, const std::vector<vtkPolyData*>& drawn)
{
  ShadowMaps::Casters casters = this->AddGlobalCasters(ownCasters, actor);
  this->Origin = Centre(casters.WorldBounds);
  MoveOrigin(casters.ModelToWorld, this->Origin);
  MoveOrigin(casters.RemoteToWorld, this->Origin);
  for (int k = 0; k < 6; ++k)
  {
    casters.WorldBounds[k] -= this->Origin[k / 2];
  }
  const double scale = this->Shading ? this->Shading->GetLightIntensityScale() : 1.0;
  const int maximum = vtkGlobalIlluminationShading::GetMaximumNumberOfLights();
  this->Lights.clear();
  std::vector<bool> atEye;
  int ignored = 0;
  std::vector<std::string> skipped;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    ShadowMaps::Light converted;
    const auto status = vtkGlobalIlluminationLights::Convert(
      light, scale, converted, this->Shading ? this->Shading->GetLightFalloff() : 0);
    const std::string why = vtkGlobalIlluminationLights::Explain(status, light);
    if (!why.empty())
    {
      skipped.push_back(why);
    }
    else if (status == vtkGlobalIlluminationLights::CONVERTED)
    {
      if (static_cast<int>(this->Lights.size()) < maximum)
      {
        for (int k = 0; k < 3; ++k)
        {
          converted.Position[k] -= this->Origin[k];
        }
        this->Lights.push_back(converted);
        atEye.push_back(light->LightTypeIsHeadlight());
      }
      else
      {
        ++ignored;
      }
    }
  }
  // Once per change, not per frame.
  if (ignored > 0 && ignored != this->IgnoredLightsWarned)
  {
    vtkWarningWithObjectMacro(
      this->Owner, << "The renderer has " << ignored << " more switched-on lights than the "
                   << maximum << " a global illumination mapper shades; they are ignored.");
  }
  this->IgnoredLightsWarned = ignored;
  if (skipped != this->SkippedLightsWarned)
  {
    for (const std::string& warning : skipped)
    {
      vtkWarningWithObjectMacro(this->Owner, << warning);
    }
    this->SkippedLightsWarned = skipped;
  }
  this->UpdateLook(drawn);
  auto* window = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  const bool shadows = this->Shading && this->Shading->GetShadows();
  const int resolution = this->Shading ? this->Shading->GetShadowMapResolution() : 1024;
  this->ShadowMaps.Update(window, this->Lights, atEye, shadows, casters, resolution);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::UpdateLook(const std::vector<vtkPolyData*>& drawn)
{
  const bool lamps = std::any_of(this->Lights.begin(), this->Lights.end(),
    [](const ShadowMaps::Light& light) { return light.FallsOff(); });
  vtkGlobalIlluminationShading* s = this->Shading;
  std::vector<vtkDataArray*> radiance;
  std::ostringstream key;
  key << lamps << ' ' << (s ? s->GetMTime() : 0);
  for (vtkPolyData* poly : drawn)
  {
    vtkDataArray* array = poly && s && s->GetRadianceArrayName()
      ? poly->GetPointData()->GetArray(s->GetRadianceArrayName())
      : nullptr;
    radiance.push_back(array);
    key << ' ' << array << ' ' << (array ? array->GetMTime() : 0);
  }
  // The percentile is a pass over every point: once per new solution, not per frame.
  if (key.str() != this->LookKey)
  {
    this->CurrentLook = s ? s->GetLook(lamps, radiance) : vtkGlobalIlluminationShading::Look();
    this->LookKey = key.str();
  }
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::LightTypes() const
{
  std::string types;
  for (std::size_t i = 0; i < this->Lights.size(); ++i)
  {
    types += (i > 0 ? ", " : "") + std::to_string(this->Lights[i].Type);
  }
  return types;
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::ShaderKey(vtkActor* actor) const
{
  std::ostringstream key;
  key << this->LightTypes() << " / " << this->ShadowMaps.GetKinds(this->LightCount()) << " / "
      << this->Present.Albedo << this->Present.Indirect << this->Present.IndirectBack
      << this->Present.Emission;
  if (this->Shading)
  {
    key << ' ' << this->Shading->GetDisplayMode() << ' ' << this->CurrentLook.ToneMapping << ' '
        << (this->Shading->GetShadowFilterRadius() > 0.0);
  }
  key << ' ' << (actor && actor->GetProperty()->GetSpecular() > 0.0);
  return key.str();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::ReplaceShaderLight(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkActor* actor) const
{
  std::ostringstream defines;
  defines << "#define GI_LIGHT_COUNT " << this->Lights.size() << "\n"
          << "#define GI_LIGHT_TYPES " << this->LightTypes() << "\n"
          << "#define GI_SHADOW_KINDS " << this->ShadowMaps.GetKinds(this->LightCount()) << "\n"
          << "#define GI_HAS_ALBEDO " << this->Present.Albedo << "\n"
          << "#define GI_HAS_INDIRECT " << this->Present.Indirect << "\n"
          << "#define GI_HAS_INDIRECT_BACK "
          << (this->Present.Indirect && this->Present.IndirectBack) << "\n"
          << "#define GI_HAS_EMISSION " << this->Present.Emission << "\n"
          << "#define GI_GLOSSY " << (actor->GetProperty()->GetSpecular() > 0.0) << "\n"
          << "#define GI_MODE " << (this->Shading ? this->Shading->GetDisplayMode() : 0) << "\n"
          << "#define GI_TONE_MAPPING " << this->CurrentLook.ToneMapping << "\n"
          << "#define GI_SOFT_SHADOWS "
          << (this->Shading && this->Shading->GetShadowFilterRadius() > 0.0) << "\n";
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(vs, "//VTK::Light::Dec",
    defines.str() + vtkGlobalIlluminationVertexDec + "//VTK::Light::Dec", false);
  vtkShaderProgram::Substitute(vs, "//VTK::Light::Impl",
    std::string(vtkGlobalIlluminationVertexImpl) + "  //VTK::Light::Impl", false);
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Dec",
    defines.str() + vtkGlobalIlluminationLightDec + "//VTK::Light::Dec", false);
  vtkShaderProgram::Substitute(fs, "//VTK::UniformFlow::Impl",
    std::string(vtkGlobalIlluminationUniformFlow) + "  //VTK::UniformFlow::Impl", false);
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Impl",
    std::string(vtkGlobalIlluminationLightImpl) + "  //VTK::Light::Impl", false);
  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Fragment]->SetSource(fs);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::SetShaderParameters(
  vtkShaderProgram* program, vtkRenderer* renderer)
{
  vtkGlobalIlluminationShading* s = this->Shading;
  program->SetUniformf("giExposure", static_cast<float>(this->CurrentLook.Exposure));
  program->SetUniformf("giInvGamma", static_cast<float>(1.0 / (s ? s->GetGamma() : 2.2)));

  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkMatrix4x4> viewToWorld;
  vtkMatrix4x4::Invert(camera->GetModelViewTransformMatrix(), viewToWorld);
  std::array<double, 16> viewToLocal;
  std::copy(&viewToWorld->Element[0][0], &viewToWorld->Element[0][0] + 16, viewToLocal.begin());
  MoveOrigin(viewToLocal, this->Origin);
  float matrix[16];
  ToColumnMajor(viewToLocal, matrix);
  program->SetUniformMatrix4x4("giViewToWorld", matrix);
  float eye[4] = { 0.f, 0.f, 0.f, 0.f };
  double v[3];
  if (camera->GetParallelProjection())
  {
    camera->GetDirectionOfProjection(v);
    eye[3] = 1.f;
    for (double& x : v)
    {
      x = -x;
    }
  }
  else
  {
    camera->GetPosition(v);
    for (int k = 0; k < 3; ++k)
    {
      v[k] -= this->Origin[k];
    }
  }
  std::copy(v, v + 3, eye);
  program->SetUniform4fv("giCamera", 1, eye);

  const int n = static_cast<int>(this->Lights.size());
  std::vector<float> positions(3 * n), directions(3 * n), intensities(3 * n), cones(2 * n),
    attenuations(3 * n);
  for (int i = 0; i < n; ++i)
  {
    const ShadowMaps::Light& l = this->Lights[i];
    for (int k = 0; k < 3; ++k)
    {
      positions[3 * i + k] = static_cast<float>(l.Position[k]);
      directions[3 * i + k] = static_cast<float>(l.Direction[k]);
      intensities[3 * i + k] = static_cast<float>(l.Intensity[k]);
      attenuations[3 * i + k] = static_cast<float>(l.Attenuation[k]);
    }
    cones[2 * i] = static_cast<float>(l.CosCone());
    cones[2 * i + 1] = static_cast<float>(l.Exponent);
  }
  if (n > 0)
  {
    program->SetUniform3fv("giLightPosition", n, positions.data());
    program->SetUniform3fv("giLightDirection", n, directions.data());
    program->SetUniform3fv("giLightIntensity", n, intensities.data());
    program->SetUniform2fv("giLightCone", n, cones.data());
    program->SetUniform3fv("giLightAttenuation", n, attenuations.data());
  }
  if (!this->TextureActive)
  {
    this->TextureActive = this->ShadowMaps.Activate();
  }
  this->ShadowMaps.SetUniforms(
    program, n, s ? s->GetShadowFilterRadius() : 1.5, s ? s->GetShadowBias() : 1.0);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::FinishDraw()
{
  if (this->TextureActive)
  {
    this->ShadowMaps.Deactivate();
    this->TextureActive = false;
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::ReleaseGraphicsResources(vtkWindow* window)
{
  this->FinishDraw();
  this->ShadowMaps.ReleaseGraphicsResources(window);
}
