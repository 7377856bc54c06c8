#pragma once

#include <stdexcept>
#include <string>

namespace linkgi
{
/// Every engine error: the message is a sentence a user can act on.
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Thrown when the caller's progress callback asks to stop.
class Aborted : public Error
{
public:
  Aborted() : Error("The update was aborted; the previous result is kept.") {}
};
}
