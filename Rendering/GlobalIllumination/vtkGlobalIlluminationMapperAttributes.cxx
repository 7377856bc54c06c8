// vtkGlobalIlluminationMapperCore, its per-vertex shading attributes: reading them from a
// polydata, their vertex buffers, and the keys that decide whether VTK's buffers must be
// built again or the attributes alone uploaded. (Lights, shadow maps and shaders are in
// vtkGlobalIlluminationMapperCore.cxx.)
#include "vtkGlobalIlluminationMapperCore.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationColors.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkMapper.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkTexture.h"

#include <cstdint>

namespace
{
/// The named point array as float colours (RGBA with A = 1 for the albedo, else RGB), or
/// null if the input has no numeric point array of that name with a tuple for every point.
/// Read and clamped by vtkGlobalIlluminationColors, the filter's rule.
vtkSmartPointer<vtkFloatArray> ReadColors(vtkPolyData* poly, const char* name, bool albedo)
{
  vtkDataArray* array = (name && *name) ? poly->GetPointData()->GetArray(name) : nullptr;
  const vtkIdType n = poly->GetNumberOfPoints();
  if (!array || array->GetNumberOfTuples() < n || array->GetNumberOfComponents() < 1)
  {
    return nullptr;
  }
  using Colors = vtkGlobalIlluminationColors;
  const Colors::Quantity quantity = albedo ? Colors::REFLECTANCE : Colors::RADIOMETRIC;
  auto out = vtkSmartPointer<vtkFloatArray>::New();
  out->SetNumberOfComponents(albedo ? 4 : 3);
  out->SetNumberOfTuples(n);
  float* values = out->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (double v : Colors::Clamp(Colors::Read(array, i), quantity))
    {
      *values++ = static_cast<float>(v);
    }
    if (albedo)
    {
      *values++ = 1.f;
    }
  }
  return out;
}

/// Whether every value of `array` is 0 (an "Emission" array of a scene that emits
/// nothing): such an attribute only costs interpolation.
bool AllZero(vtkDataArray* array)
{
  for (int k = 0; k < array->GetNumberOfComponents(); ++k)
  {
    double range[2];
    array->GetRange(range, k);
    if (range[0] != 0.0 || range[1] != 0.0)
    {
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkFloatArray> Zeros(vtkIdType tuples, int components)
{
  auto out = vtkSmartPointer<vtkFloatArray>::New();
  out->SetNumberOfComponents(components);
  out->SetNumberOfTuples(tuples);
  out->Fill(0.0);
  return out;
}

/// Appends an object's address and modification time (0 0 for none).
void AppendObject(std::string& key, vtkObject* object)
{
  key += std::to_string(reinterpret_cast<std::uintptr_t>(object));
  key += ':';
  key += std::to_string(object ? object->GetMTime() : 0);
  key += ' ';
}

}

//------------------------------------------------------------------------------
const std::array<vtkGlobalIlluminationMapperCore::Buffer, 4>& vtkGlobalIlluminationMapperCore::Buffers()
{
  static const std::array<Buffer, 4> buffers = { {
    { "giAlbedoMC", &Layout::Albedo, &Attributes::Albedo },
    { "giIndirectMC", &Layout::Indirect, &Attributes::Indirect },
    { "giIndirectBackMC", &Layout::IndirectBack, &Attributes::IndirectBack },
    { "giEmissionMC", &Layout::Emission, &Attributes::Emission },
  } };
  return buffers;
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapperCore::Attributes vtkGlobalIlluminationMapperCore::MakeAttributes(
  vtkPolyData* poly, bool fill) const
{
  Attributes a;
  if (!poly || !this->Shading)
  {
    return a;
  }
  a.Albedo = ReadColors(poly, this->Shading->GetAlbedoArrayName(), true);
  a.Indirect = ReadColors(poly, this->Shading->GetIndirectIrradianceArrayName(), false);
  a.IndirectBack = ReadColors(poly, this->BackName().c_str(), false);
  a.Emission = this->GetLayout(poly).Emission
    ? ReadColors(poly, this->Shading->GetEmissionArrayName(), false)
    : nullptr;
  if (fill)
  {
    const vtkIdType n = poly->GetNumberOfPoints();
    a.Albedo = a.Albedo ? a.Albedo : Zeros(n, 4);
    a.Indirect = a.Indirect ? a.Indirect : Zeros(n, 3);
    a.IndirectBack = a.IndirectBack ? a.IndirectBack : a.Indirect;
    a.Emission = a.Emission ? a.Emission : Zeros(n, 3);
  }
  return a;
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::BackName() const
{
  const char* name = this->Shading ? this->Shading->GetIndirectIrradianceArrayName() : nullptr;
  return name && *name ? std::string(name) + "Back" : std::string();
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapperCore::Layout vtkGlobalIlluminationMapperCore::GetLayout(
  vtkPolyData* poly) const
{
  const auto has = [poly](const char* name)
  {
    vtkDataArray* array = (poly && name && *name) ? poly->GetPointData()->GetArray(name) : nullptr;
    return array && array->GetNumberOfTuples() >= poly->GetNumberOfPoints() &&
      array->GetNumberOfComponents() > 0;
  };
  Layout layout;
  layout.Albedo = this->Shading && has(this->Shading->GetAlbedoArrayName());
  layout.Indirect = this->Shading && has(this->Shading->GetIndirectIrradianceArrayName());
  layout.IndirectBack = this->Shading && has(this->BackName().c_str());
  layout.Emission = this->Shading && has(this->Shading->GetEmissionArrayName()) &&
    !AllZero(poly->GetPointData()->GetArray(this->Shading->GetEmissionArrayName()));
  return layout;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::Keep(const Attributes& attributes)
{
  for (const auto& array :
    { attributes.Albedo, attributes.Indirect, attributes.IndirectBack, attributes.Emission })
  {
    if (array)
    {
      this->Kept.push_back(array);
    }
  }
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::BufferKey() const
{
  const auto name = [](const char* s) { return std::string(s ? s : ""); };
  vtkGlobalIlluminationShading* s = this->Shading;
  return s ? name(s->GetAlbedoArrayName()) + '\n' + name(s->GetIndirectIrradianceArrayName()) +
      '\n' + name(s->GetEmissionArrayName())
           : std::string();
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::GeometryKey(
  vtkMapper* mapper, vtkActor* actor, const std::vector<vtkPolyData*>& polys) const
{
  // Not a composite mapper's display attributes: block visibility, opacity and colour are
  // set at each draw (and ParaView modifies them at every render).
  std::string key = std::to_string(mapper->GetMTime()) + ' ' +
    std::to_string(actor->GetProperty()->GetMTime()) + ' ' +
    std::to_string(actor->GetTexture() ? actor->GetTexture()->GetMTime() : 0) + '\n';
  const std::string indirect = this->Shading && this->Shading->GetIndirectIrradianceArrayName()
    ? this->Shading->GetIndirectIrradianceArrayName()
    : "";
  const std::string back = this->BackName();
  for (vtkPolyData* poly : polys)
  {
    key += std::to_string(reinterpret_cast<std::uintptr_t>(poly)); // its time moves with any array
    key += '|';
    if (!poly)
    {
      continue;
    }
    AppendObject(key, poly->GetPoints());
    for (vtkCellArray* cells :
      { poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips() })
    {
      AppendObject(key, cells);
    }
    for (vtkFieldData* data : { static_cast<vtkFieldData*>(poly->GetPointData()),
           static_cast<vtkFieldData*>(poly->GetCellData()) })
    {
      key += '|';
      for (int a = 0; a < data->GetNumberOfArrays(); ++a)
      {
        vtkAbstractArray* array = data->GetAbstractArray(a);
        const char* name = array ? array->GetName() : nullptr;
        const bool shadingOnly = name &&
          (vtkGlobalIlluminationFilter::IsResultArray(name) ||
            (!indirect.empty() && indirect == name) || (!back.empty() && back == name));
        if (!shadingOnly)
        {
          AppendObject(key, array);
        }
      }
    }
    key += '|';
    if (mapper->GetScalarVisibility())
    {
      // What the mapper colours by, light array or not (its mapped colours are in the buffers).
      int cellFlag = 0;
      AppendObject(key, vtkAbstractMapper::GetAbstractScalars(poly, mapper->GetScalarMode(),
        mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag));
    }
    key += '\n';
  }
  return key;
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationMapperCore::ShadingKey(const std::vector<vtkPolyData*>& polys) const
{
  std::string key;
  const std::string back = this->BackName();
  for (vtkPolyData* poly : polys)
  {
    vtkPointData* data = poly ? poly->GetPointData() : nullptr;
    if (!data || !this->Shading)
    {
      continue;
    }
    for (const char* name : std::initializer_list<const char*>{ this->Shading->GetAlbedoArrayName(),
           this->Shading->GetIndirectIrradianceArrayName(), back.c_str(),
           this->Shading->GetEmissionArrayName() })
    {
      AppendObject(key, name && *name ? data->GetAbstractArray(name) : nullptr);
    }
    key += '|';
  }
  return key;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapperCore::UploadShading(
  vtkOpenGLVertexBufferObjectGroup* vbos, const std::vector<vtkPolyData*>& polys, bool fill) const
{
  std::vector<Attributes> attributes;
  for (vtkPolyData* poly : polys)
  {
    attributes.push_back(this->MakeAttributes(poly, fill));
  }
  // The calls vtkOpenGLVertexBufferObjectGroup::BuildAllVBOs makes, so that the buffers
  // end as a full build leaves them.
  for (const Buffer& buffer : Buffers())
  {
    vtkOpenGLVertexBufferObject* vbo =
      this->Present.*buffer.Present ? vbos->GetVBO(buffer.Name) : nullptr;
    if (!vbo)
    {
      continue;
    }
    if (attributes.size() == 1)
    {
      vbo->UploadDataArray(attributes[0].*buffer.Array);
      continue;
    }
    for (const Attributes& a : attributes)
    {
      vbo->AppendDataArray(a.*buffer.Array);
    }
    vbo->UploadVBO();
  }
}
