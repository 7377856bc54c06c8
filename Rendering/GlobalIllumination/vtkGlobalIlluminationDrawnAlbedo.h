/**
 * @class   vtkGlobalIlluminationDrawnAlbedo
 * @brief   gives vtkGlobalIlluminationFilter the albedo a surface is drawn with
 *
 * Light bounces off a surface in the colour it is drawn with. Apply() configures a
 * vtkGlobalIlluminationFilter so that its albedo is what `mapper` and `property` draw, in
 * the order vtkGlobalIlluminationMapper reads it:
 * - the point array AlbedoArrayName ("Albedo", as vtkGlobalIlluminationShading's default);
 * - else, with scalar visibility on, the mapper's colouring array through its lookup table
 *   (colour mode, array component and point or cell scalars as the mapper uses them),
 *   added to a shallow copy of the data as the float array "GlobalIlluminationAlbedo"
 *   (linear);
 * - else the property's solid colour;
 * the last two times the property's Diffuse. Blocks of a composite dataset without the
 * array take the solid colour. The lookup table's colours and the solid colour are display
 * (sRGB) values: they reach the filter decoded to linear reflectance
 * (vtkGlobalIlluminationColors::ToLinear), as the filter itself reads an unsigned char
 * Albedo array; a float Albedo array is linear already.
 *
 * The copy with mapped colours is kept and remade only when the data, the lookup table or
 * the colouring parameters change, so calling Apply() before every update of a render loop
 * costs nothing while they stay the same. The ParaView representation uses this class; a
 * VTK or Python program that draws with vtkGlobalIlluminationMapper does the same:
 *
 * @code{.cpp}
 * gi->SetInputDataObject(drawnAlbedo->Apply(surface, mapper, actor->GetProperty(), gi));
 * @endcode
 */
#ifndef vtkGlobalIlluminationDrawnAlbedo_h
#define vtkGlobalIlluminationDrawnAlbedo_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr

class vtkDataObject;
class vtkGlobalIlluminationFilter;
class vtkMapper;
class vtkProperty;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationDrawnAlbedo : public vtkObject
{
public:
  static vtkGlobalIlluminationDrawnAlbedo* New();
  vtkTypeMacro(vtkGlobalIlluminationDrawnAlbedo, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Sets `filter`'s Albedo, AlbedoArrayName and AlbedoArrayAssociation for `data` as drawn
   * by `mapper` with `property`, and returns the data the filter should take as input:
   * `data` itself, or the kept copy with the mapped colours (owned by this object, valid
   * until the next call). Returns nullptr when `data` is null.
   */
  vtkDataObject* Apply(vtkDataObject* data, vtkMapper* mapper, vtkProperty* property,
    vtkGlobalIlluminationFilter* filter);

  ///@{
  /**
   * The point array that overrides the drawn colour, as vtkGlobalIlluminationShading's
   * AlbedoArrayName (set both alike). The default value is "Albedo".
   */
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  ///@}

  /// Name of the array of mapped colours in the returned copy.
  static const char* GetMappedAlbedoName() { return "GlobalIlluminationAlbedo"; }

protected:
  vtkGlobalIlluminationDrawnAlbedo();
  ~vtkGlobalIlluminationDrawnAlbedo() override;

private:
  vtkGlobalIlluminationDrawnAlbedo(const vtkGlobalIlluminationDrawnAlbedo&) = delete;
  void operator=(const vtkGlobalIlluminationDrawnAlbedo&) = delete;

  char* AlbedoArrayName = nullptr;
  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
