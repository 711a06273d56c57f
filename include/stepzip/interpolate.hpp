// stepzip — every forward interpolator (vectors -> steps), one header per family.
#pragma once

#include "stepzip/interpolate/linear.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/carrier.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/interpolate/dda.hpp"
#include "stepzip/interpolate/feedrate.hpp"
#include "stepzip/interpolate/prediction.hpp"
#include "stepzip/interpolate/recursion.hpp"
#include "stepzip/interpolate/segment.hpp"
