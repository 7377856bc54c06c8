/**
 * @class   vtkPVGlobalIlluminationStateInformation
 * @brief   the background solve's state of a Global Illumination representation, gathered
 *          from the processes that render it
 *
 * In client-server mode with remote rendering the server's representation solves and the
 * client's has no data, and ParaView pulls information properties from the client's copy
 * only. The client's vtkGlobalIlluminationRepresentation therefore gathers this from its
 * proxy on the client and every server process: each copies its own
 * vtkGlobalIlluminationRepresentation::GetLocalAsynchronousState() (of the active
 * representation, when gathered on ParaView's composite representation; this also reports the
 * worker's progress there), and the states combine to the most urgent one (READY over
 * SOLVING over IDLE).
 */
#ifndef vtkPVGlobalIlluminationStateInformation_h
#define vtkPVGlobalIlluminationStateInformation_h

#include "LinkGIParaViewGlobalIlluminationModule.h" // for export macro
#include "vtkPVInformation.h"

class LINKGIPARAVIEWGLOBALILLUMINATION_EXPORT vtkPVGlobalIlluminationStateInformation
  : public vtkPVInformation
{
public:
  static vtkPVGlobalIlluminationStateInformation* New();
  vtkTypeMacro(vtkPVGlobalIlluminationStateInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// A vtkGlobalIlluminationRepresentation::AsynchronousStates value.
  vtkGetMacro(State, int);

  /// From a vtkGlobalIlluminationRepresentation, or a vtkCompositeRepresentation whose active
  /// representation is one; anything else is IDLE.
  void CopyFromObject(vtkObject* object) override;
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;

protected:
  vtkPVGlobalIlluminationStateInformation() = default;
  ~vtkPVGlobalIlluminationStateInformation() override = default;

  int State = 0;

private:
  vtkPVGlobalIlluminationStateInformation(const vtkPVGlobalIlluminationStateInformation&) = delete;
  void operator=(const vtkPVGlobalIlluminationStateInformation&) = delete;
};

#endif
