#pragma once
// rtiow accuracy as the library runs it: the error of renders against a cached high-spp
// reference, swept over spp, samplers, adaptive targets, depth, intersector and Fresnel model;
// tables on stdout, accuracy.json, accuracy.csv and accuracy.png.

#include "core/measure/accuracy_options.h"

namespace rtiow {

// Measures and reports (its options checked by the caller, before minutes of rendering); the
// exit status.
int run_accuracy(const AccuracyOptions& o);

}  // namespace rtiow
