#include "vtkPVGlobalIlluminationStateInformation.h"

#include "vtkClientServerStream.h"
#include "vtkCompositeRepresentation.h"
#include "vtkGlobalIlluminationRepresentation.h"
#include "vtkObjectFactory.h"

#include <algorithm>

vtkStandardNewMacro(vtkPVGlobalIlluminationStateInformation);

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationStateInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "State: " << this->State << "\n";
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationStateInformation::CopyFromObject(vtkObject* object)
{
  // Gathered on the display proxy, whose object is ParaView's composite representation.
  auto* composite = vtkCompositeRepresentation::SafeDownCast(object);
  auto* representation = vtkGlobalIlluminationRepresentation::SafeDownCast(
    composite ? composite->GetActiveRepresentation() : object);
  this->State = representation ? representation->GetLocalAsynchronousState()
                               : vtkGlobalIlluminationRepresentation::IDLE;
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationStateInformation::AddInformation(vtkPVInformation* other)
{
  // The states are ordered by urgency: a new solution anywhere wants a render, a solve
  // anywhere keeps the watcher polling.
  if (auto* state = vtkPVGlobalIlluminationStateInformation::SafeDownCast(other))
  {
    this->State = std::max(this->State, state->State);
  }
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationStateInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << this->State << vtkClientServerStream::End;
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationStateInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  if (!stream->GetArgument(0, 0, &this->State))
  {
    vtkErrorMacro("The Global Illumination state is missing from the server's reply.");
    this->State = vtkGlobalIlluminationRepresentation::IDLE;
  }
}
