// stepzip — every forward interpolator (vectors -> steps), one header per family.
#pragma once

#include "stepzip/interpolate/linear.hpp"
