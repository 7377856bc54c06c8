/**
 * @class   vtkGlobalIlluminationCompositeMapperHelper
 * @brief   draws the blocks of vtkGlobalIlluminationCompositeMapper with global illumination
 *
 * vtkCompositePolyDataMapper2 draws all blocks of the same kind with one helper, in one
 * vertex buffer. This helper adds the shading attributes of every block to that buffer
 * (zeros for blocks without an array, with the actor's colour as their albedo) and shades
 * like vtkGlobalIlluminationMapper; its shadow maps hold the triangles of all its blocks.
 * Blocks with the same vtkPoints share their vertices in the buffer (VTK appends an array
 * once), so they also share the first such block's shading arrays.
 *
 * Not wrapped, not installed.
 */
#ifndef vtkGlobalIlluminationCompositeMapperHelper_h
#define vtkGlobalIlluminationCompositeMapperHelper_h

// VTK 9.1's vtkCompositeMapperHelper2.h uses these without including them.
#include "vtkColor.h" // for vtkColor3d
#include "vtk_glew.h" // for GLenum

#include "vtkCompositeMapperHelper2.h"

#include <map>    // for std::map
#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkGlobalIlluminationMapperCore;
class vtkGlobalIlluminationShading;

class vtkGlobalIlluminationCompositeMapperHelper : public vtkCompositeMapperHelper2
{
public:
  static vtkGlobalIlluminationCompositeMapperHelper* New();
  vtkTypeMacro(vtkGlobalIlluminationCompositeMapperHelper, vtkCompositeMapperHelper2);

  /// The parent's settings (the parent keeps the reference).
  void SetShading(vtkGlobalIlluminationShading* shading);

  int GetShadowMapRenderCount();
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkGlobalIlluminationCompositeMapperHelper();
  ~vtkGlobalIlluminationCompositeMapperHelper() override;

  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderLight(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void SetLightingShaderParameters(
    vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void AppendOneBufferObject(vtkRenderer* ren, vtkActor* act, vtkCompositeMapperHelperData* hdata,
    vtkIdType& flatIndex, std::vector<unsigned char>& colors, std::vector<float>& norms) override;

  bool Shades(const vtkOpenGLHelper* cellBO, vtkActor* act);

  /// What the superclass's buffers are built of (vtkGlobalIlluminationMapperCore::GeometryKey).
  std::string MakeGeometryKey(vtkActor* act);

private:
  vtkGlobalIlluminationCompositeMapperHelper(
    const vtkGlobalIlluminationCompositeMapperHelper&) = delete;
  void operator=(const vtkGlobalIlluminationCompositeMapperHelper&) = delete;

  std::unique_ptr<vtkGlobalIlluminationMapperCore> Core;
  std::map<const vtkOpenGLHelper*, std::string> ShaderKeys;
  std::string BufferKey;
  // When only the light arrays of the blocks changed, only the shading attributes are
  // uploaded again (vtkGlobalIlluminationMapperCore::GeometryKey).
  std::string GeometryKey; ///< of the last full build; empty: none
  std::string ShadingKey;  ///< of the shading arrays in the buffers
  std::vector<vtkPolyData*> ShadedBlocks; ///< blocks whose attributes are in the buffers, in order
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationCompositeMapperHelper.h
