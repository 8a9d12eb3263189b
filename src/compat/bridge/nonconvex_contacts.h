// Deprecated include path of graspcd 0.1, kept for one release (removed in 0.3): include
// <graspcd/mujoco/nonconvex_contacts.h> instead.
#pragma once

#include "graspcd/mujoco/nonconvex_contacts.h"
