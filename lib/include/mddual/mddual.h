// Umbrella header of the mddual core library.
#pragma once

#include "mddual/brute_force.h"
#include "mddual/constants.h"
#include "mddual/defaults.h"
#include "mddual/distance.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/penetration.h"
#include "mddual/polytope.h"
#include "mddual/query.h"
