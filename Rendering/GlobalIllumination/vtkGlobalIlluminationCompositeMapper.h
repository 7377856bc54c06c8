/**
 * @class   vtkGlobalIlluminationCompositeMapper
 * @brief   vtkGlobalIlluminationMapper for composite datasets (multiblock, partitioned)
 *
 * The composite counterpart of vtkGlobalIlluminationMapper, for ParaView representations
 * and any vtkCompositeDataSet of polydata: every block is drawn with shadow-mapped direct
 * light from the renderer's lights plus its per-vertex indirect light, with the per-block
 * colours, opacities and visibilities of vtkCompositePolyDataMapper2. The blocks drawn by
 * one helper (all blocks with the same kinds of cells and arrays, usually all of them)
 * shadow each other; blocks in different helpers do not.
 *
 * @sa vtkGlobalIlluminationMapper vtkGlobalIlluminationShading
 */
#ifndef vtkGlobalIlluminationCompositeMapper_h
#define vtkGlobalIlluminationCompositeMapper_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkCompositePolyDataMapper2.h"

class vtkGlobalIlluminationShading;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationCompositeMapper
  : public vtkCompositePolyDataMapper2
{
public:
  static vtkGlobalIlluminationCompositeMapper* New();
  vtkTypeMacro(vtkGlobalIlluminationCompositeMapper, vtkCompositePolyDataMapper2);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The shading settings, shared by all blocks. Setting nullptr restores a new default
   * object. The default value is a new vtkGlobalIlluminationShading.
   */
  virtual void SetShading(vtkGlobalIlluminationShading* shading);
  vtkGetObjectMacro(Shading, vtkGlobalIlluminationShading);
  ///@}

  /**
   * How many times the helpers of this mapper have rendered their shadow maps, in total.
   */
  int GetShadowMapRenderCount();

protected:
  vtkGlobalIlluminationCompositeMapper();
  ~vtkGlobalIlluminationCompositeMapper() override;

  vtkCompositeMapperHelper2* CreateHelper() override;
  void CopyMapperValuesToHelper(vtkCompositeMapperHelper2* helper) override;

  vtkGlobalIlluminationShading* Shading = nullptr;

private:
  vtkGlobalIlluminationCompositeMapper(const vtkGlobalIlluminationCompositeMapper&) = delete;
  void operator=(const vtkGlobalIlluminationCompositeMapper&) = delete;
};

#endif
