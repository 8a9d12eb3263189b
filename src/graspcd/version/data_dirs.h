// Where graspcd finds the files it ships and the ones it uses by path, with no reference to the
// source tree (docs/library.md, "Using graspcd in your MuJoCo program"):
//  - the template scenes (mjcf/ and its meshes: `grasp --object --hand`, `validate --objects`, the
//    study): installed as PREFIX/share/graspcd/mjcf and found from the executable's own path;
//  - the real models of the Robotiq and Shadow templates (MuJoCo Menagerie's hands), never copied
//    or installed: found where the build was configured to find them, or where the environment
//    says.
#pragma once

#include <string>

namespace graspcd {

// The folder of the template scenes: EXE_DIR/../share/graspcd/mjcf when it exists (an installed
// executable, found from /proc/self/exe, wherever the prefix was moved), else the build tree's
// share/graspcd/mjcf (a link to the checkout's mjcf/, made at configure time; recorded then).
// Either with its links resolved (the checkout's mjcf/ for the build tree).
std::string mjcf_dir();

// The folder of the real models: $GRASPCD_MODELS_DIR when set and not empty, else the CMake cache
// variable GRASPCD_MODELS_DIR of the build (by default ../shared/models beside the checkout).
// Whether it holds anything is the caller's question.
std::string models_dir();

}  // namespace graspcd
