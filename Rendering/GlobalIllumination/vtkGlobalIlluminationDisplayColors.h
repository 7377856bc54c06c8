/**
 * @class   vtkGlobalIlluminationDisplayColors
 * @brief   the colours vtkGlobalIlluminationMapper displays, baked per vertex
 *
 * Per-vertex light is data on the mesh, so any viewer that draws vertex colours (a web
 * page, a glTF viewer, Blender, VTK itself with lighting off) can show a lit result
 * without LinkGI. This filter gives, per point of the output of
 * vtkGlobalIlluminationFilter, the colour the global illumination mappers display there:
 * the drawn colour (the Albedo array, the mapper's colour map or the property's solid
 * colour, times Diffuse) lit by the filter's DirectIrradiance and IndirectIrradiance,
 * plus Emission, through the exposure and tone curve of the vtkGlobalIlluminationShading
 * (vtkGlobalIlluminationShading::GetLook(), with the lamps of the given lights), exactly
 * as the mappers' shaders compute it. Three unsigned char RGB point arrays, display (sRGB)
 * values, one per display mode:
 * - `DisplayColors`: direct + indirect light (COMBINED);
 * - `DisplayColorsDirect`: direct light and emission (DIRECT);
 * - `DisplayColorsIndirect`: indirect light (INDIRECT);
 * and for two-sided solutions (the filter's TwoSided output) their `Back` twins, the
 * colours of the back faces.
 *
 * What differs from the mapper's picture: shadows are the filter's per-vertex shadows,
 * not the mapper's per-pixel shadow maps, so a shadow edge is as sharp as the mesh; the
 * glossy (specular) lobe, which depends on the eye, is left out; and the back faces of a
 * one-sided solution get the front's colours (the mapper lights them per pixel).
 *
 * Colours by cell (a cell colouring array) cannot be point colours: the output then has
 * each cell's points of its own (every cell keeps its cells' data, the points their
 * point data), so that every point carries its cell's colour.
 *
 * Input: vtkPolyData or a composite dataset of them (output of the same type); the
 * automatic exposure of lamp scenes is taken over all blocks together, as a composite
 * mapper does.
 *
 * @code{.py}
 * colors = linkgi.vtkGlobalIlluminationDisplayColors()
 * colors.SetInputConnection(gi.GetOutputPort())
 * colors.SetMapper(actor.GetMapper()); colors.SetProperty(actor.GetProperty())
 * colors.SetShading(actor.GetMapper().GetShading()); colors.SetLights(renderer.GetLights())
 * colors.Update()
 * @endcode
 *
 * @sa vtkGlobalIlluminationShading vtkGlobalIlluminationMapper
 */
#ifndef vtkGlobalIlluminationDisplayColors_h
#define vtkGlobalIlluminationDisplayColors_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkPassInputTypeAlgorithm.h"

class vtkGlobalIlluminationShading;
class vtkLightCollection;
class vtkMapper;
class vtkProperty;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationDisplayColors
  : public vtkPassInputTypeAlgorithm
{
public:
  static vtkGlobalIlluminationDisplayColors* New();
  vtkTypeMacro(vtkGlobalIlluminationDisplayColors, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The mapper's settings: arrays, exposure, tone curve, gamma, light intensity scale and
   * falloff. Null draws with a default vtkGlobalIlluminationShading. The default value is
   * null.
   */
  virtual void SetShading(vtkGlobalIlluminationShading* shading);
  vtkGetObjectMacro(Shading, vtkGlobalIlluminationShading);
  ///@}

  ///@{
  /**
   * The mapper whose colour map colours the surface (scalar visibility, colouring array,
   * lookup table, colour mode). Null, or a mapper that maps no scalars: the property's
   * solid colour. The default value is null.
   */
  virtual void SetMapper(vtkMapper* mapper);
  vtkGetObjectMacro(Mapper, vtkMapper);
  ///@}

  ///@{
  /**
   * The actor's property: the solid colour and the Diffuse coefficient. Null: white,
   * Diffuse 1. The default value is null.
   */
  virtual void SetProperty(vtkProperty* property);
  vtkGetObjectMacro(Property, vtkProperty);
  ///@}

  ///@{
  /**
   * The lights the scene is drawn with (a renderer's GetLights()): the AUTOMATIC tone
   * mapping picks the lamp look where one of them is a lamp. Null: the lights the input was
   * lit with, as vtkGlobalIlluminationFilter records them (the field value LinkGI.Lamps;
   * none without it). The default value is null.
   */
  virtual void SetLights(vtkLightCollection* lights);
  vtkGetObjectMacro(Lights, vtkLightCollection);
  ///@}

  /// The names of the output arrays: `mode` a vtkGlobalIlluminationShading::DisplayModes,
  /// `back` for the back faces' colours.
  static const char* GetColorsArrayName(int mode, bool back = false);

  /// The tone curve (never AUTOMATIC) and exposure of the last update.
  vtkGetMacro(ToneMapping, int);
  vtkGetMacro(Exposure, double);

protected:
  vtkGlobalIlluminationDisplayColors();
  ~vtkGlobalIlluminationDisplayColors() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  vtkMTimeType GetMTime() override;

  vtkGlobalIlluminationShading* Shading = nullptr;
  vtkMapper* Mapper = nullptr;
  vtkProperty* Property = nullptr;
  vtkLightCollection* Lights = nullptr;
  int ToneMapping = 3;
  double Exposure = 1.0;

private:
  vtkGlobalIlluminationDisplayColors(const vtkGlobalIlluminationDisplayColors&) = delete;
  void operator=(const vtkGlobalIlluminationDisplayColors&) = delete;
};

#endif
