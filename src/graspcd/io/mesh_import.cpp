#include "graspcd/io/mesh_import.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcntl.h>
#include <link.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "graspcd/io/input_error.h"
#include "graspcd/io/output_files.h"

namespace graspcd::io {

namespace {

ImportedMesh import_in_process(const std::string& path, const std::string& format) {
  ImportedMesh out;
  Assimp::Importer importer;
  // The file's own axes: COLLADA's up_axis is not turned to Y-up (the user's --up says which axis
  // is up). Assimp scales COLLADA by its <unit meter> (to metres) whatever is set.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const auto failed = [&] {
    out.error = one_line(importer.GetErrorString());
    if (out.error.find("bad_alloc") != std::string::npos) {
      out.error = "the import library (Assimp) ran out of memory reading it";
    }
    if (out.error.empty()) out.error = "Assimp cannot read it";
    return out;
  };
  // The file as its reader makes it, each mesh's faces counted; then the post-processing.
  // Points and lines are kept (aiProcess_SortByPType is not run) so that they can be refused.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr) return failed();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    out.read_faces.push_back(scene->mMeshes[m] != nullptr ? scene->mMeshes[m]->mNumFaces : 0);
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices);
  if (scene == nullptr) return failed();
  (void)format;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (mesh == nullptr) continue;
    out.parts.emplace_back(mesh->mName.C_Str());
    const std::size_t base = out.mesh.vertices.size();
    if (base + mesh->mNumVertices >
        static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
      out.error = "too many vertices";
      return out;
    }
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.mesh.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) {
        out.error = (face.mNumIndices < 3 ? std::to_string(face.mNumIndices) +
                                                " vertices (a point or a line; a face needs 3)"
                                          : "a polygon Assimp did not triangulate");
        out.error_mesh = m + 1;
        out.error_face = f + 1;
        return out;
      }
      std::array<std::int32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          out.error = "vertex index " + std::to_string(face.mIndices[k]) + " out of range (" +
                      std::to_string(mesh->mNumVertices) + " vertices)";
          out.error_mesh = m + 1;
          out.error_face = f + 1;
          return out;
        }
        t[k] = static_cast<std::int32_t>(base + face.mIndices[k]);
      }
      out.mesh.faces.push_back(t);
    }
  }
  return out;
}

// --- The child process's answer, through a pipe: a plain byte encoding of ImportedMesh.
void put_u64(std::string& b, std::uint64_t x) { b.append(reinterpret_cast<const char*>(&x), 8); }
void put_string(std::string& b, const std::string& s) {
  put_u64(b, s.size());
  b += s;
}

std::string encode(const ImportedMesh& m) {
  std::string b;
  put_string(b, m.error);
  put_u64(b, m.error_mesh);
  put_u64(b, m.error_face);
  put_u64(b, m.parts.size());
  for (const std::string& p : m.parts) put_string(b, p);
  put_u64(b, m.read_faces.size());
  for (const std::uint64_t n : m.read_faces) put_u64(b, n);
  put_u64(b, m.mesh.vertices.size());
  for (const Vec3& v : m.mesh.vertices) b.append(reinterpret_cast<const char*>(v.data()), 24);
  put_u64(b, m.mesh.faces.size());
  for (const auto& f : m.mesh.faces) b.append(reinterpret_cast<const char*>(f.data()), 12);
  return b;
}

struct Reader {
  const std::string& b;
  std::size_t at = 0;
  bool ok = true;
  bool take(void* to, std::size_t n) {
    if (!ok || n > b.size() - at) return ok = false;
    std::memcpy(to, b.data() + at, n);
    at += n;
    return true;
  }
  std::uint64_t u64() {
    std::uint64_t x = 0;
    take(&x, 8);
    return x;
  }
  std::string str() {
    const std::uint64_t n = u64();
    if (!ok || n > b.size() - at) {
      ok = false;
      return {};
    }
    std::string s = b.substr(at, n);
    at += n;
    return s;
  }
};

bool decode(const std::string& b, ImportedMesh& m) {
  Reader r{b};
  m.error = r.str();
  m.error_mesh = r.u64();
  m.error_face = r.u64();
  const std::uint64_t parts = r.u64();
  for (std::uint64_t i = 0; r.ok && i < parts; ++i) m.parts.push_back(r.str());
  const std::uint64_t meshes = r.u64();
  for (std::uint64_t i = 0; r.ok && i < meshes; ++i) m.read_faces.push_back(r.u64());
  const std::uint64_t nv = r.u64();
  if (!r.ok || nv > (b.size() - r.at) / 24) return false;
  m.mesh.vertices.resize(nv);
  for (Vec3& v : m.mesh.vertices) r.take(v.data(), 24);
  const std::uint64_t nf = r.u64();
  if (!r.ok || nf > (b.size() - r.at) / 12) return false;
  m.mesh.faces.resize(nf);
  for (auto& f : m.mesh.faces) r.take(f.data(), 12);
  return r.ok && r.at == b.size();
}

// The reader is this program run again (/proc/self/exe) with kReaderFd, kReaderFile and
// kReaderFormat in its environment: mesh_reader_entry, a constructor of this file, sees them
// before main, reads the file, writes encode()'s bytes to the descriptor and ends. graspcd forks
// while other threads run (the progress line's, a study's workers), and a forked child may only
// make async-signal-safe calls until it execs: a child that ran Assimp itself could block for
// ever on a lock another thread held at the fork (the sanitizer's allocator did).
constexpr const char* kReaderFd = "GRASPCD_MESH_READER_FD";
constexpr const char* kReaderFile = "GRASPCD_MESH_READER_FILE";
constexpr const char* kReaderFormat = "GRASPCD_MESH_READER_FORMAT";
// The reader's exit status when it could not be started (exec failed).
constexpr int kReaderNotStarted = 127;

// The reader's address space is limited (setrlimit RLIMIT_AS) to kImportMemoryBase plus
// kImportMemoryPerByte times the file's size, so that a file on which Assimp allocates without end
// (the fuzzer found a COLLADA file taking more than 3 GB) fails in the reader with bad_alloc rather
// than exhaust the machine. Not under AddressSanitizer, whose shadow memory the limit would deny.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GRASPCD_IMPORT_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define GRASPCD_IMPORT_ASAN 1
#endif

// The limit for `path`, 0 for none.
std::uint64_t memory_limit(const std::string& path) {
#ifndef GRASPCD_IMPORT_ASAN
  constexpr std::uint64_t kImportMemoryBase = std::uint64_t{4} << 30;
  constexpr std::uint64_t kImportMemoryPerByte = 64;
  struct stat info {};
  const std::uint64_t size =
      ::stat(path.c_str(), &info) == 0 ? static_cast<std::uint64_t>(info.st_size) : 0;
  return kImportMemoryBase + kImportMemoryPerByte * size;
#else
  (void)path;
  return 0;
#endif
}

// Reads `path` and writes encode()'s bytes to `fd`, then ends the process (exit 0; 3 when the
// answer could not be written).
[[noreturn]] void answer(int fd, const std::string& path, const std::string& format) {
  std::string bytes;
  try {
    bytes = encode(import_in_process(path, format));
  } catch (const std::bad_alloc&) {
    ImportedMesh failed;
    failed.error = "the import library (Assimp) ran out of memory reading it";
    bytes = encode(failed);
  } catch (const std::exception& e) {
    ImportedMesh failed;
    failed.error = one_line(e.what());
    bytes = encode(failed);
  }
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    done += static_cast<std::size_t>(n);
  }
  ::_exit(0);
}

// In the reader's process, before main: when the environment names a file to read, it is read,
// the answer written to the descriptor, and the process ends.
__attribute__((constructor)) void mesh_reader_entry() {
  const char* fd_text = std::getenv(kReaderFd);
  const char* path = std::getenv(kReaderFile);
  const char* format = std::getenv(kReaderFormat);
  if (fd_text == nullptr || path == nullptr || format == nullptr) return;
  char* end = nullptr;
  const long fd = std::strtol(fd_text, &end, 10);
  if (end == fd_text || *end != '\0' || fd < 3 || fd > 1 << 20 ||
      fcntl(static_cast<int>(fd), F_GETFD) < 0) {
    return;  // not a reader started by import_in_child
  }
  answer(static_cast<int>(fd), path, format);
}

// Whether mesh_reader_entry is code of the program's executable, so that the program run again
// is a reader; not when graspcd is linked into a shared library that another program loaded
// (a plugin, a Python module): that program, run again, would be itself. dl_iterate_phdr visits
// the executable first.
bool reader_in_executable() {
  static const bool yes = [] {
    struct Probe {
      std::uintptr_t address;
      bool found;
    } probe{reinterpret_cast<std::uintptr_t>(&mesh_reader_entry), false};
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* data) {
          auto* p = static_cast<Probe*>(data);
          for (int i = 0; i < info->dlpi_phnum; ++i) {
            const ElfW(Phdr)& h = info->dlpi_phdr[i];
            const std::uintptr_t start = info->dlpi_addr + h.p_vaddr;
            if (h.p_type == PT_LOAD && p->address >= start && p->address - start < h.p_memsz) {
              p->found = true;
            }
          }
          return 1;  // the executable only
        },
        &probe);
    return probe.found;
  }();
  return yes;
}

ImportedMesh import_in_child(const std::string& path, const std::string& format,
                             double timeout_seconds) {
  ImportedMesh out;
  // Everything the child needs is made here: after the fork it only calls fcntl, setrlimit, dup2
  // and execve. Its stdin, stdout and stderr go nowhere (Assimp's own messages, an ai_assert's, its
  // logger's, would add lines to the one error line).
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    out.error = std::string("cannot start the reader: ") + std::strerror(errno);
    return out;
  }
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  const bool self_reader = reader_in_executable();
  std::vector<std::string> own = {std::string(kReaderFd) + "=" + std::to_string(fds[1]),
                                  std::string(kReaderFile) + "=" + path,
                                  std::string(kReaderFormat) + "=" + format};
  std::vector<char*> env;
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::strncmp(*e, "GRASPCD_MESH_READER_", 20) != 0) env.push_back(*e);
  }
  for (std::string& s : own) env.push_back(s.data());
  env.push_back(nullptr);
  char program[] = "graspcd-mesh-reader";
  char* argv[] = {program, nullptr};
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(memory_limit(path));
  // A child tied to the run (output_files.h): killed with graspcd, never left looping.
  ChildProcess process;
  const pid_t child = process.pid();
  if (child < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    if (null >= 0) ::close(null);
    out.error = std::string("cannot start the reader: ") + std::strerror(error);
    return out;
  }
  if (child == 0) {
    ::fcntl(fds[1], F_SETFD, 0);
    if (limit.rlim_cur > 0) ::setrlimit(RLIMIT_AS, &limit);
    if (null >= 0) {
      ::dup2(null, 0);
      ::dup2(null, 1);
      ::dup2(null, 2);
    }
    if (self_reader) {
      ::execve("/proc/self/exe", argv, env.data());
      ::_exit(kReaderNotStarted);
    }
    // graspcd in a shared library: the forked child reads, safe only while no other thread of
    // the program holds a lock Assimp needs (mesh_import.h).
    answer(fds[1], path, format);
  }
  ::close(fds[1]);
  if (null >= 0) ::close(null);
  std::string bytes;
  char buffer[1 << 16];
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<long>(timeout_seconds * 1000));
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long>(left, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) process.kill();
  int status = 0;
  process.wait(&status, true);
  if (timed_out) {
    out.error = "the import library did not finish reading it in " +
                std::to_string(static_cast<long>(timeout_seconds)) + " s";
  } else if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    out.error = "the import library (Assimp) crashed reading it (signal " + std::to_string(sig) +
                (name ? std::string(", ") + name : std::string()) + ")";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kReaderNotStarted) {
    out = ImportedMesh{};
    out.error = "cannot start the reader (this program again, as /proc/self/exe)";
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !decode(bytes, out)) {
    out = ImportedMesh{};
    out.error = "the import library (Assimp) failed reading it (exit status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
  }
  return out;
}

std::atomic<double> g_import_timeout{kImportTimeout};

}  // namespace

void set_import_timeout(double seconds) { g_import_timeout = seconds; }
double import_timeout() { return g_import_timeout; }

ImportedMesh import_with_assimp(const std::string& path, const std::string& format, bool isolated,
                                double timeout_seconds) {
  if (!isolated) return import_in_process(path, format);
  if (timeout_seconds < 0) timeout_seconds = import_timeout();
  return import_in_child(path, format, timeout_seconds);
}

}  // namespace graspcd::io
