/**
 * @class   vtkGlobalIlluminationFilter
 * @brief   per-vertex multi-bounce diffuse global illumination of a surface
 *
 * vtkGlobalIlluminationFilter lights the polygons and triangle strips of a surface with
 * vtkLight objects, an environment (sky) and emissive surfaces, following Schmitz,
 * Tavenrath & Kobbelt, "Interactive Global Illumination for Deformable Geometry in CUDA"
 * (2008): every vertex traces RaysPerVertex cosine-distributed rays once, and the hits
 * become links along which NumberOfBounces bounces of light are iterated.
 *
 * The output is the input geometry (a shallow copy: points, cells, point, cell and field
 * data are kept; vertices and lines are passed through unlit, their points get 0) with three
 * float point arrays of linear RGB (for composite and other input, see Input below):
 * - `DirectIrradiance`: irradiance E_d from the lights, with shadows;
 * - `IndirectIrradiance`: irradiance E_ind from bounced light, emissive surfaces and the
 *   environment;
 * - `Radiance`: outgoing radiance L = Le + albedo / pi * (E_d + E_ind).
 * With TwoSided on, `DirectIrradianceBack`, `IndirectIrradianceBack` and `RadianceBack`
 * hold the values of the back sides. Field data `LinkGI.*` holds the engine's counters
 * (lifetime numbers of BVH builds and refits, link builds, light link builds and bounce
 * runs; sizes of the link structure), the stage times of the last update in milliseconds
 * (`LinkGI.MsFilter` is the whole RequestData), `LinkGI.Warnings`, and `LinkGI.Lamps` (1
 * where a light is a lamp, which picks the lamp look of vtkGlobalIlluminationShading where
 * the result is displayed without its lights).
 *
 * Input: a vtkPolyData; any other vtkDataSet, lit as its surface (vtkDataSetSurfaceFilter),
 * which is then the output; or a composite dataset (vtkMultiBlockDataSet,
 * vtkPartitionedDataSetCollection, vtkPartitionedDataSet, nested as deep as you like) whose
 * blocks are solved together as one scene, so that light bounces and shadows cross blocks.
 * A composite output has the input's type and structure: each polydata block is a shallow
 * copy with its own result arrays, other dataset blocks become their lit surfaces, empty
 * nodes stay empty, and the `LinkGI.*` field data is on the composite (GetOutput() is for
 * vtkPolyData output; use GetOutputDataObject(0)). Blocks without the albedo array get
 * Albedo, blocks without the emission array emit nothing; an array that no block has is an
 * error, as it is for a vtkPolyData.
 *
 * Units: linear RGB with no hidden factors. A point or spot vtkLight with Intensity 1 and a
 * white DiffuseColor has a radiant intensity of 1 W/sr per channel (times
 * LightIntensityScale), so a surface at distance r facing it receives
 * 1 / (c + l r + q r^2), (c, l, q) the light's AttenuationValues: 1 with VTK's default,
 * 1/r^2 for a lamp's (0, 0, 1); a directional light of intensity 1 gives irradiance 1 on a
 * surface facing it. Lights are read by
 * vtkGlobalIlluminationLights, as vtkGlobalIlluminationMapper reads them: switched-off
 * lights are ignored; positional lights with a cone angle below 90 degrees are spot lights
 * (with the light's exponent), other positional lights point lights; headlights and camera
 * lights are used at their transformed positions, as last placed by a renderer; a spot or
 * directional light whose focal point equals its position is skipped with a warning.
 *
 * Surfaces: triangles are lit on the side their normal points to. Normals come from the
 * input's point normals, or are computed with vtkPolyDataNormals (feature angle
 * FeatureAngle, splitting on, consistent ordering) when the input has none or
 * ComputeNormals is on, and, with a warning, when the input's normals are averaged across
 * sharp edges (points whose normal lies more than 30 degrees from every one of their
 * triangles hold a tenth of the surface's area or more, as in CAD exports). A point split
 * at a sharp edge is solved once per side; its output value is the mean of its copies (by
 * count). With TwoSided off, a ray that hits the back
 * of a triangle is blocked and sees black. Real data (the user guide's section of that
 * name): a closed surface wound inward is lit from outside unless a light is inside it, and
 * coordinates are taken relative to the surface's centre, in double precision.
 *
 * Updates are incremental: the filter keeps its solver between executions, so moving or
 * recolouring a light recomputes only direct light and bounces, and changing albedo,
 * emission or environment only the bounces. Moving a light re-executes the filter because
 * GetMTime includes the lights' (and the environment texture's) modification times.
 *
 * Errors: invalid input (no polygons, NaN or infinite coordinates, missing arrays, negative
 * albedo, ...) is reported with vtkErrorMacro and the previous output is handed out again.
 * Degenerate triangles are dropped and albedo above 1 is clamped (unless ClampAlbedo is
 * off), with a warning. An empty input gives an empty output and a warning; a point cloud
 * (points without polygons) is an error that says how to make a surface of it. With no lights,
 * the result comes from the environment and emission only (all zero, with a warning, if
 * both are black). Setting AbortExecute (from a progress observer) stops the update and
 * keeps the previous output; VTK before 9.3 does not re-execute an aborted filter by
 * itself, so change a property or call Modified() to try again.
 */

#ifndef vtkGlobalIlluminationFilter_h
#define vtkGlobalIlluminationFilter_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkImageData;
class vtkLight;
class vtkMultiProcessController;
class vtkRenderer;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGlobalIlluminationFilter* New();
  vtkTypeMacro(vtkGlobalIlluminationFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Whether `name` is one of the point arrays the filter computes (`DirectIrradiance`,
   * `IndirectIrradiance`, `Radiance`, `CausticIrradiance` and their `Back` twins): arrays
   * that change at every update while the geometry stays (a mapper re-uploads only them).
   */
  static bool IsResultArray(const char* name);

  /// Where the engine runs.
  enum BackendType
  {
    AUTO = 0, ///< CUDA when the build has it and a CUDA device exists, else the CPU
    CPU = 1,  ///< Embree on all cores
    CUDA = 2  ///< the GPU(s); without a device (or out of GPU memory) the CPU, with a warning
  };

  /// How the indirect light is computed: the values of linkgi::Method, the engine's
  /// registered methods (SetMethod refuses a value none of them has).
  enum MethodType
  {
    LINKS = 0,             ///< the link structure (Schmitz, Tavenrath & Kobbelt 2008)
    INSTANT_RADIOSITY = 1, ///< virtual point lights (Marques & Santos 2010)
    IMPLICIT_VISIBILITY = 2, ///< hierarchical links, visibility implied (Dong et al. 2007)
    PHOTON_MAPPING = 3,      ///< photons, clustered final gather (Wang et al. 2009)
    REFERENCE = 4            ///< per-vertex path tracing: ground truth, slow on purpose
  };

  ///@{
  /**
   * Method: LINKS traces rays between vertices once and bounces light over those links
   * (a light move costs milliseconds, a deformation relinks); INSTANT_RADIOSITY shoots light
   * paths from the lights, emissive surfaces and environment, leaves a virtual point light
   * at each diffuse hit and gathers them at every vertex with shadow rays (nothing is
   * precomputed: a deformation costs what a light move costs). Both give the same output
   * arrays; the stages that ran are in the field data (LinkGI.Method, LinkGI.Ms<Stage>).
   * IMPLICIT_VISIBILITY links clusters of vertices whose direction bins keep only their
   * shortest link (visibility implied, no rays for the bounced light), rebuilt on every
   * deformation; one-sided elements only (TwoSided is an error with it).
   * PHOTON_MAPPING traces photons from the lights, emissive surfaces and environment,
   * clusters the vertices and final-gathers only at one sample vertex per cluster, against
   * radiance estimates of the photons, then interpolates to every vertex (a light move keeps
   * the clusters).
   * RaysPerVertex applies to LINKS, the VPL properties below to INSTANT_RADIOSITY,
   * ImplicitVisibilityBins to IMPLICIT_VISIBILITY, the photon properties to PHOTON_MAPPING.
   * The default value is LINKS. A value no registered method has is an error and changes
   * nothing. GetMethodAsString() gives the method's name as the output's LinkGI.Method
   * says it ("links", "instant-radiosity", ...).
   */
  virtual void SetMethod(int method);
  vtkGetMacro(Method, int);
  void SetMethodToLinks() { this->SetMethod(LINKS); }
  void SetMethodToInstantRadiosity() { this->SetMethod(INSTANT_RADIOSITY); }
  void SetMethodToImplicitVisibility() { this->SetMethod(IMPLICIT_VISIBILITY); }
  void SetMethodToPhotonMapping() { this->SetMethod(PHOTON_MAPPING); }
  void SetMethodToReference() { this->SetMethod(REFERENCE); }
  const char* GetMethodAsString();
  ///@}

  ///@{
  /**
   * INSTANT_RADIOSITY: about how many virtual point lights each update makes
   * (NumberOfVPLs / NumberOfBounces light paths). The default value is 1024.
   */
  vtkSetClampMacro(NumberOfVPLs, int, 1, 1048576);
  vtkGetMacro(NumberOfVPLs, int);
  ///@}

  ///@{
  /**
   * INSTANT_RADIOSITY: the minimum distance of the paper's smoothstep bound on the geometry
   * term, as a fraction of the bounding-box diagonal: VPLs nearer than 0.8 times it give a
   * vertex nothing, so they cannot spike; VPLCompensationRays take the light of those short
   * paths back. The default value is 0.02.
   */
  vtkSetClampMacro(VPLClampDistance, double, 0.0, 1.0);
  vtkGetMacro(VPLClampDistance, double);
  ///@}

  ///@{
  /**
   * INSTANT_RADIOSITY: the clamp's bias compensation. Each vertex traces this many short
   * cosine-weighted rays (a perfect square, at most 1024) and takes back the light the
   * clamp removed from the surfaces nearer than it, with the solution's own radiance there.
   * 0 turns it off. The default value is 64.
   */
  vtkSetClampMacro(VPLCompensationRays, int, 0, 1024);
  vtkGetMacro(VPLCompensationRays, int);
  ///@}

  ///@{
  /**
   * INSTANT_RADIOSITY: interleaved sampling. The VPLs are split into this many subsets and
   * each vertex gathers one (scaled up), and the one-ring smoothing, on whenever this is
   * above 1, recombines neighbours. 1 turns it off.
   * The default value is 1.
   */
  vtkSetClampMacro(VPLInterleaving, int, 1, 64);
  vtkGetMacro(VPLInterleaving, int);
  ///@}

  ///@{
  /**
   * INSTANT_RADIOSITY: imperfect visibility. VPL shadow rays test a coarse proxy of the mesh
   * (vertices clustered on a grid of ProxyResolution cells along the longest axis) instead
   * of the mesh. The default value is off, with a resolution of 32.
   */
  vtkSetMacro(ProxyVisibility, vtkTypeBool);
  vtkGetMacro(ProxyVisibility, vtkTypeBool);
  vtkBooleanMacro(ProxyVisibility, vtkTypeBool);
  vtkSetClampMacro(ProxyResolution, int, 2, 4096);
  vtkGetMacro(ProxyResolution, int);
  ///@}

  ///@{
  /**
   * IMPLICIT_VISIBILITY: N, the bins per side of each face of every element's cube map of
   * directions (6 N^2 bins; the paper uses 8, 12, 16). More bins: finer shadows of the
   * bounced light and less light through silhouettes, at about N^2 the cost. The GPU
   * holds up to 16; a larger N runs on the CPU, with a warning.
   * The default value is 12.
   */
  vtkSetClampMacro(ImplicitVisibilityBins, int, 2, 32);
  vtkGetMacro(ImplicitVisibilityBins, int);
  ///@}

  ///@{
  /**
   * Mirrors and glass: the 1-component cell (or else point) array that gives each triangle
   * its material, 0 diffuse, 1 mirror, 2 glass (a point array: the value most of the
   * triangle's points have), and the array of glass's index of refraction (cell or point,
   * the mean of the points'; none: 1.5). PHOTON_MAPPING carries light through mirrors and
   * glass and adds the caustics they focus (output array CausticIrradiance, part of
   * IndirectIrradiance); the other methods light them as diffuse surfaces, with a warning.
   * Any other material value, or an index of refraction not above 0, is an error naming it.
   * The default values are none (every surface diffuse).
   */
  vtkSetStringMacro(MaterialArrayName);
  vtkGetStringMacro(MaterialArrayName);
  vtkSetStringMacro(IndexOfRefractionArrayName);
  vtkGetStringMacro(IndexOfRefractionArrayName);
  ///@}

  ///@{
  /**
   * REFERENCE: cosine-weighted paths traced from every vertex (the first floor(sqrt(M))^2
   * stratified); the noise falls as 1/sqrt(M). From 1 to 1048576. The default value is 1024.
   */
  vtkSetClampMacro(ReferencePathsPerVertex, int, 1, 1048576);
  vtkGetMacro(ReferencePathsPerVertex, int);
  ///@}

  ///@{
  /**
   * PHOTON_MAPPING: about how many photons each light update stores (one per diffuse hit of
   * a light path), from 1 to 16777216. The default value is 262144.
   */
  vtkSetClampMacro(NumberOfPhotons, int, 1, 16777216);
  vtkGetMacro(NumberOfPhotons, int);
  ///@}

  ///@{
  /**
   * PHOTON_MAPPING: clusters of vertices; only one sample vertex per cluster final-gathers,
   * the others interpolate. At most the vertex count is used. The default value is 12288.
   */
  vtkSetClampMacro(NumberOfClusters, int, 1, 1048576);
  vtkGetMacro(NumberOfClusters, int);
  ///@}

  ///@{
  /**
   * PHOTON_MAPPING: final-gather rays per sample vertex, a perfect square (64, 144, 256,
   * 1024; any other value is an error naming it). The default value is 144.
   */
  vtkSetClampMacro(FinalGatherRays, int, 1, 65536);
  vtkGetMacro(FinalGatherRays, int);
  ///@}

  ///@{
  /**
   * Host memory an update may use, in MiB. A synchronous update estimated to need more (the
   * links of a large mesh at many rays) is lit through a proxy of half the vertices that
   * would fit (see ProxyVertices), with a warning; where that would be under 1000 vertices,
   * or asynchronously, it fails with an error that says what would fit, before anything is
   * allocated, and the previous output stays: the operating system never kills the process.
   * 0 (automatic): what the machine has available, less a margin. The default value is 0.
   */
  vtkSetClampMacro(MemoryBudget, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  ///@{
  /**
   * Lighting through a proxy: when above 0, the indirect light is solved on a copy of the
   * surface decimated to about this many vertices (OpenMesh) and carried to every input
   * point; the direct light is still computed at every input point. The proxy is kept while
   * the geometry stays, so a light move does not decimate again. It must be smaller than the
   * input; negative values are an error. Synchronous updates only. The default value is 0
   * (off).
   */
  vtkSetMacro(ProxyVertices, vtkIdType);
  vtkGetMacro(ProxyVertices, vtkIdType);
  ///@}

  ///@{
  /**
   * Adaptive refinement: the lighting's resolution follows the light instead of the input's
   * tessellation. After a solve, every edge across which the direct or indirect irradiance
   * changes by more than RefinementTolerance (relative to the local light level), or whose
   * midpoint's direct light departs from its ends' by that much (a shadow boundary), is
   * split at its midpoint, and the refined surface is solved again, for up to
   * RefinementRounds rounds and at most RefinementMaxVertices points (0: four times the
   * input's). The output is then the refined surface: the input's point arrays interpolated
   * onto the new points, its cell arrays inherited by the pieces of each cell, the light
   * arrays, and the point normals the light was solved with (the input's, or those computed
   * for it, at its points; their edge ends' normalized mean at the new points), so that the
   * refined surface is shaded as it was lit. Its triangles lie inside the input's, so edges,
   * boundaries and creases stay.
   * Synchronous updates of a vtkPolyData input only; not with ProxyVertices. Defaults: off,
   * 0.1, 0 and 3.
   */
  vtkSetMacro(Refinement, vtkTypeBool);
  vtkGetMacro(Refinement, vtkTypeBool);
  vtkBooleanMacro(Refinement, vtkTypeBool);
  vtkSetMacro(RefinementTolerance, double);
  vtkGetMacro(RefinementTolerance, double);
  vtkSetMacro(RefinementMaxVertices, vtkIdType);
  vtkGetMacro(RefinementMaxVertices, vtkIdType);
  vtkSetMacro(RefinementRounds, int);
  vtkGetMacro(RefinementRounds, int);
  ///@}

  ///@{
  /**
   * Number of rays traced from each vertex (n_C), a perfect square k*k because the
   * directions form a k x k stratified grid. Other values are rounded to the nearest perfect
   * square (with a warning). Changing it rebuilds the links. The default value is 256.
   */
  virtual void SetRaysPerVertex(int rays);
  vtkGetMacro(RaysPerVertex, int);
  ///@}

  ///@{
  /**
   * Number of bounces of indirect light (n_B). 0 gives only emission and environment light
   * in IndirectIrradiance. The default value is 3.
   */
  vtkSetClampMacro(NumberOfBounces, int, 0, 1000);
  vtkGetMacro(NumberOfBounces, int);
  ///@}

  ///@{
  /**
   * Feature angle in degrees: edges sharper than this split the vertex normals (when normals
   * are computed), and smoothing does not average across them. The default value is 30.
   */
  vtkSetClampMacro(FeatureAngle, double, 0.0, 180.0);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /**
   * Smooth the indirect irradiance over each vertex's one-ring, within the feature angle:
   * less noise, more blur (a bias that grows with the triangles' size). Instant radiosity's
   * interleaving (VPLInterleaving > 1) and the coarse solutions of a progressive update
   * smooth whatever this says. The default value is off.
   */
  vtkSetMacro(Smoothing, vtkTypeBool);
  vtkGetMacro(Smoothing, vtkTypeBool);
  vtkBooleanMacro(Smoothing, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Always compute point normals (splitting at FeatureAngle), even when the input has
   * point normals. When off, the input's normals are used if present, unless they are
   * averaged across sharp edges (see the class description). The default value is off.
   */
  vtkSetMacro(ComputeNormals, vtkTypeBool);
  vtkGetMacro(ComputeNormals, vtkTypeBool);
  vtkBooleanMacro(ComputeNormals, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Backend: AUTO, CPU or CUDA. AUTO runs on the GPU when this build has the CUDA backend
   * and the machine a CUDA device, else on the CPU; CUDA falls back to the CPU with a
   * warning when it cannot run (no device, GPU out of memory). The backend that ran, the
   * device and the reason are in the output's field data (LinkGI.Backend, LinkGI.Device,
   * LinkGI.BackendNote). The default value is AUTO.
   */
  vtkSetClampMacro(Backend, int, AUTO, CUDA);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(AUTO); }
  void SetBackendToCPU() { this->SetBackend(CPU); }
  void SetBackendToCUDA() { this->SetBackend(CUDA); }
  const char* GetBackendAsString();
  ///@}

  ///@{
  /**
   * Name of the array holding the diffuse albedo (reflectance in [0,1], linear RGB). An
   * array with 1 component is grey, with 3 RGB, with 4 RGBA (alpha unused); any other
   * component count, or a non-numeric array, is an error naming the array (as for
   * EmissionArrayName). Unsigned char arrays hold display colours: divided by 255 and
   * decoded from sRGB to linear (vtkGlobalIlluminationColors::Read); other types are
   * linear. When empty, Albedo is used.
   * The default value is empty.
   */
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  ///@}

  ///@{
  /**
   * Whether AlbedoArrayName names a point array (vtkDataObject::FIELD_ASSOCIATION_POINTS)
   * or a cell array (FIELD_ASSOCIATION_CELLS; each vertex gets the mean of its cells, per
   * side of a sharp edge). The default value is FIELD_ASSOCIATION_POINTS.
   */
  vtkSetClampMacro(AlbedoArrayAssociation, int, 0, 1);
  vtkGetMacro(AlbedoArrayAssociation, int);
  ///@}

  ///@{
  /**
   * Constant albedo (linear RGB) used when AlbedoArrayName is empty. The default value is
   * (0.7, 0.7, 0.7).
   */
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /**
   * Albedo above 1 would create energy. On: clamp it to 1 with a warning. Off: report an
   * error. The default value is on.
   */
  vtkSetMacro(ClampAlbedo, vtkTypeBool);
  vtkGetMacro(ClampAlbedo, vtkTypeBool);
  vtkBooleanMacro(ClampAlbedo, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Name of an array of emitted radiance Le (linear RGB, >= 0; area lights), read like the
   * albedo array. When empty, nothing emits. The default value is empty.
   */
  vtkSetStringMacro(EmissionArrayName);
  vtkGetStringMacro(EmissionArrayName);
  ///@}

  ///@{
  /**
   * Point or cell association of EmissionArrayName, as for the albedo. The default value is
   * FIELD_ASSOCIATION_POINTS.
   */
  vtkSetClampMacro(EmissionArrayAssociation, int, 0, 1);
  vtkGetMacro(EmissionArrayAssociation, int);
  ///@}

  ///@{
  /**
   * Radiance of the sky seen by rays that hit nothing (linear RGB). A uniform sky of
   * radiance L gives an unoccluded surface irradiance pi * L. The default value is
   * (0, 0, 0).
   */
  vtkSetVector3Macro(EnvironmentColor, double);
  vtkGetVector3Macro(EnvironmentColor, double);
  ///@}

  ///@{
  /**
   * Optional lat-long (equirectangular) map of the sky with +Y up, multiplied by
   * EnvironmentColor (set the colour to 1,1,1 to use the map as is). Its point scalars are
   * read like colour arrays; the image's last row (the top of a picture read by a VTK
   * reader) looks up. The default value is nullptr.
   */
  virtual void SetEnvironmentTexture(vtkImageData* texture);
  vtkGetObjectMacro(EnvironmentTexture, vtkImageData);
  ///@}

  ///@{
  /**
   * Give every vertex a back side (normal -n) with its own solution, for open surfaces.
   * Adds the `...Back` arrays. The default value is off.
   */
  vtkSetMacro(TwoSided, vtkTypeBool);
  vtkGetMacro(TwoSided, vtkTypeBool);
  vtkBooleanMacro(TwoSided, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Seed of the per-vertex random rotation of the ray directions; results are deterministic
   * for a given seed. The default value is 0.
   */
  vtkSetClampMacro(Seed, int, 0, VTK_INT_MAX);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Also trace shadow rays at the edge midpoints around each vertex, so that hard shadow
   * edges do not alias onto vertices. The default value is on.
   */
  vtkSetMacro(LightOversampling, vtkTypeBool);
  vtkGetMacro(LightOversampling, vtkTypeBool);
  vtkBooleanMacro(LightOversampling, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Rotate the shared ray directions by a random angle about each vertex normal, which turns
   * structured aliasing into noise. The default value is on.
   */
  vtkSetMacro(Twist, vtkTypeBool);
  vtkGetMacro(Twist, vtkTypeBool);
  vtkBooleanMacro(Twist, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Factor applied to every light's DiffuseColor * Intensity, e.g. to express the lights in
   * other units than the scene's lengths. The default value is 1.
   */
  vtkSetClampMacro(LightIntensityScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LightIntensityScale, double);
  ///@}

  ///@{
  /**
   * The lights. The filter keeps references to the vtkLight objects themselves, so changing
   * a light re-executes the filter. SetLightsFromRenderer replaces the lights with those of
   * `renderer` (the same objects, so what the renderer shows and what the filter bounces
   * agree); note that a renderer creates its automatic headlight only on its first render.
   */
  void AddLight(vtkLight* light);
  void RemoveLight(vtkLight* light);
  void RemoveAllLights();
  void SetLightsFromRenderer(vtkRenderer* renderer);
  int GetNumberOfLights();
  vtkLight* GetLight(int index);
  ///@}

  ///@{
  /**
   * Asynchronous updates, for interactive use: RequestData hands the scene to a background
   * worker and returns at once with the newest finished result, which may belong to an
   * earlier request (the field data's LinkGI.ShownRequest says which; LinkGI.Pending = 1
   * while the worker is busy), or with zero arrays before the first result for this mesh.
   * A newer request supersedes a running one instead of queueing. The render loop calls
   * PollAsynchronousResult(), or lets a vtkGlobalIlluminationAsyncWatcher (module
   * LinkGI::RenderingGlobalIllumination) do it on an interactor's timer, so the filter
   * re-executes when a newer result is ready. Solver errors surface as warnings in
   * LinkGI.Warnings. The default value is off.
   */
  vtkSetMacro(Asynchronous, vtkTypeBool);
  vtkGetMacro(Asynchronous, vtkTypeBool);
  vtkBooleanMacro(Asynchronous, vtkTypeBool);
  ///@}

  ///@{
  /**
   * The processes among which the surface is partitioned (MPI: pvbatch --mpi, pvserver).
   * With more than one, RequestData is collective: every process gathers every partition's
   * surface (without ghost cells), lights the whole, so that shadows and bounced light cross
   * the partition boundaries, and outputs the light of its own points; ghost points
   * (vtkGhostType's DUPLICATEPOINT) get the values of their owner's copy. The surfaces are
   * exchanged again only when one of them changed: a light move re-runs only the light
   * links and the bounces. LinkGI.Processes and LinkGI.PartitionBytesReceived in the field
   * data say what happened. A failure on one process fails the update on all. Asynchronous
   * updates solve the whole surface on every process (Documentation/Distributed.md).
   * Refinement is not available with more than one process. nullptr or one
   * process: this process's input alone. The default value is the global controller
   * (vtkMultiProcessController::GetGlobalController() when the filter is made).
   */
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * Temporal stability in asynchronous mode: each new indirect irradiance is blended as
   * TemporalBlend * new + (1 - TemporalBlend) * previous, damping flicker of the sampled
   * indirect light under a moving light or mesh (direct light is exact and never blended).
   * 1 shows each result as it is. The default value is 1.
   */
  vtkSetClampMacro(TemporalBlend, double, 0.001, 1.0);
  vtkGetMacro(TemporalBlend, double);
  ///@}

  ///@{
  /**
   * Progressive solutions in asynchronous mode: where the final solution is predicted to take
   * long (the first update of a mesh, a new time step, a new contour), the worker first
   * publishes a coarse solution of the same light (fewer rays, VPLs, photons or bins),
   * aimed at ProgressiveFirstStageSeconds of work on this machine, and then the final one,
   * exactly what a non-progressive update gives. LinkGI.ShownStage and LinkGI.Stages in the
   * field data say which stage the output shows. Updates that are quick anyway (a light
   * move with the link method) and continuous changes publish their final solution alone.
   * Synchronous updates always give the final solution. The defaults are off and 0.5 s.
   */
  vtkSetMacro(Progressive, vtkTypeBool);
  vtkGetMacro(Progressive, vtkTypeBool);
  vtkBooleanMacro(Progressive, vtkTypeBool);
  vtkSetClampMacro(ProgressiveFirstStageSeconds, double, 0.01, 60.0);
  vtkGetMacro(ProgressiveFirstStageSeconds, double);
  ///@}

  /**
   * In asynchronous mode: if a result newer than the one in the output is ready, marks the
   * filter modified (so the next render re-executes it) and returns true. Collective under
   * MPI, like RequestData: all processes are marked when any has a newer result.
   */
  bool PollAsynchronousResult();

  /**
   * In asynchronous mode: blocks until the worker has published the final result of the
   * newest request, or went idle without it (the update failed), for at most `timeoutSeconds`;
   * then returns what PollAsynchronousResult returns. For scripts that want the finished
   * picture. Returns false at once when nothing was requested. Collective under MPI, as
   * PollAsynchronousResult.
   */
  bool WaitForAsynchronousResult(double timeoutSeconds = 1e9);

  ///@{
  /**
   * In asynchronous mode: the id of the newest request (0 before the first), whether the
   * worker is busy (a request waiting or being solved), the id of the request being solved
   * (0 while the worker is idle), the fraction of its running stage done, and which stage
   * of how many that is (1 of 1 without progressive stages; 0 of 0 while idle). The
   * output's LinkGI.ShownRequest says which request it shows.
   */
  vtkTypeUInt64 GetAsynchronousRequest();
  bool GetAsynchronousBusy();
  vtkTypeUInt64 GetAsynchronousSolving();
  double GetAsynchronousProgress();
  int GetAsynchronousStage();
  int GetAsynchronousStages();
  /// The error of the newest asynchronous update that failed (empty if none).
  std::string GetAsynchronousError();
  ///@}

  /**
   * Includes the modification times of the lights and the environment texture.
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkGlobalIlluminationFilter();
  ~vtkGlobalIlluminationFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /// A vtkPolyData for a vtkDataSet input, a dataset of the input's type for a composite one.
  virtual int RequestDataObject(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int RaysPerVertex;
  int NumberOfBounces;
  int Method;
  int NumberOfVPLs;
  double VPLClampDistance;
  int VPLInterleaving;
  int VPLCompensationRays;
  vtkTypeBool ProxyVisibility;
  int ProxyResolution;
  int ImplicitVisibilityBins;
  char* MaterialArrayName;
  char* IndexOfRefractionArrayName;
  int NumberOfPhotons;
  int ReferencePathsPerVertex = 1024;
  int NumberOfClusters;
  int FinalGatherRays;
  double MemoryBudget;
  vtkIdType ProxyVertices;
  vtkTypeBool Refinement;
  double RefinementTolerance;
  vtkIdType RefinementMaxVertices;
  int RefinementRounds;
  double FeatureAngle;
  vtkTypeBool Smoothing;
  vtkTypeBool ComputeNormals;
  int Backend;
  char* AlbedoArrayName;
  int AlbedoArrayAssociation;
  double Albedo[3];
  vtkTypeBool ClampAlbedo;
  char* EmissionArrayName;
  int EmissionArrayAssociation;
  double EnvironmentColor[3];
  vtkImageData* EnvironmentTexture;
  vtkTypeBool TwoSided;
  int Seed;
  vtkTypeBool LightOversampling;
  vtkTypeBool Twist;
  double LightIntensityScale;
  vtkTypeBool Asynchronous;
  double TemporalBlend;
  vtkTypeBool Progressive;
  double ProgressiveFirstStageSeconds;
  vtkMultiProcessController* Controller;

private:
  vtkGlobalIlluminationFilter(const vtkGlobalIlluminationFilter&) = delete;
  void operator=(const vtkGlobalIlluminationFilter&) = delete;

  /// Hands out the last good output again after an error or an abort.
  void RestorePreviousOutput(vtkDataObject* output);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
