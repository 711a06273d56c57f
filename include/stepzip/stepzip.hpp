// stepzip — lossless compression of unit-step chains by reverse interpolation.
// Umbrella header: includes the whole public C++ API.
#pragma once

#include "stepzip/chain.hpp"
#include "stepzip/container.hpp"
#include "stepzip/error.hpp"
#include "stepzip/interpolate.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"
#include "stepzip/streaming.hpp"
#include "stepzip/timed.hpp"
#include "stepzip/vectors.hpp"
#include "stepzip/version.hpp"
