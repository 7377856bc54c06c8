/**
 * @class   vtkGlobalIlluminationMapper
 * @brief   draws surfaces with shadow-mapped direct light from every light of the renderer
 *          plus the per-vertex indirect light of vtkGlobalIlluminationFilter
 *
 * The rendering half of LinkGI (Schmitz, Tavenrath & Kobbelt 2008, section 3.4): per pixel,
 * direct light from every switched-on vtkLight of the renderer (point, spot and
 * directional; diffuse, plus a normalized Blinn-Phong lobe when the actor's Specular is
 * above 0; HDR colours and intensities) with percentage-closer filtered shadow maps (a
 * cube map per point light, a 2D map per spot or directional light), plus the
 * `IndirectIrradiance` point array interpolated from the vertices, times albedo / pi.
 * Lights are converted like vtkGlobalIlluminationFilter converts them (1/r^2 falloff,
 * vtkLight attenuation ignored), so that the same lights given to the filter with
 * SetLightsFromRenderer give, in COMBINED mode, the filter's `Radiance` up to the shadow
 * filtering (per pixel here, per vertex with oversampling there).
 *
 * What is drawn (display mode, arrays, exposure and tone curve, shadow settings) is set on
 * the vtkGlobalIlluminationShading object, which several mappers may share.
 *
 * Shadows: the mapper's own triangles cast them (the geometry the filter lit). The maps
 * are rendered again only when a light moves or turns, the geometry or the actor's
 * transform changes, or the shadow settings change; ordinary frames and camera moves reuse
 * them. A renderer's headlight moves with the camera, so its map follows every camera move.
 *
 * Triangles and strips of lit actors (Lighting on, not PBR) get this shading; points,
 * lines and unlit actors are drawn as vtkOpenGLPolyDataMapper draws them. VTK's shader tags
 * are kept, so vtkSSAOPass and vtkToneMappingPass compose (see vtkGlobalIlluminationShading
 * for the tone mapping settings to use with the latter).
 *
 * @sa vtkGlobalIlluminationShading vtkGlobalIlluminationCompositeMapper
 */
#ifndef vtkGlobalIlluminationMapper_h
#define vtkGlobalIlluminationMapper_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <map>    // for std::map
#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkGlobalIlluminationMapperCore;
class vtkGlobalIlluminationShading;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationMapper
  : public vtkOpenGLPolyDataMapper
{
public:
  static vtkGlobalIlluminationMapper* New();
  vtkTypeMacro(vtkGlobalIlluminationMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The shading settings. Setting nullptr restores a new default object. The default value
   * is a new vtkGlobalIlluminationShading.
   */
  virtual void SetShading(vtkGlobalIlluminationShading* shading);
  vtkGetObjectMacro(Shading, vtkGlobalIlluminationShading);
  ///@}

  /**
   * How many times this mapper has rendered its shadow maps.
   */
  int GetShadowMapRenderCount();

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkGlobalIlluminationMapper();
  ~vtkGlobalIlluminationMapper() override;

  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderLight(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void SetLightingShaderParameters(
    vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;

  /// Whether the global illumination shader draws `cellBO`.
  bool Shades(const vtkOpenGLHelper* cellBO, vtkActor* act);

  vtkGlobalIlluminationShading* Shading = nullptr;

private:
  vtkGlobalIlluminationMapper(const vtkGlobalIlluminationMapper&) = delete;
  void operator=(const vtkGlobalIlluminationMapper&) = delete;

  std::unique_ptr<vtkGlobalIlluminationMapperCore> Core;
  std::map<const vtkOpenGLHelper*, std::string> ShaderKeys;
  std::string BufferKey;
  std::string GeometryKey; ///< of the last full build (vtkGlobalIlluminationMapperCore); empty: none
  std::string ShadingKey;  ///< of the shading arrays in the buffers
};

#endif
