// Installed as <graspcd/core/warnings.h>, the sink's path before 0.5: it forwards to
// <graspcd/io/warnings.h>, where the warning sink lives beside the input error.
#pragma once

#include "graspcd/io/warnings.h"
