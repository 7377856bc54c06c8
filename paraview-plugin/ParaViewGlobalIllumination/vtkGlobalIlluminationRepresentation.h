/**
 * @class   vtkGlobalIlluminationRepresentation
 * @brief   ParaView's "Global Illumination" surface representation
 *
 * A surface representation that lights its data with vtkGlobalIlluminationFilter, using
 * the view's own lights, and draws it with vtkGlobalIlluminationCompositeMapper: direct
 * light with shadow maps plus the per-vertex indirect light.
 *
 * The filter runs where the data is rendered, just before each render (the view's render
 * request), on the delivered composite dataset, whose blocks it solves as one scene so
 * that light bounces between them. Its lights are the
 * view's lights in world coordinates, gathered at that moment:
 * - every light of the Light Inspector (vtkPVLight), scene or camera relative;
 * - the light kit's key light (UseKeyLight), a directional light that follows the camera.
 *   The kit's fill, back and head lights are not bounced: they stand in for the indirect
 *   light that the filter computes. (The mapper draws the direct light of all lights.)
 * When a light moves or changes, or the camera moves a camera light, the next render
 * recomputes only the direct light and the bounces; the links are rebuilt only when the
 * data or the ray settings change.
 *
 * The filter solves asynchronously (vtkGlobalIlluminationFilter's Asynchronous mode): a
 * render hands the scene to a background worker and draws at once with the newest finished
 * solution. Before the first one the view shows the direct light with shadows and no
 * indirect light; after a change it keeps the last indirect light until the new one
 * arrives. A change while the worker is busy replaces the request waiting, never queues
 * behind it. WaitForSolution says whether a render waits for the pending solution instead:
 * by default (WAIT_AUTOMATIC) scripts (pvbatch, pvpython) wait, so Render() and
 * SaveScreenshot() give the finished picture, and the GUI never does. Where the view has an
 * interactor and renders do not wait (the GUI), a vtkGlobalIlluminationAsyncWatcher on that
 * interactor polls for the new solution and renders through it, which ParaView turns into a
 * render of the view proxy (on the server too, in client-server mode); its polls also show
 * the worker's progress in ParaView's progress bar. Renders report the worker's progress
 * through this representation as well.
 *
 * The albedo is the colour the surface is drawn with: an `Albedo` point array if the data
 * has one, else the colours mapped from the coloring array, else the solid colour, times
 * the Diffuse coefficient. Points and lines are drawn unlit by the filter's light.
 * Level-of-detail rendering is off for this representation (its decimated geometry would
 * need its own links).
 */
#ifndef vtkGlobalIlluminationRepresentation_h
#define vtkGlobalIlluminationRepresentation_h

#include "LinkGIParaViewGlobalIlluminationModule.h" // for export macro
#include "vtkGeometryRepresentationWithFaces.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkGlobalIlluminationFilter;
class vtkGlobalIlluminationShading;
class vtkPVRenderView;
class vtkRenderer;
class vtkSMProxy;

class LINKGIPARAVIEWGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkGlobalIlluminationRepresentation* New();
  vtkTypeMacro(vtkGlobalIlluminationRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  /// Always suppressed: see the class description.
  void SetSuppressLOD(bool) override;

  ///@{
  /**
   * Forwarded to the filter: rays per vertex, bounces, smoothing, sky colour and the
   * factor on every light's intensity (also given to the mapper).
   */
  void SetRaysPerVertex(int rays);
  void SetNumberOfBounces(int bounces);
  /// vtkGlobalIlluminationFilter::SetMethod: a linkgi::Method value.
  void SetMethod(int method);
  void SetSmoothing(int smoothing);
  void SetEnvironmentColor(double r, double g, double b);
  void SetLightIntensityScale(double scale);
  ///@}

  ///@{
  /**
   * How the view's point and spot lights fall off (vtkGlobalIlluminationLights::Falloffs):
   * 0 as the lights say (ParaView's lights: not at all, as in Surface), 1 with 1/r^2
   * (lamps). Given to the filter's copies of the lights and to the mapper. The default
   * value is 0.
   */
  void SetLightFalloff(int falloff);
  int GetLightFalloff() { return this->LightFalloff; }
  ///@}

  ///@{
  /**
   * Forwarded to the mapper's vtkGlobalIlluminationShading: display mode (0 combined,
   * 1 direct, 2 indirect), exposure, tone mapping (vtkGlobalIlluminationShading's
   * ToneMappingTypes) and shadows.
   */
  void SetDisplayMode(int mode);
  void SetExposure(double exposure);
  void SetToneMapping(int toneMapping);
  void SetShadows(int shadows);
  ///@}

  ///@{
  /**
   * Bounce the light kit's key light too. The default value is on.
   */
  void SetUseKeyLight(bool use);
  bool GetUseKeyLight() { return this->UseKeyLight; }
  ///@}

  ///@{
  /**
   * Indirect light of each new solution blended with the previous one, as
   * factor * new + (1 - factor) * previous (the filter's TemporalBlend): damps flicker of
   * the indirect light while lights or the camera move. 1 shows each solution as it is. The
   * default value is 1.
   */
  void SetTemporalBlend(double factor);
  double GetTemporalBlend();
  ///@}

  ///@{
  /**
   * Progressive solutions (the filter's Progressive): where a solution would take long, a
   * coarse one of the same light is drawn first, within about half a second of work, and
   * the final one replaces it; the first-stage seconds are the filter's
   * ProgressiveFirstStageSeconds. The defaults are on and 0.5 s.
   */
  void SetProgressive(bool progressive);
  bool GetProgressive();
  void SetFirstStageSeconds(double seconds);
  double GetFirstStageSeconds();
  ///@}

  ///@{
  /**
   * The filter's MemoryBudget (MiB; 0: what the machine has) and ProxyVertices (0: the
   * surface as given, or, when the budget refuses it, a proxy the budget chooses). A surface
   * beyond the budget is lit through a proxy in the background like any other.
   */
  void SetMemoryBudget(double mebibytes);
  void SetProxyVertices(int vertices);
  ///@}

  /// When renders wait for the pending solution.
  enum WaitModes
  {
    WAIT_NEVER = 0,    ///< never: draw the newest finished solution (animations)
    WAIT_ALWAYS = 1,   ///< always: every render shows the solution of its own scene
    WAIT_AUTOMATIC = 2 ///< in scripts (pvbatch, pvpython), never in the GUI
  };

  ///@{
  /**
   * When a render waits for the pending solution, a WaitModes value. The default value is
   * WAIT_AUTOMATIC.
   */
  vtkSetClampMacro(WaitForSolution, int, WAIT_NEVER, WAIT_AUTOMATIC);
  vtkGetMacro(WaitForSolution, int);
  ///@}

  ///@{
  /**
   * Set by the GUI's client on the servers in client-server mode (the servers cannot tell
   * who their client is): renders there are interactive, WAIT_AUTOMATIC does not wait. Not
   * saved in state files. The default value is off.
   */
  vtkSetMacro(InteractiveClient, bool);
  vtkGetMacro(InteractiveClient, bool);
  ///@}

  /// Whether renders wait now (WaitForSolution resolved for this process).
  bool GetWaits();

  /// What the background worker is doing, as GetAsynchronousState reports it.
  enum AsynchronousStates
  {
    IDLE = 0,    ///< nothing requested, or the newest solution is drawn
    SOLVING = 1, ///< a request is waiting or being solved
    READY = 2    ///< a solution newer than the drawn one is ready: render to show it
  };

  /**
   * An AsynchronousStates value; while SOLVING, also reports the worker's progress through
   * this representation (what ParaView's progress bar shows). Polled by the GUI's client.
   * On the client of a remote server it is that of every process that may render (the
   * server's, where it renders remotely, the client's, where it renders locally),
   * gathered with vtkPVGlobalIlluminationStateInformation.
   */
  int GetAsynchronousState();

  /// The state of this process's own filter (GetAsynchronousState elsewhere than a client).
  int GetLocalAsynchronousState();

  ///@{
  /**
   * What the last update did, for tests and the curious: the filter's counters (its
   * lifetime numbers of link builds, light-link builds and bounce runs), the number of
   * solutions drawn, the lights it used, and the mean of the indirect irradiance over the
   * points and channels. The requests to the worker: the newest one's id, the drawn
   * solution's and the id being solved (0 while idle).
   */
  int GetLinkBuilds();
  int GetLightLinkBuilds();
  int GetBounceRuns();
  int GetNumberOfUpdates() { return this->NumberOfUpdates; }
  int GetNumberOfLights();
  double GetMeanIndirectIrradiance();
  /// The elements the drawn solution solved (LinkGI.Elements): the surface's, or fewer when
  /// it was lit through a proxy.
  int GetSolvedElements();
  int GetNewestRequest();
  int GetShownRequest();
  int GetSolvingRequest();
  /// Which progressive stage of the drawn request is drawn, of how many (1 of 1: final).
  int GetShownStage();
  int GetShownStages();
  /// The error of the newest background update that failed (empty if none).
  const char* GetLastError();
  ///@}

  /// How many times the mapper rendered its shadow maps (for tests of the shadow cache).
  int GetShadowMapRenders();

  ///@{
  /**
   * In a parallel run: the other processes' triangles that this process draws into its
   * shadow maps, and how many times the processes exchanged them (once per change of
   * anyone's geometry, see vtkGlobalIlluminationGlobalCasters).
   */
  int GetGlobalCasterTriangles();
  int GetGlobalCasterGathers();
  ///@}

  /// In a parallel run, the bytes of the other processes' partitions that the filter
  /// received at its last exchange (its LinkGI.PartitionBytesReceived; 0 on one process).
  double GetPartitionBytesReceived();

  /**
   * The most triangles of other processes drawn into the shadow maps
   * (vtkGlobalIlluminationGlobalCasters::SetMaximumTriangles); above it the processes
   * exchange decimated proxies, with a warning (at 0 nothing).
   */
  void SetMaximumGlobalCasterTriangles(int triangles);

  /// The internal filter, for C++ callers.
  vtkGlobalIlluminationFilter* GetFilter();

protected:
  vtkGlobalIlluminationRepresentation();
  ~vtkGlobalIlluminationRepresentation() override;

  /**
   * Runs the filter on the delivered data with the renderer's lights if anything changed;
   * returns what the mapper draws (the filter's output, or the delivered data when there is
   * nothing to solve).
   */
  vtkDataObject* UpdateGlobalIllumination(vtkDataObject* delivered, vtkRenderer* renderer);

  /// Copies the renderer's lights that are bounced into the filter's own world-space lights.
  void GatherLights(vtkRenderer* renderer);

  /// Blocks until the pending solution is drawn, reporting the worker's progress.
  void WaitForSolutionNow();

  /// Where this process renders interactively without waiting: polls for new solutions.
  void WatchForSolutions(vtkPVRenderView* view);

  /// One poll of the watcher: a vtkGlobalIlluminationAsyncWatcher::PollResult.
  int PollForSolution();

  /// On the GUI's client, once, at the first poll: sets InteractiveClient on every process
  /// (so that a remote server's renders do not wait for the solution either). Not sooner:
  /// a property pushed during a view update breaks the client-server protocol (the update
  /// may run inside an information request).
  void TellServersTheClientIsInteractive();

  /// The display (representation) proxy of this object where this process has a proxy
  /// manager (a client, or a builtin session), else null; found once.
  vtkSMProxy* GetDisplayProxy();

  /// The filter's warning events.
  void OnFilterEvent(vtkObject* caller, unsigned long event, void* data);

  bool UseKeyLight = true;
  int LightFalloff = 0;
  int NumberOfUpdates = 0;
  int WaitForSolution = WAIT_AUTOMATIC;
  bool InteractiveClient = false;

private:
  vtkGlobalIlluminationRepresentation(const vtkGlobalIlluminationRepresentation&) = delete;
  void operator=(const vtkGlobalIlluminationRepresentation&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  std::string LastError; // what GetLastError() returned
};

#endif
