#include "graspcd/grasp/object_run.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "graspcd/grasp/hand_wrapper.h"
#include "graspcd/io/input_error.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

// The files a kept scene leaves in DIR.
struct SceneTargets {
  fs::path dir;
  std::string stem;
  fs::path scene() const { return dir / (stem + ".xml"); }
  fs::path pairs() const { return dir / (stem + ".pairs.json"); }
  fs::path meshes() const { return dir / (stem + ".meshes"); }
};

// Whether `scene` is a scene graspcd generated: its header carries kGeneratedMarker.
bool generated_by_graspcd(const fs::path& scene) {
  std::ifstream in(scene, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find(kGeneratedMarker) != std::string::npos;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

// Before the work: the targets replace no file the run reads and, without `force`, none graspcd
// did not write.
void check_scene_targets(const SceneTargets& t, const HandTemplate& hand,
                         const std::string& object_file, bool force) {
  std::error_code ec;
  const bool ours = generated_by_graspcd(t.scene());
  for (const fs::path& target : {t.scene(), t.pairs(), t.meshes()}) {
    if (same_file(target, hand.scene) || same_file(target, hand.pairs()) ||
        same_file(target, hand.drive)) {
      throw io::InputError(target.string(), 0,
                           "is the template this run reads: not overwritten (write the scene "
                           "into another folder)");
    }
    const fs::path object = fs::absolute(object_file).lexically_normal();
    const fs::path folder = fs::absolute(target).lexically_normal();
    if (same_file(target, object_file) || object.string().rfind(folder.string() + "/", 0) == 0) {
      throw io::InputError(target.string(), 0,
                           "holds the object this run reads: not overwritten (write the scene "
                           "into another folder)");
    }
    if (!force && fs::exists(fs::symlink_status(target, ec)) && !ours) {
      throw io::InputError(
          target.string(), 0,
          "exists and graspcd did not write it (no '" + std::string(kGeneratedMarker) + "' in " +
              t.scene().filename().string() + "): not overwritten; --force replaces it");
    }
  }
}

// The written files renamed from the private folder `work` into place, replacing graspcd's
// earlier ones (moved into `work`, removed with it), DIR locked meanwhile.
void keep_scene(const SceneTargets& t, const fs::path& work) {
  const int lock = ::open(t.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock >= 0) ::flock(lock, LOCK_EX);
  const auto move = [&](const std::string& name, const std::string& old) {
    const fs::path target = t.dir / name;
    std::error_code ec;
    if (fs::exists(fs::symlink_status(target, ec))) fs::rename(target, work / old, ec);
    fs::rename(work / name, target, ec);
    if (ec) {
      if (lock >= 0) ::close(lock);
      throw io::InputError(target.string(), 0, "cannot write: " + ec.message());
    }
  };
  move(t.meshes().filename().string(), "replaced.meshes");
  move(t.pairs().filename().string(), "replaced.pairs.json");
  move(t.scene().filename().string(), "replaced.xml");
  if (lock >= 0) ::close(lock);
}

SceneTargets targets_of(const ObjectRunOptions& o) {
  return {o.write_scene, fs::path(o.file).stem().string()};
}

}  // namespace

ObjectRun::ObjectRun(const ObjectRunOptions& options) : options_(options) {
  const std::string& dir = options.write_scene;
  if (dir.empty()) {
    const fs::path temporary = io::temporary_folder();
    folder_ = io::make_private_folder(temporary, "graspcd-object", temporary.string());
  } else {
    if (io::prepare_output_folder(dir)) created_.emplace(dir);
    check_scene_targets(targets_of(options), options.hand, options.file, options.force);
    folder_ = io::make_private_folder(dir, ".graspcd-" + targets_of(options).stem, dir);
  }
  description_.file = options.file;
  description_.hand = options.hand.name;
}

const ObjectScene& ObjectRun::write(const ObjectPlacement& placement) {
  const CostTimer timer(&cost_, CostPart::kScene);
  // A hand file with a drive: its template written first, in the run's folder (removed with it).
  const HandTemplate hand =
      options_.hand.drive.empty()
          ? options_.hand
          : write_hand_wrapper(options_.hand, (folder_.path() / "wrapped_hand").string());
  description_.scene = write_object_scene(placement, hand, folder_.path().string());
  // A kept scene's pair config is the user's file from now on: messages name it there.
  if (!options_.write_scene.empty()) {
    for (auto& [written, known] : description_.scene.names.files) {
      if (written == description_.scene.pairs) known = targets_of(options_).pairs().string();
    }
  }
  return description_.scene;
}

std::string ObjectRun::wait_notice() const {
  const std::size_t faces = description_.scene.faces;
  if (faces < kLargeObjectFaces) return "";
  std::ostringstream out;
  out << description_.file << ": " << faces
      << " triangles: MuJoCo compiles a mesh this large slowly (about 20 s of CPU at 200,000 "
         "triangles, more on a loaded machine), and the grasp starts after it";
  if (options_.load_timeout > 0) {
    out << "; stopped if it has not started in " << options_.load_timeout << " s (--load-timeout)";
  }
  return out.str();
}

GraspResult ObjectRun::grasp(GraspOptions options) {
  options.names = names();
  // MuJoCo's compiler cannot be stopped from inside: a deadline ends the run, as an error does,
  // unless the first closing step comes first.
  std::optional<io::Deadline> deadline;
  if (options_.load_timeout > 0) {
    std::ostringstream message;
    message << description_.file << ": the grasp did not start within " << options_.load_timeout
            << " s (MuJoCo compiling the scene with the object's " << description_.scene.faces
            << " triangles, then graspcd's trees and the start check): --load-timeout raises "
               "the limit, a coarser mesh shortens the wait";
    deadline.emplace(options_.load_timeout, message.str());
    options.on_grasp_step = [&deadline, step = std::move(options.on_grasp_step)](
                                const mjModel* m, const mjData* d, int k) {
      if (deadline) deadline->cancel();
      if (step) step(m, d, k);
    };
  }
  GraspResult result;
  try {
    result = run_grasp(scene(), options);
  } catch (const io::InputError&) {
    keep();  // a refused scene is kept too, so that it can be edited
    throw;
  }
  keep();
  result.scene = description_.kept ? description_.scene.scene : description_.file;
  result.cost += cost_;
  return result;
}

void ObjectRun::keep() {
  if (options_.write_scene.empty() || description_.kept) return;
  const SceneTargets t = targets_of(options_);
  keep_scene(t, folder_.path());
  description_.kept = true;
  description_.scene.scene = t.scene().string();
  description_.scene.pairs = t.pairs().string();
  description_.scene.meshes = t.meshes().string();
}

}  // namespace graspcd::grasp
