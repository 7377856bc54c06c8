#pragma once

#include <cstdint>
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

/// Thrown on the processes of a partitioned update (Partition) when another of them failed:
/// they leave the update together, each keeping its previous result.
class PeerFailed : public Error
{
public:
  explicit PeerFailed(std::uint64_t failures)
    : Error("This update failed on " + std::to_string(failures) + " of the other processes that share the "
        "surface (the error is in " + (failures == 1 ? "its" : "their") + " output); the previous result is kept.")
    , failures(failures)
  {
  }
  const std::uint64_t failures;
};
}
