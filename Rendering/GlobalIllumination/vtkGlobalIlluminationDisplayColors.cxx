#include "vtkGlobalIlluminationDisplayColors.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationColors.h"
#include "vtkGlobalIlluminationDrawnColors.h"
#include "vtkGlobalIlluminationLights.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace
{
using Colors = vtkGlobalIlluminationColors;
using RGB = Colors::RGB;
using GIShading = vtkGlobalIlluminationShading;

/// The display curve of a look: the shaders' giKeepHue and giToneMap.
struct Curve
{
  int ToneMapping = GIShading::HUE_PRESERVING;
  double Exposure = 1.0;
  double InverseGamma = 1.0 / 2.2;

  /// The display value of a surface of drawn colour `drawn` (display units) and linear
  /// albedo `albedo` receiving irradiance `e` and emitting (or reflecting glossily) `le`.
  RGB Display(const RGB& drawn, const RGB& albedo, const RGB& e, const RGB& le) const
  {
    RGB c;
    if (this->ToneMapping == GIShading::HUE_PRESERVING)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[k] = this->Exposure * (drawn[k] * e[k] + vtkMath::Pi() * le[k]);
      }
      return KeepHue(c);
    }
    for (int k = 0; k < 3; ++k)
    {
      double x = std::max((albedo[k] / vtkMath::Pi() * e[k] + le[k]) * this->Exposure, 0.0);
      if (this->ToneMapping == GIShading::EXPONENTIAL)
      {
        x = 1.0 - std::exp(-x);
      }
      else if (this->ToneMapping == GIShading::REINHARD)
      {
        x = x / (1.0 + x);
      }
      c[k] = std::pow(x, this->InverseGamma);
    }
    return c;
  }

  /// Within [0, 1] as it is; beyond, the luminance kept (up to white) and the colour blended
  /// towards its grey just enough to fit (vtkGlobalIlluminationGIShading::HUE_PRESERVING).
  static RGB KeepHue(RGB c)
  {
    for (double& v : c)
    {
      v = std::max(v, 0.0);
    }
    const double top = std::max({ c[0], c[1], c[2] });
    const double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    const double grey = std::min(y, 1.0);
    const double keep =
      top > 1.0 ? std::min(std::max((1.0 - grey) / std::max(top - y, 1e-6), 0.0), 1.0) : 1.0;
    for (double& v : c)
    {
      v = std::min(grey + (v - y) * keep, 1.0);
    }
    return c;
  }
};

unsigned char Byte(double v)
{
  // NaN fails both comparisons and becomes 0.
  const double clamped = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
  return static_cast<unsigned char>(std::lround(clamped * 255.0));
}

/// Tuple `i` of `array` in the range of `quantity`; black where there is no array.
RGB Value(vtkDataArray* array, vtkIdType i, Colors::Quantity quantity)
{
  return array ? Colors::Clamp(Colors::Read(array, i), quantity) : RGB{ { 0.0, 0.0, 0.0 } };
}

/// `in` with every cell on points of its own (cell data kept, point data copied), and
/// for every new point the cell it belongs to.
vtkSmartPointer<vtkPolyData> Explode(vtkPolyData* in, std::vector<vtkIdType>& cellOfPoint)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(in->GetPoints() ? in->GetPoints()->GetDataType() : VTK_FLOAT);
  vtkPointData* from = in->GetPointData();
  vtkPointData* to = out->GetPointData();
  const vtkIdType corners = in->GetVerts()->GetNumberOfConnectivityIds() +
    in->GetLines()->GetNumberOfConnectivityIds() + in->GetPolys()->GetNumberOfConnectivityIds() +
    in->GetStrips()->GetNumberOfConnectivityIds();
  points->Allocate(corners);
  to->CopyAllocate(from, corners);
  cellOfPoint.clear();
  cellOfPoint.reserve(static_cast<std::size_t>(corners));
  vtkIdType cell = 0;
  std::vector<vtkIdType> ids;
  std::array<vtkCellArray*, 4> arrays{ { in->GetVerts(), in->GetLines(), in->GetPolys(),
    in->GetStrips() } };
  std::array<vtkSmartPointer<vtkCellArray>, 4> exploded;
  for (std::size_t a = 0; a < arrays.size(); ++a)
  {
    exploded[a] = vtkSmartPointer<vtkCellArray>::New();
    vtkIdType n = 0;
    const vtkIdType* pts = nullptr;
    for (arrays[a]->InitTraversal(); arrays[a]->GetNextCell(n, pts); ++cell)
    {
      ids.resize(static_cast<std::size_t>(n));
      for (vtkIdType k = 0; k < n; ++k)
      {
        ids[k] = points->InsertNextPoint(in->GetPoint(pts[k]));
        to->CopyData(from, pts[k], ids[k]);
        cellOfPoint.push_back(cell);
      }
      exploded[a]->InsertNextCell(n, ids.data());
    }
  }
  out->SetPoints(points);
  out->SetVerts(exploded[0]);
  out->SetLines(exploded[1]);
  out->SetPolys(exploded[2]);
  out->SetStrips(exploded[3]);
  out->GetCellData()->ShallowCopy(in->GetCellData());
  out->GetFieldData()->ShallowCopy(in->GetFieldData());
  return out;
}
}

vtkStandardNewMacro(vtkGlobalIlluminationDisplayColors);
vtkCxxSetObjectMacro(vtkGlobalIlluminationDisplayColors, Shading, vtkGlobalIlluminationShading);
vtkCxxSetObjectMacro(vtkGlobalIlluminationDisplayColors, Mapper, vtkMapper);
vtkCxxSetObjectMacro(vtkGlobalIlluminationDisplayColors, Property, vtkProperty);
vtkCxxSetObjectMacro(vtkGlobalIlluminationDisplayColors, Lights, vtkLightCollection);

//------------------------------------------------------------------------------
vtkGlobalIlluminationDisplayColors::vtkGlobalIlluminationDisplayColors() = default;

//------------------------------------------------------------------------------
vtkGlobalIlluminationDisplayColors::~vtkGlobalIlluminationDisplayColors()
{
  this->SetShading(nullptr);
  this->SetMapper(nullptr);
  this->SetProperty(nullptr);
  this->SetLights(nullptr);
}

//------------------------------------------------------------------------------
const char* vtkGlobalIlluminationDisplayColors::GetColorsArrayName(int mode, bool back)
{
  switch (mode)
  {
    case GIShading::DIRECT:
      return back ? "DisplayColorsDirectBack" : "DisplayColorsDirect";
    case GIShading::INDIRECT:
      return back ? "DisplayColorsIndirectBack" : "DisplayColorsIndirect";
    default:
      return back ? "DisplayColorsBack" : "DisplayColors";
  }
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationDisplayColors::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGlobalIlluminationDisplayColors::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  const auto newer = [&time](vtkObject* o) {
    if (o)
    {
      time = std::max(time, o->GetMTime());
    }
  };
  newer(this->Shading);
  newer(this->Mapper);
  newer(this->Mapper ? this->Mapper->GetLookupTable() : nullptr);
  newer(this->Property);
  newer(this->Lights);
  if (this->Lights)
  {
    vtkCollectionSimpleIterator it;
    this->Lights->InitTraversal(it);
    while (vtkLight* light = this->Lights->GetNextLight(it))
    {
      newer(light);
    }
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationDisplayColors::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  auto defaults = vtkSmartPointer<GIShading>::New();
  GIShading* shading = this->Shading ? this->Shading : defaults.Get();

  // The look, as the mappers choose it (vtkGlobalIlluminationMapperCore::UpdateLook).
  bool lamps = false;
  if (this->Lights)
  {
    vtkCollectionSimpleIterator it;
    this->Lights->InitTraversal(it);
    while (vtkLight* light = this->Lights->GetNextLight(it))
    {
      vtkGlobalIlluminationLights::Light converted;
      lamps = lamps ||
        (vtkGlobalIlluminationLights::Convert(light, shading->GetLightIntensityScale(), converted,
           shading->GetLightFalloff()) == vtkGlobalIlluminationLights::CONVERTED &&
          converted.FallsOff());
    }
  }
  std::vector<vtkPolyData*> leaves = vtkCompositeDataSet::GetDataSets<vtkPolyData>(input);
  if (!this->Lights)
  {
    // Without the lights, what vtkGlobalIlluminationFilter recorded of them.
    std::vector<vtkDataObject*> holders(leaves.begin(), leaves.end());
    holders.push_back(input); // a composite output has it on the composite
    for (vtkDataObject* holder : holders)
    {
      vtkFieldData* fd = holder->GetFieldData();
      auto recorded = vtkDataArray::SafeDownCast(fd ? fd->GetAbstractArray("LinkGI.Lamps") : nullptr);
      lamps = lamps || (recorded && recorded->GetNumberOfTuples() > 0 && recorded->GetTuple1(0) > 0);
    }
  }
  std::vector<vtkDataArray*> radiance;
  for (vtkPolyData* leaf : leaves)
  {
    const char* name = shading->GetRadianceArrayName();
    radiance.push_back(name ? leaf->GetPointData()->GetArray(name) : nullptr);
  }
  const GIShading::Look look = shading->GetLook(lamps, radiance);
  Curve curve;
  curve.ToneMapping = look.ToneMapping;
  curve.Exposure = look.Exposure;
  curve.InverseGamma = 1.0 / shading->GetGamma();
  this->ToneMapping = look.ToneMapping;
  this->Exposure = look.Exposure;

  // The colour drawn where the data give none: the property's, times Diffuse.
  RGB solid{ { 1.0, 1.0, 1.0 } };
  double diffuse = 1.0;
  if (this->Property)
  {
    this->Property->GetDiffuseColor(solid.data());
    diffuse = this->Property->GetDiffuse();
  }
  bool cells = false;
  const bool mapped = vtkGlobalIlluminationDrawnColors::MapsScalars(this->Mapper, cells);

  const auto bake = [&](vtkPolyData* in) -> vtkSmartPointer<vtkPolyData> {
    vtkDataArray* scalars =
      mapped ? vtkGlobalIlluminationDrawnColors::ColoringArray(in, this->Mapper, cells) : nullptr;
    const char* albedoName = shading->GetAlbedoArrayName();
    vtkDataArray* albedo = albedoName ? in->GetPointData()->GetArray(albedoName) : nullptr;
    vtkSmartPointer<vtkUnsignedCharArray> rgba =
      (scalars && !albedo) ? vtkGlobalIlluminationDrawnColors::Map(this->Mapper, scalars) : nullptr;
    std::vector<vtkIdType> cellOfPoint;
    vtkSmartPointer<vtkPolyData> out;
    if (rgba && cells)
    {
      out = Explode(in, cellOfPoint);
    }
    else
    {
      out = vtkSmartPointer<vtkPolyData>::New();
      out->ShallowCopy(in);
    }
    vtkPointData* pd = out->GetPointData();
    if (albedo)
    {
      albedo = pd->GetArray(albedoName);
    }
    const std::string indirectName =
      shading->GetIndirectIrradianceArrayName() ? shading->GetIndirectIrradianceArrayName() : "";
    const char* emissionName = shading->GetEmissionArrayName();
    vtkDataArray* emission = emissionName ? pd->GetArray(emissionName) : nullptr;
    const vtkIdType n = out->GetNumberOfPoints();
    for (const bool back : { false, true })
    {
      const std::string suffix = back ? "Back" : "";
      vtkDataArray* direct = pd->GetArray(("DirectIrradiance" + suffix).c_str());
      vtkDataArray* indirect =
        indirectName.empty() ? nullptr : pd->GetArray((indirectName + suffix).c_str());
      if (back && !direct && !indirect)
      {
        continue; // one-sided: back faces show the front's colours
      }
      std::array<vtkSmartPointer<vtkUnsignedCharArray>, 3> arrays;
      for (int mode = 0; mode < 3; ++mode)
      {
        arrays[mode] = vtkSmartPointer<vtkUnsignedCharArray>::New();
        arrays[mode]->SetName(GetColorsArrayName(mode, back));
        arrays[mode]->SetNumberOfComponents(3);
        arrays[mode]->SetNumberOfTuples(n);
      }
      for (vtkIdType i = 0; i < n; ++i)
      {
        RGB drawn = solid;
        RGB linear;
        if (albedo)
        {
          linear = Value(albedo, i, Colors::REFLECTANCE);
          for (int k = 0; k < 3; ++k)
          {
            drawn[k] = Colors::ToDisplay(linear[k]);
          }
        }
        else
        {
          if (rgba)
          {
            const vtkIdType tuple = cells ? cellOfPoint[static_cast<std::size_t>(i)] : i;
            for (int k = 0; k < 3; ++k)
            {
              drawn[k] = rgba->GetTypedComponent(tuple, k) / 255.0;
            }
          }
          for (int k = 0; k < 3; ++k)
          {
            drawn[k] *= diffuse;
            linear[k] = Colors::ToLinear(drawn[k]);
          }
        }
        const RGB ed = Value(direct, i, Colors::RADIOMETRIC);
        const RGB ei = Value(indirect, i, Colors::RADIOMETRIC);
        const RGB le = Value(emission, i, Colors::RADIOMETRIC);
        const RGB black{ { 0.0, 0.0, 0.0 } };
        const RGB both{ { ed[0] + ei[0], ed[1] + ei[1], ed[2] + ei[2] } };
        const std::array<RGB, 3> shown{ { curve.Display(drawn, linear, both, le),
          curve.Display(drawn, linear, ed, le), curve.Display(drawn, linear, ei, black) } };
        for (int mode = 0; mode < 3; ++mode)
        {
          for (int k = 0; k < 3; ++k)
          {
            arrays[mode]->SetTypedComponent(i, k, Byte(shown[mode][k]));
          }
        }
      }
      for (const auto& array : arrays)
      {
        pd->AddArray(array);
      }
    }
    return out;
  };

  if (auto composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    auto result = vtkCompositeDataSet::SafeDownCast(output);
    result->CopyStructure(composite);
    auto it = vtk::TakeSmartPointer(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
      {
        result->SetDataSet(it, bake(leaf));
      }
    }
  }
  else if (auto poly = vtkPolyData::SafeDownCast(input))
  {
    output->ShallowCopy(bake(poly));
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationDisplayColors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shading: " << this->Shading << "\n";
  os << indent << "Mapper: " << this->Mapper << "\n";
  os << indent << "Property: " << this->Property << "\n";
  os << indent << "Lights: " << this->Lights << "\n";
  os << indent << "Tone Mapping: " << this->ToneMapping << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
}
