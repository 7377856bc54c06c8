/**
 * @class   vtkGlobalIlluminationAsyncWatcher
 * @brief   re-renders an interactor's window when an asynchronous vtkGlobalIlluminationFilter
 *          has a newer result
 *
 * In asynchronous mode the filter returns at once with the newest finished solution, and a
 * newer one arrives later, from a background thread, without anything asking for a render.
 * This helper closes the loop in an interactive application: Watch() adds a repeating
 * timer to the interactor, and on each of its ticks Poll() asks the filter
 * (vtkGlobalIlluminationFilter::PollAsynchronousResult) and, when a newer result is ready,
 * renders the interactor's window, which re-executes the filter with that result.
 *
 * @code
 * vtkNew<vtkGlobalIlluminationAsyncWatcher> watcher; // keep it alive while watching
 * watcher->SetFilter(gi);                            // gi->SetAsynchronous(true)
 * watcher->SetInterval(20);                          // milliseconds
 * watcher->Watch(interactor);                        // before interactor->Start()
 * @endcode
 *
 * The watcher holds the filter and a weak reference to the interactor; Stop() and the
 * destructor remove the timer and the observer. Other timers of the interactor are left
 * alone (their ticks are not polls).
 *
 * Where the filter is out of reach (ParaView, whose filter may run on a server), a poll
 * function says what to do on each tick instead: RENDER, WAIT (poll again) or STOP (stop
 * watching until the next Watch()).
 */
#ifndef vtkGlobalIlluminationAsyncWatcher_h
#define vtkGlobalIlluminationAsyncWatcher_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer
#include "vtkWeakPointer.h"  // for vtkWeakPointer

#include <functional> // for std::function

class vtkCallbackCommand;
class vtkGlobalIlluminationFilter;
class vtkRenderWindowInteractor;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationAsyncWatcher : public vtkObject
{
public:
  static vtkGlobalIlluminationAsyncWatcher* New();
  vtkTypeMacro(vtkGlobalIlluminationAsyncWatcher, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The filter whose results are watched. The default value is nullptr.
   */
  void SetFilter(vtkGlobalIlluminationFilter* filter);
  vtkGlobalIlluminationFilter* GetFilter();
  ///@}

  /// What a poll function asks for.
  enum PollResult
  {
    STOP = 0,  ///< nothing more to wait for: stop watching
    WAIT = 1,  ///< no new result yet: poll again
    RENDER = 2 ///< a new result is ready: render
  };

  /**
   * Polls with `function` (returning a PollResult) instead of the filter's
   * PollAsynchronousResult; an empty function goes back to the filter. Not wrapped.
   */
#ifndef __VTK_WRAP__
  void SetPollFunction(std::function<int()> function);
#endif

  ///@{
  /**
   * Milliseconds between polls; takes effect at the next Watch(). The default value is 30.
   */
  vtkSetClampMacro(Interval, int, 1, VTK_INT_MAX);
  vtkGetMacro(Interval, int);
  ///@}

  /**
   * Starts polling on a repeating timer of `interactor` (stopping any earlier watch). The
   * interactor must be initialized before its timers fire (Initialize() or Start()).
   */
  void Watch(vtkRenderWindowInteractor* interactor);

  /// Removes the timer and the observer; does nothing when not watching.
  void Stop();

  /// The interactor being watched, or nullptr.
  vtkRenderWindowInteractor* GetInteractor();

  /// The id of the interactor timer that polls (its TimerEvent's call data), -1 when not
  /// watching.
  vtkGetMacro(TimerId, int);

  /**
   * One poll: if the filter (or the poll function) has a result newer than the one drawn,
   * renders the interactor's window and returns true; stops watching when the poll function
   * says STOP. The timer calls it; tests may too.
   */
  bool Poll();

  /// How many times Poll() rendered (for tests and the curious).
  vtkGetMacro(NumberOfRenders, int);

protected:
  vtkGlobalIlluminationAsyncWatcher();
  ~vtkGlobalIlluminationAsyncWatcher() override;

  int Interval = 30;
  int NumberOfRenders = 0;

private:
  vtkGlobalIlluminationAsyncWatcher(const vtkGlobalIlluminationAsyncWatcher&) = delete;
  void operator=(const vtkGlobalIlluminationAsyncWatcher&) = delete;

  static void OnTimer(vtkObject* caller, unsigned long event, void* self, void* callData);

  vtkSmartPointer<vtkGlobalIlluminationFilter> Filter;
#ifndef __VTK_WRAP__
  std::function<int()> PollFunction;
#endif
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  vtkSmartPointer<vtkCallbackCommand> Command;
  unsigned long ObserverTag = 0;
  int TimerId = -1;
};

#endif
