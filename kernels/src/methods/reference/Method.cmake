# The reference path tracer: per-vertex Monte Carlo ground truth, also a method of its own.
linkgi_method(ENUM Reference VALUE 4 LABEL "Reference"
  DESCRIPTION "Monte Carlo path tracing from every vertex, the ground truth the other methods are checked against (slow: minutes where the others take seconds; Reference Paths Per Vertex sets its noise)."
  SPEC reference::referenceMethod
  SOURCES Reference.cpp ReferenceMethod.cpp)
