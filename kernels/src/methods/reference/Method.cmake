# The reference path tracer: per-vertex Monte Carlo ground truth.
linkgi_method(SOURCES Reference.cpp)
